#pragma once
// Recording a live stream: LiveRecorder takes samples from the live buffer (a little behind
// the newest, so late packets are in place) and writes them on its own thread with a
// RecordingWriter, so the frame never waits for the disk; ContactDetector decides when a
// recording should start and stop by itself (a contact begins: a channel leaves its noise
// band; it ends after a quiet time).

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "tactile/io/disk_room.h"
#include "tactile/io/recording.h"
#include "tactile/io/recording_writer.h"
#include "tactile/live/live_source.h"

namespace tactile {

struct LiveRecorderOptions {
  double pretrigger_seconds = 5.0;  // the recording starts with this much already in the buffer
  double lag_seconds = 0.2;         // stay this far behind the newest sample (late packets)
  double flush_seconds = 1.0;
  Metadata metadata;
  // Room on the recording's disk, asked after every flush: below `warn_minutes` at the current
  // rate the recorder says so (room().low); before it runs out (a few flushes and the closing
  // are left) it stops by itself and closes a whole file (room().stopped).
  double warn_minutes = 10.0;
  std::function<int64_t(const std::string&)> room = room_to_grow;  // bytes; -1 unknown
  std::function<double()> clock;  // seconds, for the rate; empty: the steady clock
};

// The recorder's view of its disk, as of the last flush.
struct RecorderRoom {
  int64_t free_bytes = -1;        // the disk's room for the file (-1: unknown)
  double bytes_per_second = 0.0;  // the file's growth per second of the wall clock
  double minutes_left = -1.0;     // until the recorder stops by itself (-1: unknown)
  bool low = false;               // less than warn_minutes left
  std::string stopped;            // why the recorder stopped by itself ("" while it records)
};

class LiveRecorder {
 public:
  // Creates `path` (never over an existing file) and starts at the pre-trigger's first sample
  // still in `source`. Throws tactile::Error naming the file.
  LiveRecorder(const std::string& path, const LiveSampleSource& source,
               const LiveRecorderOptions& options);
  ~LiveRecorder();  // finish(), errors swallowed
  LiveRecorder(const LiveRecorder&) = delete;
  LiveRecorder& operator=(const LiveRecorder&) = delete;

  // Takes what the source holds past what was taken (up to the lag) and queues it for the
  // writer thread. Samples that left the buffer before they were taken are written as gaps.
  void take(const LiveSampleSource& source);
  // Takes everything left (no lag), writes it and closes the file. Throws tactile::Error when
  // the writer failed (what was flushed before stays in the file; `tactile repair` rebuilds the
  // rest). After a stop for room the file is already closed and whole: nothing is thrown.
  void finish(const LiveSampleSource& source);

  const std::string& path() const { return path_; }
  const std::string& recording_id() const { return recording_id_; }
  double start_time() const { return start_time_; }
  int64_t samples_taken() const { return next_ - first_; }
  int64_t samples_on_disk() const;
  std::string error() const;  // the writer's failure, "" while all is well
  RecorderRoom room() const;
  // True once the recorder stopped by itself for room (room().stopped says why).
  bool stopped() const;
  bool finished() const { return finished_; }

 private:
  void run();
  // After a flush, on the writer thread: the room left, and the clean stop when it is short.
  void check_room();

  std::string path_;
  std::string recording_id_;
  double start_time_ = 0.0;
  double lag_seconds_;
  int64_t first_ = 0;  // source index of the recording's first sample
  int64_t next_ = 0;   // next source index to take
  std::unique_ptr<RecordingWriter> writer_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<SampleMatrix> queue_;
  bool closing_ = false;
  bool finished_ = false;
  std::string error_;
  int64_t on_disk_ = 0;
  double writer_rate_ = 1.0;
  double warn_minutes_;
  std::function<int64_t(const std::string&)> room_probe_;
  RecorderRoom room_;
  std::function<double()> clock_;
  int64_t measured_bytes_ = 0;      // file size at the last flush
  double measured_seconds_ = -1.0;  // the clock then (-1: no flush yet)
  double bytes_per_flush_ = 0.0;    // the file's growth per flush, smoothed
  std::thread thread_;
};

struct ContactDetectorOptions {
  double noise_sigmas = 6.0;   // a channel beyond rest +- this many noise deviations is touched
  double learn_seconds = 2.0;  // the rest level and noise of each channel, from the first samples
  double quiet_seconds = 3.0;  // no contact for this long ends the touch
  int min_channels = 1;        // channels that must be beyond their band at once
};

// Contact from the noise band of each channel, learnt from the first seconds of a stream
// (assumed untouched: median and median absolute deviation per channel).
class ContactDetector {
 public:
  ContactDetector(int channels, double rate_hz, const ContactDetectorOptions& options = {});
  // One sample; returns the state after it.
  enum class State { kLearning, kQuiet, kContact };
  State add(std::span<const float> values);
  State state() const { return state_; }
  // The sample count since the last contact ended (for "stop after a quiet time").
  bool quiet_for_long() const;
  bool contact_began() const { return began_; }  // on the last add()

 private:
  int channels_;
  double rate_;
  ContactDetectorOptions options_;
  std::vector<std::vector<float>> learning_;  // per channel, while learning
  std::vector<float> rest_, band_;
  int64_t learnt_ = 0;
  int64_t quiet_samples_ = 0;
  State state_ = State::kLearning;
  bool began_ = false;
};

}  // namespace tactile

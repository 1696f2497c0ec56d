#pragma once
// LiveReceiver: one thread that takes datagrams from a DatagramInput, decodes them against
// the skin's layout, tracks their sequence numbers and hands each sample to the UI thread
// through a SampleRing. Nothing it receives can stop it: a broken datagram is counted and
// its error kept; a device that goes away is waited for (the input reopens it); only an
// input that fails for good ends it (failure()). Samples go to the ring at the stream times
// LiveTimeline gives them (live_timeline.h), not at the sender's raw time stamps.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_input.h"
#include "tactile/live/sample_ring.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

struct LiveCounters {
  int64_t datagrams = 0;     // everything that arrived
  int64_t samples = 0;       // handed to the ring
  int64_t lost = 0;          // datagrams skipped in the sequence and still missing
  int64_t duplicated = 0;    // dropped
  int64_t reordered = 0;     // arrived after a later one
  int64_t broken = 0;        // refused by the decoder or the framing
  int64_t overflow = 0;      // samples the ring had no room for (the UI fell behind)
  int64_t restarts = 0;      // the sender's count started over
  int64_t saturated = 0;     // datagrams flagged as clamped by the device
  int64_t unplugs = 0;       // the device went away (a serial port unplugged)
  int64_t replugs = 0;       // ... and came back
  int64_t stalls = 0;        // silences longer than LiveTimeline's stall time
  int64_t clock_jumps = 0;   // the sender's time stamps jumped (placed by sequence instead)
  int64_t late_dropped = 0;  // late datagrams whose place was no longer free
  bool stalled = false;      // silent for longer than the stall time now
  std::string gone;          // while the device is away: what the input waits for; else ""
  std::string last_error;    // of the last broken datagram, "where: what"
};

class LiveReceiver {
 public:
  // Starts receiving at once. `ring_seconds` of samples at the skin's rate fit in the
  // hand-over ring (at least 4096). Throws tactile::Error when the layout has no packet format.
  LiveReceiver(std::unique_ptr<DatagramInput> input, SkinLayout layout, double ring_seconds = 2.0);
  ~LiveReceiver();  // stops the thread
  LiveReceiver(const LiveReceiver&) = delete;
  LiveReceiver& operator=(const LiveReceiver&) = delete;

  // What a LiveSampleSource fed from this receiver carries: the layout's device channels.
  const SourceInfo& source_info() const { return info_; }
  SampleRing& ring() { return *ring_; }
  LiveCounters counters() const;
  bool ended() const { return ended_.load(); }  // the input ended (a replay) or failed
  std::string failure() const;                  // why the input failed ("" when it did not)
  std::string describe() const { return description_; }
  void stop();

 private:
  void run();

  std::unique_ptr<DatagramInput> input_;
  SkinLayout layout_;
  SourceInfo info_;
  std::unique_ptr<SampleRing> ring_;
  std::string description_;
  mutable std::mutex mutex_;  // guards counters_ and failure_
  LiveCounters counters_;
  std::string failure_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> ended_{false};
  std::thread thread_;
};

}  // namespace tactile

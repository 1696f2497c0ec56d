#pragma once
// The workbench's services: what lives longer than a frame and is not data (threads,
// sockets, serial ports, files being written). The Workbench owns them, outside the
// WorkbenchState; views never reach them: a view puts a request in the state (record, stop,
// classify, clear), which the workbench carries out with its services at the next frame's
// start, and the services' news (counters, the file being recorded) is copied into the state.
// Jobs are handles in the state (jobs.h); the label store is the open document's.

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>

#include "tactile/live/live_receiver.h"
#include "tactile/live/live_recorder.h"
#include "tactile/live/online_classifier.h"
#include "tactile/video/camera.h"

namespace tactile {

// The stream's clock as the camera's thread reads it: the newest sample's time when the window
// took it in, moved on by the steady clock since; frames stamped with it lie on the recording's
// time axis.
class LiveClock {
 public:
  void set(double stream_time) {
    std::lock_guard lock(mutex_);
    stream_time_ = stream_time;
    at_ = std::chrono::steady_clock::now();
  }
  // Never earlier than a time it gave before: when samples arrive late, the newest one's time
  // lies behind the clock's estimate, and a camera frame must not be stamped before the last.
  double now() const {
    std::lock_guard lock(mutex_);
    const double estimate =
        stream_time_ +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - at_).count();
    given_ = std::max(given_, estimate);
    return given_;
  }

 private:
  mutable double given_ = -1e300;
  mutable std::mutex mutex_;
  double stream_time_ = 0.0;
  std::chrono::steady_clock::time_point at_ = std::chrono::steady_clock::now();
};

// Live mode (live.h): the receiver's thread, the recorder's file, the contact detector that
// starts a recording by itself, the online classifier, the camera beside the skin.
struct LiveServices {
  std::unique_ptr<LiveReceiver> receiver;  // null when not live
  std::unique_ptr<LiveRecorder> recorder;
  std::unique_ptr<ContactDetector> detector;
  std::unique_ptr<OnlineClassifier> online;
  std::shared_ptr<LiveClock> clock = std::make_shared<LiveClock>();
  std::unique_ptr<Camera> camera;  // --camera URL (docs/VIDEO.md, "Live camera")
};

struct WorkbenchServices {
  LiveServices live;
};

}  // namespace tactile

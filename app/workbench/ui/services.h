#pragma once
// The workbench's services: what lives longer than a frame and is not data (threads,
// sockets, serial ports, files being written). The Workbench owns them, outside the
// WorkbenchState; views never reach them: a view puts a request in the state (record, stop,
// classify, clear), which the workbench carries out with its services at the next frame's
// start, and the services' news (counters, the file being recorded) is copied into the state.
// Jobs are handles in the state (jobs.h); the label store is the open document's.

#include <memory>

#include "tactile/live/live_receiver.h"
#include "tactile/live/live_recorder.h"
#include "tactile/live/online_classifier.h"

namespace tactile {

// Live mode (live.h): the receiver's thread, the recorder's file, the contact detector that
// starts a recording by itself, the online classifier.
struct LiveServices {
  std::unique_ptr<LiveReceiver> receiver;  // null when not live
  std::unique_ptr<LiveRecorder> recorder;
  std::unique_ptr<ContactDetector> detector;
  std::unique_ptr<OnlineClassifier> online;
};

struct WorkbenchServices {
  LiveServices live;
};

}  // namespace tactile

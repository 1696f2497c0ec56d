#pragma once
// A clip of one label for a talk (`tactile clip`, View > Export clip): the headless workbench
// draws the "clip" view (the skin and the video side by side, the signals with the cursor, the
// label's lanes) at each frame time across the label and a margin, waits until each video
// shows its frame, and encodes the frames with libavcodec (VideoWriter).

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "tactile/widgets/image.h"
#include "workbench.h"

namespace tactile {

struct ClipRequest {
  int64_t label = -1;   // the label's id
  std::string out;      // CLIP.mp4
  std::string video;    // the attachment shown ("" = every one)
  double margin = 1.0;  // seconds before and after the label
  double rate = 30.0;   // frames per second of the clip
};

class VideoWriter;

class ClipRecorder {
 public:
  explicit ClipRecorder(ClipRequest request);
  ~ClipRecorder();
  // Before a frame: on the first, finds the label and sets up the view; then puts the cursor
  // at the clip's next frame time. Returns the seconds the workbench's clock advances (none).
  double before_frame(Workbench& workbench);
  // After a frame is drawn: writes it once every video shows its frame, and moves on.
  void after_frame(Workbench& workbench, const std::function<const Image&()>& image);
  bool done() const { return done_; }
  const std::string& error() const { return error_; }
  int64_t frames_written() const { return written_; }

 private:
  ClipRequest request_;
  std::unique_ptr<VideoWriter> writer_;
  double start_ = 0.0, end_ = 0.0;
  int64_t written_ = 0;
  int waited_ = 0;  // frames drawn waiting for the videos at this time
  bool started_ = false, done_ = false;
  std::string error_;
};

}  // namespace tactile

#pragma once
// A live camera read through libavdevice (V4L2 on Linux; FFmpeg's lavfi test sources stand in
// for a device in tests): frames stamped on the live clock as they arrive, kept for a
// pre-trigger span, and written to a video file beside the recording while it records, so the
// video's attachment offset is exact.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "tactile/video/video_file.h"

namespace tactile {

struct CameraOptions {
  // "v4l2:/dev/video0", "lavfi:testsrc2=size=320x240:rate=30" (FFmpeg's device name, a colon,
  // its input). Throws at open when the device cannot be opened, naming it.
  std::string url;
  int max_width = 640;     // frames shown and recorded at most this wide
  double pre_trigger = 5;  // seconds of frames kept before recording starts
};

class Camera {
 public:
  // `clock()` gives the live clock's now (seconds): each frame is stamped with it on arrival.
  Camera(CameraOptions options, std::function<double()> clock);
  ~Camera();  // stops the reading thread and finishes a recording
  Camera(const Camera&) = delete;
  Camera& operator=(const Camera&) = delete;

  // The newest frame (time: its live-clock stamp), or null before the first: shared, so a
  // window asking every frame copies no pixels.
  std::shared_ptr<const VideoFrame> latest() const;
  // Frames received and dropped (the reader fell behind) so far.
  int64_t frames_received() const;
  // Starts writing to `path` with the pre-trigger frames first; returns the live-clock time of
  // the first frame written (the attachment's offset relative to the recording's start).
  double start_recording(const std::string& path);
  void stop_recording();
  // An error that stopped the camera ("" while it runs).
  std::string error() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile

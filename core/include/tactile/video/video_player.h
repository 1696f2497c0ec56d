#pragma once
// A video shown beside a recording: a worker thread owns the VideoFile, opens it (indexing
// takes a moment on a long file) and decodes the frame the window asks for, so the window's
// frame never waits for a decoder. While playing it decodes the next frame ahead, which is
// shown the moment the time reaches it.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tactile/video/video_file.h"

namespace tactile {

class VideoPlayer {
 public:
  // Starts the worker, which opens `path`; problem() says why when it cannot.
  VideoPlayer(std::string path, VideoOpenOptions options);
  ~VideoPlayer();
  VideoPlayer(const VideoPlayer&) = delete;
  VideoPlayer& operator=(const VideoPlayer&) = delete;

  // Asks for the frame shown at `video_time` (none before the first frame or past the end).
  // Cheap: the worker decodes it. `playing`: the next frame is read ahead too.
  void want(double video_time, bool playing);
  // The frame shown now (null before the first decode or when the time is outside the video).
  std::shared_ptr<const VideoFrame> shown() const;
  // The frame index last asked for (-1: outside the video), and whether shown() is it.
  int64_t wanted() const;
  bool caught_up() const;
  // The file's description and frame times, once it is open (null before, or on failure).
  std::shared_ptr<const VideoInfo> info() const;
  std::shared_ptr<const std::vector<double>> frame_times() const;
  bool opening() const;
  // Why the video cannot be shown ("" while it can): the file's or a frame's Error message.
  std::string problem() const;

 private:
  void run(std::string path, VideoOpenOptions options);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool opening_ = true;
  double want_time_ = 0.0;
  bool want_set_ = false;
  bool playing_ = false;
  int64_t wanted_ = -1;
  std::shared_ptr<const VideoFrame> shown_;
  // While playing, the frame after the shown one, decoded before it falls due: want() shows it
  // the moment the time reaches it, without waiting for the worker.
  std::shared_ptr<const VideoFrame> ahead_;
  std::shared_ptr<const VideoInfo> info_;
  std::shared_ptr<const std::vector<double>> times_;
  std::string problem_;
  std::thread worker_;
};

}  // namespace tactile

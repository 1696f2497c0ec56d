#pragma once
// Writes frames to a video file through libavcodec/libavformat: the tests' own videos, clips,
// the live camera's recording. Each frame carries its own time, so variable rates are written
// as they are.

#include <cstdint>
#include <memory>
#include <string>

namespace tactile {

struct VideoWriterOptions {
  int width = 0;  // even numbers: the encoders' 4:2:0 chroma needs them (odd ones are refused)
  int height = 0;
  // The nominal frame rate: the stream's time base is 1/(rate*100) (Matroska keeps 1 ms; AVI,
  // which has no time stamps, 1/rate: there each frame's time is rounded to a whole frame).
  // Key frames every 2 s.
  double rate = 30;
  // libavcodec encoder name; "" chooses by the file's extension: .mp4/.mov/.mkv H.264
  // (libx264) when this FFmpeg has it, else MPEG-4 part 2; .avi MJPEG; .webm VP9.
  std::string codec;
  int quality = 23;  // constant quality where the encoder has one (lower is better)
};

class VideoWriter {
 public:
  // Creates the file (the container by its extension). Throws tactile::Error naming the path.
  VideoWriter(const std::string& path, VideoWriterOptions options);
  ~VideoWriter();  // finishes the file if finish() was not called, ignoring errors
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // One RGBA frame (top row first, width*height*4 bytes) shown from `time` seconds on; times
  // increase (also once rounded to the time base). A reader places the first frame at 0,
  // whatever its time here. Throws tactile::Error naming the file (and the time).
  void write(const uint8_t* rgba, double time);
  // Flushes the encoder and writes the trailer. Throws tactile::Error naming the file.
  void finish();
  const std::string& codec() const;  // the encoder chosen

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile

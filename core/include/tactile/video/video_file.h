#pragma once
// A video file read through FFmpeg's libavformat/libavcodec/libswscale: its frames placed by
// their presentation time stamps (a variable frame rate works), the frame shown at a time
// decoded on demand (seek to the key frame before it, decode forward), and a small cache.
// One VideoFile is used by one thread at a time; a view's worker owns its own.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tactile {

// What the file holds, read when it is opened (the packets are indexed, not decoded).
struct VideoInfo {
  std::string path;
  std::string container;  // libavformat's name: "mov,mp4,m4a,3gp,3g2,mj2", "matroska,webm"
  std::string codec;      // libavcodec's name: "h264", "hevc", "vp9", "mjpeg", "mpeg4"
  int width = 0;          // as coded
  int height = 0;
  double duration = 0;         // seconds: from the first frame's time to the last frame's end
  double mean_rate = 0;        // frames per second over the whole file
  bool variable_rate = false;  // frame intervals differ by more than 1 % of their median
  int64_t frame_count = 0;
};

// A decoded frame, converted to RGBA (top row first) at the size VideoOpenOptions asks.
struct VideoFrame {
  int64_t index = -1;   // its place among the file's frames in presentation order
  double time = 0;      // seconds from the video's first frame (which is at 0)
  double duration = 0;  // until the next frame (the last: the mean interval)
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;
};

struct VideoOpenOptions {
  int max_width = 0;     // scale frames down (aspect kept) to at most this width; 0: as coded;
                         // either way rounded to even sizes
  bool grey = false;     // one byte per pixel (luma) instead of RGBA: for motion energy
  int cache_frames = 8;  // decoded frames kept (the cache holds at most this many)
};

class VideoFile {
 public:
  // Opens, probes and indexes the file. Throws tactile::Error naming the path and what is wrong:
  // missing, unreadable, not a video, no video stream, a codec this FFmpeg cannot decode, cut
  // short (no frame decodes: frame 0 is decoded here, to know).
  explicit VideoFile(const std::string& path, VideoOpenOptions options = {});
  ~VideoFile();
  VideoFile(const VideoFile&) = delete;
  VideoFile& operator=(const VideoFile&) = delete;

  const VideoInfo& info() const;
  // Every frame's time (seconds from the first frame), ascending.
  const std::vector<double>& frame_times() const;
  // The frame shown at video time `time`: the last frame whose time <= time; -1 before the
  // first frame or at/after the end (info().duration).
  int64_t frame_index_at(double time) const;
  // Decodes frame `index` (0 <= index < frame_count): reads forward from the current position
  // when it lies ahead within a few key frames, else seeks. Throws tactile::Error naming the
  // file and frame when the data there is corrupt.
  // The reference stays valid until the next call of frame().
  const VideoFrame& frame(int64_t index);

  // What the decoding has cost so far, for tests and benchmarks: the seeks frame() made (the
  // one at opening not counted), the frames the decoder gave out, the bytes the cache holds.
  int64_t seek_count() const;
  int64_t decoded_frame_count() const;
  size_t cached_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Where a video time falls relative to the file, in words for the window and the command line:
// "" inside; "before the video (it starts at 12.0 s)", "past the video's end (it ends at 95.2 s)".
std::string video_time_problem(const VideoInfo& info, double video_time, double offset);

}  // namespace tactile

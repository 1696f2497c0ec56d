#pragma once
// Small videos whose frames carry their own number, written with core's VideoWriter (never the
// ffmpeg program): the video tests, the workbench's and the clips' read a decoded frame's number
// back and so know exactly which frame they got. The number is 16 bits drawn as a 4 x 4 grid of
// large black or white blocks (bit 0 top left, row by row), which survives lossy compression and
// scaling: a block's mean over its inner half is far from the middle grey.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tactile/video/video_file.h"
#include "tactile/video/video_writer.h"

namespace tactile::test {

constexpr int kVideoNumberBits = 16;

// An RGBA image (width*height*4 bytes) showing `number`.
inline std::vector<uint8_t> numbered_image(int number, int width, int height) {
  std::vector<uint8_t> rgba(static_cast<size_t>(width) * height * 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int bit = (y * 4 / height) * 4 + x * 4 / width;
      const uint8_t value = ((number >> bit) & 1) ? 235 : 20;
      uint8_t* pixel = &rgba[(static_cast<size_t>(y) * width + x) * 4];
      pixel[0] = value;
      pixel[1] = value;
      pixel[2] = value;
      pixel[3] = 255;
    }
  return rgba;
}

// The number shown in an image of `channels` bytes per pixel (4: RGBA, 1: grey), read from the
// first channel of each block's inner half.
inline int number_in_image(const uint8_t* pixels, int width, int height, int channels) {
  int number = 0;
  for (int bit = 0; bit < kVideoNumberBits; ++bit) {
    const int row = bit / 4;
    const int column = bit % 4;
    const int x0 = column * width / 4 + width / 16;
    const int x1 = (column + 1) * width / 4 - width / 16;
    const int y0 = row * height / 4 + height / 16;
    const int y1 = (row + 1) * height / 4 - height / 16;
    long sum = 0;
    long count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        sum += pixels[(static_cast<size_t>(y) * width + x) * channels];
        ++count;
      }
    if (count > 0 && sum > 128 * count) number |= 1 << bit;
  }
  return number;
}

// The number a decoded frame shows (RGBA or grey, told by its size).
inline int number_in_frame(const VideoFrame& frame) {
  const size_t pixels = static_cast<size_t>(frame.width) * frame.height;
  if (pixels == 0) return -1;
  return number_in_image(frame.rgba.data(), frame.width, frame.height,
                         static_cast<int>(frame.rgba.size() / pixels));
}

// `count` frame times at `rate` frames per second from 0.
inline std::vector<double> constant_rate_times(int count, double rate) {
  std::vector<double> times(count);
  for (int i = 0; i < count; ++i) times[i] = i / rate;
  return times;
}

// `count` frame times from 0 whose intervals cycle through 20, 50 and 33 ms.
inline std::vector<double> variable_rate_times(int count) {
  const double intervals[] = {0.020, 0.050, 0.033};
  std::vector<double> times(count);
  for (int i = 1; i < count; ++i) times[i] = times[i - 1] + intervals[(i - 1) % 3];
  return times;
}

// Writes frame i showing the number i at times[i]; returns the encoder chosen.
inline std::string write_numbered_video(const std::string& path, const std::vector<double>& times,
                                        int width = 64, int height = 48,
                                        const std::string& codec = "", double rate = 30) {
  if (times.size() >= (size_t{1} << kVideoNumberBits))
    throw std::invalid_argument("write_numbered_video: too many frames to number");
  VideoWriterOptions options;
  options.width = width;
  options.height = height;
  options.rate = rate;
  options.codec = codec;
  VideoWriter writer(path, options);
  for (size_t i = 0; i < times.size(); ++i) {
    const std::vector<uint8_t> image = numbered_image(static_cast<int>(i), width, height);
    writer.write(image.data(), times[i]);
  }
  writer.finish();
  return writer.codec();
}

}  // namespace tactile::test

// The video's side of the offset proposal: how much the picture changes, frame to frame.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/video/video_file.h"
#include "tactile/video/video_sync.h"

namespace tactile {

namespace {

struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

PixelBox box_of(const std::optional<VideoRegion>& region, int width, int height) {
  if (!region) return {0, 0, width, height};
  auto edge = [](double fraction, int size) {
    return std::clamp(static_cast<int>(std::lround(fraction * size)), 0, size);
  };
  PixelBox box{edge(region->x, width), edge(region->y, height),
               edge(region->x + region->width, width), edge(region->y + region->height, height)};
  box.x1 = std::max(box.x1, std::min(width, box.x0 + 1));  // at least one pixel
  box.y1 = std::max(box.y1, std::min(height, box.y0 + 1));
  box.x0 = std::min(box.x0, box.x1 - 1);
  box.y0 = std::min(box.y0, box.y1 - 1);
  return box;
}

// The luma of the box's pixels, row by row: the grey frame's bytes, or (R + 2G + B) / 4 of
// an RGBA one.
void luma_of(const VideoFrame& frame, const PixelBox& box, std::vector<int>& out) {
  const size_t pixels = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
  const size_t channels = pixels == 0 ? 1 : frame.rgba.size() / pixels;
  out.clear();
  for (int y = box.y0; y < box.y1; ++y) {
    const uint8_t* row = frame.rgba.data() + static_cast<size_t>(y) * frame.width * channels;
    for (int x = box.x0; x < box.x1; ++x) {
      const uint8_t* pixel = row + static_cast<size_t>(x) * channels;
      out.push_back(channels >= 3 ? (pixel[0] + 2 * pixel[1] + pixel[2]) / 4 : pixel[0]);
    }
  }
}

// The mean absolute difference of two frames' luma less the frame pair's own noise level, the
// median absolute difference (never below 0 per pixel). Touches move a small part of the
// picture, so the median is what every still pixel does: sensor noise, and the re-encoding of
// the whole picture at a key frame (a pulse of about a luma level every GOP that would
// otherwise beat through the series), or a camera's exposure stepping.
double change_beyond_noise(const std::vector<int>& previous, const std::vector<int>& current,
                           std::vector<int>& difference) {
  difference.resize(current.size());
  int histogram[256] = {};
  for (size_t k = 0; k < current.size(); ++k) {
    difference[k] = std::abs(current[k] - previous[k]);
    ++histogram[difference[k]];
  }
  const size_t half = current.size() / 2;
  int median = 0;
  for (size_t below = 0; median < 255; ++median) {
    below += static_cast<size_t>(histogram[median]);
    if (below > half) break;
  }
  long total = 0;
  for (int value : difference) total += std::max(0, value - median);
  return static_cast<double>(total) / static_cast<double>(current.size());
}

}  // namespace

ActivitySeries motion_energy(VideoFile& video, double rate, std::optional<VideoRegion> region,
                             const std::function<void(double)>& progress) {
  if (!(rate > 0)) throw Error("motion energy", "the rate must be positive");
  ActivitySeries series{0.0, rate, {}};
  const std::vector<double>& times = video.frame_times();
  const auto count = static_cast<int64_t>(times.size());
  if (count == 0) return series;
  const auto steps = static_cast<size_t>(std::floor(times.back() * rate)) + 1;
  // Each step the mean of the frame differences that end in it: for a steady frame rate the
  // same as their sum up to a constant (as the skin's activity sums its changes), while a
  // step with a frame more or less than its neighbours (30 fps on a 10 Hz grid from a
  // variable-rate file) does not jump; the maximum would keep one difference in three.
  std::vector<double> sum(steps, 0.0);
  std::vector<int> differences(steps, 0);
  std::vector<int> previous, current, difference;
  PixelBox box;
  const int64_t report_every = std::max<int64_t>(1, count / 100);
  for (int64_t index = 0; index < count; ++index) {
    if (cancel_requested()) throw Error("motion energy", "cancelled");
    const VideoFrame& frame = video.frame(index);
    if (index == 0) box = box_of(region, frame.width, frame.height);
    luma_of(frame, box, current);
    if (index > 0 && current.size() == previous.size() && !current.empty()) {
      const double energy = change_beyond_noise(previous, current, difference);
      const auto step = std::min(
          steps - 1, static_cast<size_t>(std::max(0.0, times[static_cast<size_t>(index)] * rate)));
      sum[step] += energy;
      ++differences[step];
    }
    std::swap(previous, current);
    if (progress && (index + 1) % report_every == 0)
      progress(static_cast<double>(index + 1) / static_cast<double>(count));
  }
  // A step no difference ends in (the first; gaps of a variable rate) takes its neighbour's.
  series.values.assign(steps, 0.0);
  double last = -1.0;
  for (size_t step = 0; step < steps; ++step) {
    if (differences[step] > 0) last = sum[step] / differences[step];
    series.values[step] = last;
  }
  const auto first = std::find_if(series.values.begin(), series.values.end(),
                                  [](double value) { return value >= 0; });
  const double lead = first == series.values.end() ? 0.0 : *first;
  for (auto it = series.values.begin(); it != first; ++it) *it = lead;
  if (progress) progress(1.0);
  return series;
}

}  // namespace tactile

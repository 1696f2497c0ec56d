#pragma once
// Synthetic videos of a simulated pressure grid being touched, for the offset proposal's tests
// and benchmark: a bright blob over where the skin is pressed, as large as the pressure there
// (what the skin view shows: the change from rest beyond the noise band), on a static textured
// background with sensor noise, and a dark "person" drifting now and then, unrelated to the
// touches. Written with core's VideoWriter; the video's time 0 is shown at recording time
// `offset`. A control whose motion is unrelated to a recording's touches: the video of another
// recording.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/signal/display_scale.h"
#include "tactile/video/video_writer.h"

namespace tactile::test {

struct TouchVideoOptions {
  int width = 160;
  int height = 120;
  double rate = 30;
  double offset = 0;     // recording time at which the video's time 0 is shown
  double seconds = 60;   // the video's length
  double unrelated = 1;  // how much the person moves (0: never)
  double noise = 3;      // sensor noise, luma levels (uniform +-)
  uint64_t seed = 1;
};

// Per sample of a grid stream (rows x columns, channel = row * columns + column): the summed
// change from rest beyond the noise band, and its centroid (row, column).
struct PressureTrack {
  std::vector<double> total, row, column;
  double rate = 0, start = 0;
};

inline PressureTrack pressure_track(const Stream& stream, int64_t columns) {
  std::vector<int> all(static_cast<size_t>(stream.channel_count()));
  for (size_t c = 0; c < all.size(); ++c) all[c] = static_cast<int>(c);
  const RestScale scale = rest_scale(stream, all);
  PressureTrack track;
  track.rate = stream.rate_hz;
  track.start = stream.start_time;
  for (int64_t i = 0; i < stream.sample_count(); ++i) {
    std::vector<float> values(all.size());
    for (size_t c = 0; c < all.size(); ++c) values[c] = stream.samples(i, static_cast<int>(c));
    const std::vector<float> change = change_from_rest(values, scale);
    double total = 0, row = 0, column = 0;
    for (size_t c = 0; c < change.size(); ++c) {
      if (!std::isfinite(change[c])) continue;
      total += change[c];
      row += change[c] * static_cast<double>(static_cast<int64_t>(c) / columns);
      column += change[c] * static_cast<double>(static_cast<int64_t>(c) % columns);
    }
    track.total.push_back(total);
    track.row.push_back(total > 0 ? row / total : 0);
    track.column.push_back(total > 0 ? column / total : 0);
  }
  return track;
}

// Linear interpolation of a track's series at recording time t; 0 outside.
inline double track_at(const PressureTrack& track, const std::vector<double>& series, double t) {
  const double position = (t - track.start) * track.rate;
  if (position < 0 || position > static_cast<double>(series.size() - 1)) return 0;
  const auto i = static_cast<size_t>(position);
  const double fraction = position - static_cast<double>(i);
  return i + 1 < series.size() ? series[i] * (1 - fraction) + series[i + 1] * fraction : series[i];
}

// Writes the video; the grid has rows x columns taxels.
inline void write_touch_video(const std::string& path, const Stream& stream, int64_t rows,
                              int64_t columns, const TouchVideoOptions& options) {
  const PressureTrack track = pressure_track(stream, columns);
  const double peak = std::max(1e-9, *std::max_element(track.total.begin(), track.total.end()));
  const int w = options.width, h = options.height;
  std::mt19937_64 engine(options.seed);
  std::uniform_int_distribution<int> texture(60, 110);
  std::vector<uint8_t> background(static_cast<size_t>(w) * h);
  for (auto& pixel : background) pixel = static_cast<uint8_t>(texture(engine));
  std::uniform_real_distribution<double> noise(-options.noise, options.noise), unit(0, 1);
  // The person: episodes of slow drift at random times, still in between.
  double person_x = w * 0.8, person_velocity = 0, episode_end = 0;

  VideoWriterOptions writer_options;
  writer_options.width = w;
  writer_options.height = h;
  writer_options.rate = options.rate;
  VideoWriter writer(path, writer_options);
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
  const auto frames = static_cast<int64_t>(options.seconds * options.rate);
  for (int64_t frame = 0; frame < frames; ++frame) {
    const double video_time = static_cast<double>(frame) / options.rate;
    const double t = options.offset + video_time;
    const double total = track_at(track, track.total, t);
    const double radius = total > 0 ? 4.0 + 20.0 * std::sqrt(total / peak) : 0.0;
    const double blob_x = (track_at(track, track.column, t) + 0.5) / columns * w * 0.6;
    const double blob_y = (track_at(track, track.row, t) + 0.5) / rows * h;
    if (options.unrelated > 0) {
      if (video_time >= episode_end) {
        const bool moving = unit(engine) < 0.5;
        person_velocity = moving ? (unit(engine) - 0.5) * 30.0 * options.unrelated : 0.0;
        episode_end = video_time + 1.0 + 4.0 * unit(engine);
      }
      person_x = std::clamp(person_x + person_velocity / options.rate, w * 0.65, w * 0.95);
    }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double value = background[static_cast<size_t>(y) * w + x] + noise(engine);
        if (radius > 0 && std::hypot(x - blob_x, y - blob_y) < radius) value = 230;
        if (options.unrelated > 0 && std::abs(x - person_x) < 8 && y > h / 3) value = 25;
        const auto level = static_cast<uint8_t>(std::clamp(value, 0.0, 255.0));
        uint8_t* pixel = &rgba[(static_cast<size_t>(y) * w + x) * 4];
        pixel[0] = pixel[1] = pixel[2] = level;
        pixel[3] = 255;
      }
    writer.write(rgba.data(), video_time);
  }
  writer.finish();
}

}  // namespace tactile::test

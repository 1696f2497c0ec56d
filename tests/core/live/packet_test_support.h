#pragma once
// Streams on each device's ADC grid, written from the ranges in docs/PACKETS.md (not from the
// codec's tables), so a wrong scale in the codec shows up as a mismatch.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"

namespace tactile::test {

struct GridRange {
  double offset;
  double step;
  int32_t min_count;
  int32_t max_count;
};

// The documented range of a channel of `skin` with modality `modality`.
inline GridRange documented_range(const std::string& skin, const std::string& modality) {
  if (skin == "nao") {
    if (modality == "ax" || modality == "ay" || modality == "az")
      return {0.0, 4.0 / 1024.0, -512, 511};
    if (modality == "prox") return {1.0, 199.0 / 65535.0, 0, 65535};
    if (modality == "temp") return {0.0, 0.01, -4000, 15000};
    return {0.0, 3.0 / 4095.0, 0, 4095};  // f1 f2 f3
  }
  if (skin == "tsa") return {0.0, 1.0, 0, 4095};
  if (skin == "robovie") return {0.0, 1.0, -32768, 32767};
  return {0.0, 1.0, 0, 1023};  // fur, flux
}

inline float grid_value(const GridRange& range, int32_t count) {
  return static_cast<float>(range.offset + count * range.step);
}

// A stream of every layout channel (flux's sums included, which the device never sends),
// `samples` rows of random counts converted to units; the first row holds each range's
// minimum and the second its maximum.
inline Stream grid_stream(const SkinLayout& layout, int64_t samples, uint64_t seed) {
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = layout.sample_rate_hz;
  stream.start_time = 12.5;
  stream.samples.resize(samples, static_cast<Eigen::Index>(layout.channels.size()));
  std::mt19937_64 engine(seed);
  for (size_t column = 0; column < layout.channels.size(); ++column) {
    const Channel& channel = layout.channels[column];
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
    const GridRange range = documented_range(layout.id, channel.modality);
    std::uniform_int_distribution<int32_t> counts(range.min_count, range.max_count);
    for (int64_t row = 0; row < samples; ++row) {
      const int32_t count = row == 0   ? range.min_count
                            : row == 1 ? range.max_count
                                       : counts(engine);
      stream.samples(row, static_cast<Eigen::Index>(column)) = grid_value(range, count);
    }
  }
  return stream;
}

}  // namespace tactile::test

#include "tactile/signal/display_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

// Top of the scale: the 99th percentile of the changes beyond the noise band.
double top_of_changes(std::vector<float>& excess) {
  if (excess.empty()) return 1.0;
  const auto top = static_cast<size_t>(0.99 * static_cast<double>(excess.size() - 1));
  return std::max(1e-6f, stats::nth_smallest(excess, top));
}

}  // namespace

RestScale rest_scale(const SampleSource& source, const std::vector<int>& columns, int probes) {
  const int64_t count = source.sample_count();
  if (count <= kRestScaleExactSamples) {
    // Few samples: the exact probe estimate over the samples themselves.
    std::vector<int> present;
    for (int column : columns)
      if (column >= 0 && column < source.channel_count()) present.push_back(column);
    Stream stream;
    stream.samples = source.read(present, 0, count);
    std::vector<int> mapped(columns.size(), -1);
    for (size_t k = 0, next = 0; k < columns.size(); ++k)
      if (columns[k] >= 0 && columns[k] < source.channel_count())
        mapped[k] = static_cast<int>(next++);
    return rest_scale(stream, mapped, probes);
  }
  RestScale scale;
  scale.rest.assign(columns.size(), std::numeric_limits<float>::quiet_NaN());
  scale.noise_band.assign(columns.size(), 0.0f);
  if (probes < 1) return scale;
  // Buckets of whole coarse blocks, so that a file answers from its overview alone, with
  // no lookup of times (the buckets are the same for every column).
  const int64_t block = std::max<int64_t>(1, source.coarse_block());
  const int64_t blocks = (count + block - 1) / block;
  probes = static_cast<int>(std::clamp<int64_t>(blocks, 1, probes));
  std::vector<int64_t> edges(static_cast<size_t>(probes) + 1);
  for (int64_t bucket = 0; bucket <= probes; ++bucket)
    edges[static_cast<size_t>(bucket)] = std::min(count, bucket * blocks / probes * block);
  std::vector<MinMax> buckets(static_cast<size_t>(probes));
  std::vector<float> centres, halves, excess;
  for (size_t k = 0; k < columns.size(); ++k) {
    const int column = columns[k];
    if (column < 0 || column >= source.channel_count()) continue;
    source.minmax(column, edges, buckets);
    centres.clear();
    halves.clear();
    for (const MinMax& bucket : buckets) {
      if (bucket.empty()) continue;
      centres.push_back(0.5f * (bucket.min + bucket.max));
      halves.push_back(0.5f * (bucket.max - bucket.min));
    }
    if (centres.empty()) continue;
    const float rest = stats::median(centres);
    const float band = stats::median(halves);
    scale.rest[k] = rest;
    scale.noise_band[k] = band;
    for (const MinMax& bucket : buckets) {
      if (bucket.empty()) continue;
      const float beyond =
          std::max(std::abs(bucket.max - rest), std::abs(bucket.min - rest)) - band;
      if (beyond > 0.0f) excess.push_back(beyond);
    }
  }
  scale.max_change = top_of_changes(excess);
  return scale;
}

RestScale rest_scale(const Stream& stream, const std::vector<int>& columns, int probes) {
  RestScale scale;
  scale.rest.assign(columns.size(), std::numeric_limits<float>::quiet_NaN());
  scale.noise_band.assign(columns.size(), 0.0f);
  const int64_t count = stream.sample_count();
  if (count == 0 || probes < 1) return scale;
  const int64_t taken = std::min<int64_t>(count, probes);
  std::vector<float> column_values;
  std::vector<float> deviations;
  std::vector<float> excess;
  for (size_t k = 0; k < columns.size(); ++k) {
    const int column = columns[k];
    if (column < 0 || column >= stream.channel_count()) continue;
    column_values.clear();
    for (int64_t probe = 0; probe < taken; ++probe) {
      const float value =
          stream.samples(probe * (count - 1) / std::max<int64_t>(1, taken - 1), column);
      if (std::isfinite(value)) column_values.push_back(value);
    }
    if (column_values.empty()) continue;
    const float rest = stats::median(column_values);
    deviations.clear();
    for (float value : column_values) deviations.push_back(std::abs(value - rest));
    const float band = 3.0f * 1.4826f * stats::median(deviations);
    scale.rest[k] = rest;
    scale.noise_band[k] = band;
    for (float value : column_values) {
      const float beyond = std::abs(value - rest) - band;
      if (beyond > 0.0f) excess.push_back(beyond);
    }
  }
  if (!excess.empty()) scale.max_change = top_of_changes(excess);
  return scale;
}

RestScale live_rest_scale(const SampleSource& source, const std::vector<int>& columns,
                          double previous_top) {
  RestScale scale = rest_scale(source, columns);
  std::vector<float> bands;
  for (size_t k = 0; k < scale.noise_band.size(); ++k)
    if (std::isfinite(scale.rest[k])) bands.push_back(scale.noise_band[k]);
  const double quiet_top = bands.empty() ? 0.0 : kQuietTopBands * stats::median(bands);
  scale.max_change = std::max({scale.max_change, previous_top, quiet_top});
  return scale;
}

std::vector<float> change_from_rest(const std::vector<float>& values, const RestScale& scale) {
  std::vector<float> changes(values.size(), std::numeric_limits<float>::quiet_NaN());
  for (size_t k = 0; k < values.size() && k < scale.rest.size(); ++k) {
    const float change = std::abs(values[k] - scale.rest[k]);  // NaN in either stays NaN
    changes[k] = std::isnan(change) ? change : std::max(0.0f, change - scale.noise_band[k]);
  }
  return changes;
}

std::vector<double> activity_edges(const SampleSource& source, const std::vector<int>& channels,
                                   const RestScale& scale, double t, double tolerance,
                                   int columns) {
  std::vector<uint8_t> active(static_cast<size_t>(columns), 0);
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] < 0 || std::isnan(scale.rest[k])) continue;
    const std::vector<MinMax> buckets =
        source.minmax_over_time(channels[k], t - tolerance, t + tolerance, columns);
    for (size_t c = 0; c < buckets.size() && c < active.size(); ++c)
      if (!buckets[c].empty() && (buckets[c].max > scale.rest[k] + scale.noise_band[k] ||
                                  buckets[c].min < scale.rest[k] - scale.noise_band[k]))
        active[c] = 1;
  }
  std::vector<double> edges;
  const double width = 2.0 * tolerance / columns;
  for (int c = 1; c < columns; ++c)
    if (active[static_cast<size_t>(c)] != active[static_cast<size_t>(c - 1)])
      edges.push_back(t - tolerance + c * width);
  return edges;
}

double peak_change_time(const SampleSource& source, const std::vector<int>& channels,
                        const RestScale& scale, double t0, double t1, int64_t max_samples) {
  std::vector<int> present;
  std::vector<float> rest;
  for (size_t k = 0; k < channels.size(); ++k)
    if (channels[k] >= 0) present.push_back(channels[k]), rest.push_back(scale.rest[k]);
  const int64_t start = source.index_at(t0);
  const int64_t end = std::min(source.index_at(t1), start + max_samples);
  if (present.empty() || source.sample_count() == 0) return source.time_of((start + end) / 2);
  const SampleMatrix samples = source.read(present, start, end - start + 1);
  int64_t best = (start + end) / 2;
  double best_change = -1.0;
  for (int64_t row = 0; row < samples.rows(); ++row) {
    double change = 0.0;
    for (size_t k = 0; k < present.size(); ++k)
      if (std::isfinite(rest[k]))
        change += std::abs(samples(row, static_cast<Eigen::Index>(k)) - rest[k]);
    if (change > best_change) best_change = change, best = start + row;
  }
  return source.time_of(best);
}

}  // namespace tactile

#include "tactile/io/minmax_pyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "tactile/error.h"

namespace tactile {

namespace {

// The finest level merges 16 raw samples and each next one 16 buckets (sizes 16,
// 256, 4096, ...): the levels hold 2 * N / 16 * 16 / 15 = N / 7.5 floats, under a
// seventh of the raw data, and a query reads at most 15 raw samples at a column
// edge. Factor 16 rather than 4 halves the levels a query climbs, and the up to 15
// buckets it merges per level and edge lie in two cache lines.
constexpr int64_t kFinestBucket = 16;
constexpr int64_t kLevelFactor = 16;
// Levels are added until the coarsest has at most this many buckets.
constexpr int64_t kTopBuckets = 4;

int64_t round_up(int64_t value, int64_t step) { return (value + step - 1) / step * step; }

}  // namespace

//---- Construction

MinMaxPyramid::MinMaxPyramid(std::span<const float> samples)
    : sample_count_(static_cast<int64_t>(samples.size())), samples_(samples) {
  if (sample_count_ == 0) return;
  Level finest;
  finest.bucket = kFinestBucket;
  finest.shift = std::countr_zero(static_cast<uint64_t>(kFinestBucket));
  finest.buckets.resize(round_up(sample_count_, kFinestBucket) / kFinestBucket);
  for (size_t bucket = 0; bucket < finest.buckets.size(); ++bucket) {
    const int64_t begin = static_cast<int64_t>(bucket) * kFinestBucket;
    const int64_t end = std::min(sample_count_, begin + kFinestBucket);
    for (int64_t index = begin; index < end; ++index) finest.buckets[bucket].add(samples[index]);
  }
  levels_.push_back(std::move(finest));
  add_coarser_levels();
}

MinMaxPyramid::MinMaxPyramid(int64_t sample_count, std::span<const float> overview_min,
                             std::span<const float> overview_max, RawSampleReader reader,
                             const std::string& where)
    : sample_count_(sample_count), reader_(std::move(reader)) {
  if (sample_count < 0) throw Error(where, "negative sample count " + std::to_string(sample_count));
  const int64_t blocks = round_up(sample_count, kOverviewBlock) / kOverviewBlock;
  if (static_cast<int64_t>(overview_min.size()) != blocks ||
      static_cast<int64_t>(overview_max.size()) != blocks) {
    throw Error(where, "overview has " + std::to_string(overview_min.size()) + " minima and " +
                           std::to_string(overview_max.size()) + " maxima, expected " +
                           std::to_string(blocks) + " blocks of " + std::to_string(kOverviewBlock) +
                           " for " + std::to_string(sample_count) + " samples");
  }
  if (!reader_) throw Error(where, "no reader for raw samples");
  if (blocks == 0) return;
  Level overview;
  overview.bucket = kOverviewBlock;
  overview.shift = std::countr_zero(static_cast<uint64_t>(kOverviewBlock));
  overview.buckets.resize(blocks);
  for (int64_t block = 0; block < blocks; ++block) {
    const float low = overview_min[block];
    const float high = overview_max[block];
    // Named only when wrong: a string per block was most of an hour's opening.
    const auto block_where = [&] { return where + " overview block " + std::to_string(block); };
    if (std::isnan(low) != std::isnan(high)) {
      throw Error(block_where(), "NaN on one side only (min " + std::to_string(low) + ", max " +
                                     std::to_string(high) + ")");
    }
    const bool gap =
        std::isnan(low) || (std::isinf(low) && low > 0 && std::isinf(high) && high < 0);
    if (!gap && low > high) {
      throw Error(block_where(),
                  "min " + std::to_string(low) + " is above max " + std::to_string(high));
    }
    if (!gap) overview.buckets[block] = {low, high};  // a gap stays the empty range
  }
  levels_.push_back(std::move(overview));
  add_coarser_levels();
}

void MinMaxPyramid::add_coarser_levels() {
  while (static_cast<int64_t>(levels_.back().buckets.size()) > kTopBuckets) {
    const Level& finer = levels_.back();
    const int64_t finer_count = static_cast<int64_t>(finer.buckets.size());
    Level coarser;
    coarser.bucket = finer.bucket * kLevelFactor;
    coarser.shift = std::countr_zero(static_cast<uint64_t>(coarser.bucket));
    coarser.buckets.resize(round_up(finer_count, kLevelFactor) / kLevelFactor);
    for (int64_t bucket = 0; bucket < static_cast<int64_t>(coarser.buckets.size()); ++bucket) {
      const int64_t end = std::min(finer_count, (bucket + 1) * kLevelFactor);
      for (int64_t child = bucket * kLevelFactor; child < end; ++child) {
        coarser.buckets[bucket].merge(finer.buckets[child]);
      }
    }
    levels_.push_back(std::move(coarser));
  }
}

//---- Queries

void MinMaxPyramid::merge_raw(int64_t first, int64_t last, MinMax& result) const {
  if (first >= last) return;
  raw_samples_read_ += last - first;
  if (!reader_) {
    for (int64_t index = first; index < last; ++index) result.add(samples_[index]);
    return;
  }
  std::vector<float> buffer(static_cast<size_t>(last - first));
  reader_(first, buffer);
  for (float value : buffer) result.add(value);
}

MinMax MinMaxPyramid::range_clipped(int64_t first, int64_t last) const {
  // Climb from raw samples to ever coarser buckets, taking at each level only the
  // partial buckets at both ends, then the whole buckets left in the middle.
  // Invariant: `first` is a multiple of the current bucket size, `last` is one too
  // or is the end of the data (the last bucket may be short). Bucket sizes are
  // powers of two, so shifts and masks stand in for divisions, which would cost
  // more than the merging itself.
  MinMax result;
  int current = -1;  // -1: raw samples
  for (int next = 0; next < static_cast<int>(levels_.size()); ++next) {
    const int64_t mask = levels_[next].bucket - 1;
    const int64_t first_up = (first + mask) & ~mask;
    const int64_t last_down = last == sample_count_ ? last : last & ~mask;
    if (first_up >= last_down) break;  // no whole bucket of the next level fits
    if (current < 0) {
      merge_raw(first, first_up, result);
      merge_raw(last_down, last, result);
    } else {
      const Level& level = levels_[current];
      const int shift = level.shift;
      const int64_t round = level.bucket - 1;
      for (int64_t index = first >> shift; index < first_up >> shift; ++index) {
        result.merge(level.buckets[index]);
      }
      for (int64_t index = last_down >> shift; index < (last + round) >> shift; ++index) {
        result.merge(level.buckets[index]);
      }
    }
    first = first_up;
    last = last_down;
    current = next;
  }
  if (current < 0) {
    merge_raw(first, last, result);
  } else {
    const Level& level = levels_[current];
    const int64_t end = (last + level.bucket - 1) >> level.shift;
    for (int64_t index = first >> level.shift; index < end; ++index) {
      result.merge(level.buckets[index]);
    }
  }
  return result;
}

MinMax MinMaxPyramid::range(int64_t first, int64_t last) const {
  first = std::max<int64_t>(first, 0);
  last = std::min(last, sample_count_);
  if (first >= last) return {};
  return range_clipped(first, last);
}

void MinMaxPyramid::query_edges(std::span<const int64_t> edges, std::span<MinMax> out) const {
  if (edges.empty() ? !out.empty() : out.size() != edges.size() - 1) {
    throw Error("min/max query", std::to_string(edges.size()) + " column edges for " +
                                     std::to_string(out.size()) + " columns");
  }
  for (size_t column = 0; column + 1 < edges.size(); ++column) {
    if (edges[column + 1] < edges[column]) {
      throw Error("min/max query", "column edges decrease at column " + std::to_string(column));
    }
  }
  if (out.empty()) return;
  const int64_t first = std::max<int64_t>(edges.front(), 0);
  const int64_t last = std::min(edges.back(), sample_count_);
  const int64_t columns = static_cast<int64_t>(out.size());
  // Edges all on block boundaries (or outside the data) are answered by the levels alone.
  const bool on_blocks = std::all_of(edges.begin(), edges.end(), [&](int64_t edge) {
    return edge <= 0 || edge >= sample_count_ || edge % kOverviewBlock == 0;
  });
  if (reader_ && !on_blocks && first < last && last - first <= kOverviewBlock * columns) {
    // Zoomed in: the visible samples are few, read them in one piece rather than
    // column edge by column edge.
    std::vector<float> visible(static_cast<size_t>(last - first));
    reader_(first, visible);
    raw_samples_read_ += last - first;
    for (int64_t column = 0; column < columns; ++column) {
      MinMax result;
      const int64_t begin = std::clamp(edges[column], first, last);
      const int64_t end = std::clamp(edges[column + 1], first, last);
      for (int64_t index = begin; index < end; ++index) result.add(visible[index - first]);
      out[column] = result;
    }
    return;
  }
  for (int64_t column = 0; column < columns; ++column) {
    out[column] = range(edges[column], edges[column + 1]);
  }
}

std::vector<MinMax> MinMaxPyramid::query(int64_t first, int64_t last, int columns) const {
  if (columns <= 0) return {};
  std::vector<int64_t> edges(static_cast<size_t>(columns) + 1);
  const int64_t span = std::max<int64_t>(last - first, 0);
  for (int column = 0; column <= columns; ++column) {
    // Exact integer split, span * column / columns rounded down, without overflow for any
    // sample count: span = whole * columns + rest, and rest * column < columns * columns.
    const int64_t whole = span / columns, rest = span % columns;
    edges[column] = first + whole * column + rest * column / columns;
  }
  std::vector<MinMax> out(static_cast<size_t>(columns));
  query_edges(edges, out);
  return out;
}

int64_t MinMaxPyramid::finest_bucket() const {
  return levels_.empty() ? (reader_ ? kOverviewBlock : kFinestBucket) : levels_.front().bucket;
}

int64_t MinMaxPyramid::memory_bytes() const {
  int64_t bytes = 0;
  for (const Level& level : levels_) {
    bytes += static_cast<int64_t>(level.buckets.size() * sizeof(MinMax));
  }
  return bytes;
}

}  // namespace tactile

// The live buffer: a ring of samples and rings of block minima and maxima.
#include "tactile/live/live_source.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tactile/error.h"

namespace tactile {

namespace {

constexpr float kGap = std::numeric_limits<float>::quiet_NaN();

constexpr int64_t block_size(int level) {
  int64_t size = LiveSampleSource::kBlock;
  for (int k = 0; k < level; ++k) size *= LiveSampleSource::kBlock;
  return size;
}

}  // namespace

LiveSampleSource::LiveSampleSource(SourceInfo info, int64_t capacity_samples)
    : info_(std::move(info)),
      capacity_(capacity_samples),
      channels_(static_cast<int>(info_.channels.size())),
      rate_(info_.rate_hz) {
  const std::string where = "live stream " + info_.layout_id;
  if (!(rate_ > 0.0) || !std::isfinite(rate_)) throw Error(where, "needs a positive sample rate");
  if (channels_ == 0) throw Error(where, "has no channels");
  if (capacity_ < 1) throw Error(where, "buffer must hold at least one sample");
  samples_.assign(static_cast<size_t>(capacity_ * channels_), kGap);
  for (int level = 0; level < kLevels; ++level) {
    // Every block overlapping the kept samples, plus the one being filled.
    level_slots_[level] = capacity_ / block_size(level) + 2;
    levels_[level].assign(static_cast<size_t>(level_slots_[level] * channels_), MinMax{});
  }
  info_.start_time = 0.0;
}

const SourceInfo& LiveSampleSource::info() const {
  std::lock_guard lock(mutex_);
  return info_;
}

int64_t LiveSampleSource::sample_count() const {
  std::lock_guard lock(mutex_);
  return count_;
}

int64_t LiveSampleSource::first_kept() const {
  std::lock_guard lock(mutex_);
  return std::max<int64_t>(0, count_ - capacity_);
}

int64_t LiveSampleSource::gap_samples() const {
  std::lock_guard lock(mutex_);
  return gaps_;
}

std::vector<std::pair<int64_t, int64_t>> LiveSampleSource::gaps() const {
  std::lock_guard lock(mutex_);
  return gap_ranges_;
}

int64_t LiveSampleSource::dropped_samples() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

MinMax& LiveSampleSource::block(int level, int64_t index, int channel) {
  const int64_t slot = (index / block_size(level)) % level_slots_[level];
  return levels_[level][static_cast<size_t>(slot * channels_ + channel)];
}

const MinMax& LiveSampleSource::block(int level, int64_t index, int channel) const {
  const int64_t slot = (index / block_size(level)) % level_slots_[level];
  return levels_[level][static_cast<size_t>(slot * channels_ + channel)];
}

void LiveSampleSource::start_block(int64_t index) {
  for (int level = 0; level < kLevels; ++level) {
    if (index % block_size(level) != 0) break;  // a coarser block cannot start here either
    for (int channel = 0; channel < channels_; ++channel) block(level, index, channel) = MinMax{};
  }
}

void LiveSampleSource::put(int64_t index, std::span<const float> values) {
  for (int channel = 0; channel < channels_; ++channel) {
    const float value = values[static_cast<size_t>(channel)];
    at(index, channel) = value;
    // A NaN is a gap: MinMax::add leaves the range alone.
    for (int level = 0; level < kLevels; ++level) block(level, index, channel).add(value);
  }
}

LiveSampleSource::Placed LiveSampleSource::add(double time, std::span<const float> values) {
  if (static_cast<int>(values.size()) != channels_)
    throw Error("live stream " + info_.layout_id, std::to_string(values.size()) + " values for " +
                                                      std::to_string(channels_) + " channels");
  std::lock_guard lock(mutex_);
  Placed placed;
  if (!std::isfinite(time)) {
    ++dropped_;
    return placed;
  }
  if (!started_) {
    started_ = true;
    info_.start_time = time;
  }
  int64_t index = std::llround((time - info_.start_time) * rate_);
  const int64_t first = std::max<int64_t>(0, count_ - capacity_);
  if (index < first) {
    // Older than anything held. Far older than the buffer: the device's clock started over
    // (a restarted sender); the stream goes on from where it is, at this time.
    if (index < count_ - 2 * capacity_ - static_cast<int64_t>(rate_)) {
      info_.start_time = time - static_cast<double>(count_) / rate_;
      index = count_;
    } else {
      ++dropped_;
      return placed;
    }
  }
  if (index < count_) {
    put(index, values);  // a late (reordered) sample fills its place
    for (size_t k = 0; k < gap_ranges_.size(); ++k) {
      auto& [from, to] = gap_ranges_[k];
      if (index < from || index >= to) continue;
      if (index == from) {
        ++from;
      } else if (index == to - 1) {
        --to;
      } else {
        const std::pair<int64_t, int64_t> after{index + 1, to};
        to = index;
        gap_ranges_.insert(gap_ranges_.begin() + static_cast<std::ptrdiff_t>(k) + 1, after);
      }
      break;
    }
    std::erase_if(gap_ranges_, [](const auto& range) { return range.first >= range.second; });
    placed.index = index;
    return placed;
  }
  // Ahead: the samples between are gaps. Only the last `capacity` of them are ever held.
  placed.gap = index - count_;
  gaps_ += placed.gap;
  if (placed.gap > 0) gap_ranges_.emplace_back(count_, index);
  // Only what the buffer still holds.
  while (!gap_ranges_.empty() && gap_ranges_.front().second <= index + 1 - capacity_)
    gap_ranges_.erase(gap_ranges_.begin());
  for (int64_t gap = std::max(count_, index - capacity_); gap < index; ++gap) {
    start_block(gap);
    for (int channel = 0; channel < channels_; ++channel) at(gap, channel) = kGap;
  }
  start_block(index);
  put(index, values);
  count_ = index + 1;
  placed.index = index;
  return placed;
}

void LiveSampleSource::clear() {
  std::lock_guard lock(mutex_);
  count_ = 0;
  started_ = false;
  gaps_ = dropped_ = 0;
  gap_ranges_.clear();
  std::fill(samples_.begin(), samples_.end(), kGap);
  for (auto& level : levels_) std::fill(level.begin(), level.end(), MinMax{});
  info_.start_time = 0.0;
}

MinMax LiveSampleSource::range(int channel, int64_t first, int64_t end) const {
  MinMax result;
  first = std::max({first, count_ - capacity_, int64_t{0}});
  end = std::min(end, count_);
  int64_t index = first;
  // Up: raw samples to the first block edge, then ever coarser blocks while they fit.
  int level = -1;
  while (index < end) {
    const int next = level + 1;
    if (next < kLevels && index % block_size(next) == 0 && index + block_size(next) <= end) {
      level = next;
      continue;
    }
    if (level < 0) {
      result.add(at(index, channel));
      ++index;
      continue;
    }
    if (index + block_size(level) <= end) {
      result.merge(block(level, index, channel));
      index += block_size(level);
      // Climb again when this block finished a coarser one.
      continue;
    }
    --level;  // down: the rest is shorter than a block of this level
  }
  return result;
}

void LiveSampleSource::minmax(int channel, std::span<const int64_t> edges,
                              std::span<MinMax> out) const {
  if (channel < 0 || channel >= channels_)
    throw Error("live stream " + info_.layout_id, "no channel " + std::to_string(channel));
  if (edges.empty() ? !out.empty() : out.size() != edges.size() - 1)
    throw Error("min/max query", std::to_string(edges.size()) + " column edges for " +
                                     std::to_string(out.size()) + " columns");
  std::lock_guard lock(mutex_);
  for (size_t column = 0; column < out.size(); ++column) {
    if (edges[column + 1] < edges[column])
      throw Error("min/max query", "column edges decrease at column " + std::to_string(column));
    out[column] = range(channel, edges[column], edges[column + 1]);
  }
}

std::vector<float> LiveSampleSource::values_at(int64_t index) const {
  std::lock_guard lock(mutex_);
  std::vector<float> values(static_cast<size_t>(channels_), kGap);
  if (index < std::max<int64_t>(0, count_ - capacity_) || index >= count_) return values;
  for (int channel = 0; channel < channels_; ++channel)
    values[static_cast<size_t>(channel)] = at(index, channel);
  return values;
}

SampleMatrix LiveSampleSource::read(std::span<const int> channels, int64_t first,
                                    int64_t count) const {
  std::lock_guard lock(mutex_);
  const int64_t kept = std::max<int64_t>(0, count_ - capacity_);
  if (first < kept || count < 0 || first + count > count_)
    throw Error("live stream " + info_.layout_id,
                "samples [" + std::to_string(first) + ", " + std::to_string(first + count) +
                    ") outside the buffer [" + std::to_string(kept) + ", " +
                    std::to_string(count_) + ")");
  SampleMatrix out(count, static_cast<Eigen::Index>(channels.size()));
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] < 0 || channels[k] >= channels_)
      throw Error("live stream " + info_.layout_id, "no channel " + std::to_string(channels[k]));
    for (int64_t row = 0; row < count; ++row)
      out(row, static_cast<Eigen::Index>(k)) = at(first + row, channels[k]);
  }
  return out;
}

SampleMatrix LiveSampleSource::read_all_channels(int64_t first, int64_t count) const {
  std::vector<int> all(static_cast<size_t>(channels_));
  for (int channel = 0; channel < channels_; ++channel) all[static_cast<size_t>(channel)] = channel;
  return read(all, first, count);
}

int64_t LiveSampleSource::memory_bytes() const {
  int64_t bytes = static_cast<int64_t>(samples_.size() * sizeof(float));
  for (const auto& level : levels_) bytes += static_cast<int64_t>(level.size() * sizeof(MinMax));
  return bytes;
}

}  // namespace tactile

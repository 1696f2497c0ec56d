#pragma once
// LiveSampleSource: the third SampleSource, a stream that grows while it is shown. It keeps
// the newest `capacity` samples in a ring (the live buffer: its length is the user's), and
// per channel a ring of block minima and maxima at 32, 1024 and 32768 samples, updated as
// samples arrive, so a plot's frame costs the same after an hour as after a minute.
//
// Samples are placed by their device time on the stream's regular grid (start_time + i /
// rate). A sample that lands ahead of the next index leaves the samples between as gaps
// (NaN: lost packets, drawn as a break, never as a line across); one that lands behind (a
// reordered packet) fills its place if the buffer still holds it. Indices keep counting
// from the first sample ever taken: sample_count() grows for ever, and the samples before
// first_kept() are gone (gaps to minmax and values_at, an error to read).

#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "tactile/signal/sample_source.h"

namespace tactile {

class LiveSampleSource final : public SampleSource {
 public:
  // `info.start_time` is ignored: the first sample's time sets it. Throws tactile::Error when
  // the rate is not positive, there are no channels, or capacity < 1.
  LiveSampleSource(SourceInfo info, int64_t capacity_samples);

  const SourceInfo& info() const override;
  int64_t sample_count() const override;
  void minmax(int channel, std::span<const int64_t> edges, std::span<MinMax> out) const override;
  std::vector<float> values_at(int64_t index) const override;
  SampleMatrix read(std::span<const int> channels, int64_t first, int64_t count) const override;
  int64_t coarse_block() const override { return kBlock; }
  int64_t memory_bytes() const override;

  //---- Feeding (any thread; calls are serialised)
  struct Placed {
    int64_t index = -1;  // where the sample went; -1 when it was dropped (older than the buffer)
    int64_t gap = 0;     // samples left as gaps before it
  };
  // One sample of every channel (values.size() == channel count) taken at device time `time`.
  Placed add(double time, std::span<const float> values);
  // Forgets every sample; the next one starts the stream again (a new start time).
  void clear();

  int64_t capacity() const { return capacity_; }
  int64_t first_kept() const;   // index of the oldest sample still held
  int64_t gap_samples() const;  // samples left as gaps so far
  // The stretches still held that are gaps, as sample index ranges [first, end), oldest
  // first (a late sample that filled its place is taken out of its stretch).
  std::vector<std::pair<int64_t, int64_t>> gaps() const;
  int64_t dropped_samples() const;  // samples that came too late for the buffer
  // Copies samples [first, first + count) (row = sample, all channels) into `out`; the
  // recorder's pre-trigger. Throws tactile::Error outside [first_kept(), sample_count()).
  SampleMatrix read_all_channels(int64_t first, int64_t count) const;

  static constexpr int64_t kBlock = 32;  // the finest block; each level is 32 times the last
  static constexpr int kLevels = 3;

 private:
  float& at(int64_t index, int channel) {
    return samples_[static_cast<size_t>((index % capacity_) * channels_ + channel)];
  }
  float at(int64_t index, int channel) const {
    return samples_[static_cast<size_t>((index % capacity_) * channels_ + channel)];
  }
  MinMax& block(int level, int64_t index, int channel);
  const MinMax& block(int level, int64_t index, int channel) const;
  void start_block(int64_t index);  // resets every level's block that begins at index
  void put(int64_t index, std::span<const float> values);
  MinMax range(int channel, int64_t first, int64_t end) const;  // caller holds mutex_

  SourceInfo info_;
  int64_t capacity_;
  int channels_;
  double rate_;
  std::vector<float> samples_;  // [capacity][channels]
  // Per level: [slots][channels] block ranges, slot = block number % slots.
  std::vector<MinMax> levels_[kLevels];
  int64_t level_slots_[kLevels] = {};
  int64_t count_ = 0;
  bool started_ = false;
  int64_t gaps_ = 0;
  std::vector<std::pair<int64_t, int64_t>> gap_ranges_;
  int64_t dropped_ = 0;
  mutable std::mutex mutex_;
};

}  // namespace tactile

#pragma once
// SampleRing: the hand-over from a receiving thread to the UI thread. Single producer,
// single consumer, no lock: the producer writes a slot then publishes it with a release
// store of its write count; the consumer reads slots up to an acquire load of that count
// and frees them the same way. A full ring refuses the sample (the producer counts it as
// lost at the hand-over), so a stalled UI never blocks the receiver.

#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace tactile {

class SampleRing {
 public:
  // `slots` samples of `channels` values each. Throws tactile::Error when either is < 1.
  SampleRing(int64_t slots, int channels);

  // Producer side. False (and nothing written) when the ring is full.
  bool push(double time, std::span<const float> values);
  // Consumer side: hands every published sample to `take` in order, then frees the slots.
  // Returns how many were taken (at most `limit`).
  using Take = std::function<void(double time, std::span<const float> values)>;
  int64_t drain(const Take& take, int64_t limit = INT64_MAX);

  int64_t slots() const { return slots_; }
  int channels() const { return channels_; }
  int64_t size() const;  // samples waiting (a moment's view)

 private:
  int64_t slots_;
  int channels_;
  std::vector<double> times_;
  std::vector<float> values_;  // [slots][channels]
  // Written and read counts; each side writes its own, on separate cache lines.
  alignas(64) std::atomic<int64_t> written_{0};
  alignas(64) std::atomic<int64_t> read_{0};
};

}  // namespace tactile

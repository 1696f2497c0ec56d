#include "tactile/live/sample_ring.h"

#include <algorithm>
#include <string>

#include "tactile/error.h"

namespace tactile {

SampleRing::SampleRing(int64_t slots, int channels) : slots_(slots), channels_(channels) {
  if (slots < 1 || channels < 1)
    throw Error("sample ring", std::to_string(slots) + " slots of " + std::to_string(channels) +
                                   " channels: both must be at least 1");
  times_.resize(static_cast<size_t>(slots));
  values_.resize(static_cast<size_t>(slots * channels));
}

bool SampleRing::push(double time, std::span<const float> values) {
  const int64_t written = written_.load(std::memory_order_relaxed);
  if (written - read_.load(std::memory_order_acquire) >= slots_) return false;
  const int64_t slot = written % slots_;
  times_[static_cast<size_t>(slot)] = time;
  const size_t count = std::min(values.size(), static_cast<size_t>(channels_));
  std::copy_n(values.begin(), count, values_.begin() + slot * channels_);
  written_.store(written + 1, std::memory_order_release);
  return true;
}

int64_t SampleRing::drain(const Take& take, int64_t limit) {
  const int64_t read = read_.load(std::memory_order_relaxed);
  const int64_t available = std::min(written_.load(std::memory_order_acquire) - read, limit);
  for (int64_t k = 0; k < available; ++k) {
    const int64_t slot = (read + k) % slots_;
    take(times_[static_cast<size_t>(slot)],
         std::span<const float>(values_.data() + slot * channels_, static_cast<size_t>(channels_)));
  }
  read_.store(read + available, std::memory_order_release);
  return available;
}

int64_t SampleRing::size() const {
  return written_.load(std::memory_order_acquire) - read_.load(std::memory_order_acquire);
}

}  // namespace tactile

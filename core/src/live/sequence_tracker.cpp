#include <algorithm>

#include "tactile/live/packets.h"

namespace tactile {

SequenceTracker::SequenceTracker(uint32_t restart_behind)
    : restart_behind_(std::clamp<uint32_t>(restart_behind, 1, kWindow)) {}

void SequenceTracker::restart_at(uint32_t sequence) {
  ++restarts_;
  start_at(sequence);
  ++received_;
}

void SequenceTracker::start_at(uint32_t sequence) {
  started_ = true;
  first_ = sequence;
  next_ = sequence + 1;
  seen_.assign(kWindow, false);
  seen_[sequence % kWindow] = true;
}

bool SequenceTracker::accept(uint32_t sequence) {
  if (!started_) {
    start_at(sequence);
    ++received_;
    return true;
  }
  // Distance on the wrapping u32 circle: ahead when in [0, 2^31), behind otherwise.
  const int32_t ahead = static_cast<int32_t>(sequence - next_);
  if (ahead >= 0) {
    lost_ += ahead;
    // The numbers that now enter the window start unseen (a jump over a whole window clears it).
    const uint32_t entering = static_cast<uint32_t>(ahead) + 1;
    if (entering >= kWindow) {
      seen_.assign(kWindow, false);
    } else {
      for (uint32_t step = 0; step < entering; ++step) seen_[(next_ + step) % kWindow] = false;
    }
    next_ = sequence + 1;
    seen_[sequence % kWindow] = true;
    ++received_;
    return true;
  }
  const uint32_t behind = next_ - sequence;  // >= 1
  if (behind > restart_behind_) {
    // Far older than any late datagram on a network: the sender started counting again.
    restart_at(sequence);
    return true;
  }
  if (behind > next_ - first_) {
    // Sent before the first datagram we saw, so never counted lost: late, but welcome.
    ++reordered_;
    ++received_;
    first_ = sequence;
    seen_[sequence % kWindow] = true;
    return true;
  }
  if (seen_[sequence % kWindow]) {
    ++duplicated_;
    return false;
  }
  // A number counted lost when a later one arrived: it came after all.
  seen_[sequence % kWindow] = true;
  ++reordered_;
  --lost_;
  ++received_;
  return true;
}

}  // namespace tactile

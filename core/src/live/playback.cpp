#include "tactile/live/playback.h"

#include <algorithm>
#include <cmath>

namespace tactile {

void PlaybackClock::set_range(double start, double end) {
  start_ = start;
  end_ = std::max(start, end);
  time_ = std::clamp(time_, start_, end_);
}

void PlaybackClock::advance(double seconds) {
  if (!playing_ || !(seconds > 0)) return;
  time_ += seconds * speed_;
  if (time_ < end_) return;
  const double length = end_ - start_;
  if (looping_ && length > 0) {
    time_ = start_ + std::fmod(time_ - start_, length);
  } else {
    time_ = end_;
    playing_ = false;
  }
}

void PlaybackClock::seek(double time) {
  if (std::isnan(time)) return;
  time_ = std::clamp(time, start_, end_);
}

void PlaybackClock::play() {
  // Pressing play at the end starts again from the beginning, as media players do.
  if (time_ >= end_) time_ = start_;
  playing_ = end_ > start_;
}

void PlaybackClock::pause() { playing_ = false; }

void PlaybackClock::set_speed(double speed) {
  if (std::isnan(speed)) return;
  speed_ = std::clamp(speed, kMinSpeed, kMaxSpeed);
}

}  // namespace tactile

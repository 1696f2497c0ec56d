// Placing received datagrams on the stream's clock: sessions, clock jumps, stalls.
#include "tactile/live/live_timeline.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tactile/error.h"

namespace tactile {

namespace {

// How far behind the newest a number may be and still be a late datagram: `seconds` of
// datagrams, at least 16, at most the tracker's window.
uint32_t timeline_restart_behind(const LiveTimelineOptions& options) {
  const double datagrams =
      options.reorder_seconds * options.rate_hz / std::max(1, options.samples_per_datagram);
  if (!std::isfinite(datagrams)) return SequenceTracker::kWindow;
  return static_cast<uint32_t>(
      std::clamp<double>(std::ceil(datagrams), 16.0, SequenceTracker::kWindow));
}

}  // namespace

LiveTimeline::LiveTimeline(const LiveTimelineOptions& options)
    : rate_(options.rate_hz),
      per_datagram_(options.samples_per_datagram),
      tracker_(timeline_restart_behind(options)) {
  if (!(rate_ > 0.0) || !std::isfinite(rate_))
    throw Error("live timeline", "needs a positive sample rate");
  if (per_datagram_ < 1) throw Error("live timeline", "needs at least one sample per datagram");
  const double period = per_datagram_ / rate_;
  stall_seconds_ =
      options.stall_seconds > 0.0 ? options.stall_seconds : std::max(0.25, 10.0 * period);
  jump_seconds_ = options.jump_seconds > 0.0 ? options.jump_seconds : std::max(0.25, 3.0 * period);
}

void LiveTimeline::idle(double now) {
  if (started_ && !stalled_ && now - last_arrival_ > stall_seconds_) {
    stalled_ = true;
    ++stalls_;
  }
}

double LiveTimeline::session_start(double arrival) const {
  // The silence beyond the last datagram's own length is time nothing was sent: a gap of
  // that many whole samples after the newest one.
  const double silence = std::max(0.0, arrival - last_arrival_ - last_duration_);
  return end_ + static_cast<double>(std::llround(silence * rate_)) / rate_;
}

LiveTimeline::Placement LiveTimeline::place(uint32_t sequence, double device_time, int64_t samples,
                                            double arrival) {
  const double duration = static_cast<double>(samples) / rate_;
  if (!started_) {
    // The first session keeps the sender's clock: a stream starts where its device says.
    started_ = true;
    tracker_.accept(sequence);
    offset_ = 0.0;
    origin_ = device_time;
    end_index_ = samples;
    device_end_ = device_time + duration;
    end_ = device_time + duration;
    last_duration_ = duration;
    last_arrival_ = arrival;
    return {true, device_time};
  }
  const double silence = arrival - last_arrival_;
  if (silence > stall_seconds_ && !stalled_) ++stalls_;  // a stall seen only now
  stalled_ = false;
  const bool after_silence = std::exchange(reconnected_, false) || silence > stall_seconds_;
  const int32_t ahead = static_cast<int32_t>(sequence - tracker_.next());

  bool new_session = false;
  if (after_silence) {
    // After a silence or a replug the count goes on only when the silence explains the
    // numbers it skipped; anything else is a sender that started over.
    const double explained = silence * rate_ / per_datagram_ * 1.25 + 2.0;
    if (ahead < 0 || static_cast<double>(ahead) > explained) {
      tracker_.restart_at(sequence);
      new_session = true;
    }
  }
  if (!new_session) {
    const int64_t restarts = tracker_.restarts();
    if (!tracker_.accept(sequence)) return {};  // a duplicate
    new_session = tracker_.restarts() != restarts;
  }

  Placement placement{true, 0.0};
  if (new_session) {
    placement.time = session_start(arrival);
    offset_ = placement.time - device_time;
  } else if (ahead < 0) {
    // Late: it fills its own place if that is still a hole left by the datagrams around it.
    placement.time = device_time + offset_;
    const int64_t first = std::llround((placement.time - origin_) * rate_);
    const auto hole = std::find_if(holes_.begin(), holes_.end(), [&](const auto& range) {
      return first >= range.first && first + samples <= range.second;
    });
    if (hole == holes_.end()) {
      ++late_dropped_;
      return {};
    }
    const std::pair<int64_t, int64_t> after{first + samples, hole->second};
    hole->second = first;
    if (after.first < after.second) holes_.insert(hole + 1, after);
    std::erase_if(holes_, [](const auto& range) { return range.first >= range.second; });
    placement.time = origin_ + static_cast<double>(first) / rate_;
    last_arrival_ = std::max(last_arrival_, arrival);
    return placement;
  } else {
    // In order: where the sequence numbers say this datagram's device time should be.
    const double by_sequence = static_cast<double>(ahead) * per_datagram_ / rate_;
    const double step = device_time - (device_end_ + by_sequence);
    // A step forward that the silence before it explains is a pause of the sender; any step
    // back, or forward further than the silence, is its clock jumping.
    const bool paused = step > 0.0 && step <= silence + jump_seconds_;
    if (step < -0.5 / rate_ || (step > jump_seconds_ && !paused)) {
      ++clock_jumps_;
      offset_ = end_ + by_sequence - device_time;
    }
    placement.time = device_time + offset_;
  }
  // On the grid of the first sample, never before the newest (a step back of under half a
  // sample is rounding, not a jump); what it skips is a hole a late datagram may fill.
  int64_t first = std::llround((placement.time - origin_) * rate_);
  if (first < end_index_) first = end_index_;
  if (first > end_index_) {
    holes_.emplace_back(end_index_, first);
    if (holes_.size() > kHoles) holes_.erase(holes_.begin());
  }
  placement.time = origin_ + static_cast<double>(first) / rate_;
  offset_ = placement.time - device_time;
  end_index_ = first + samples;
  device_end_ = device_time + duration;
  end_ = origin_ + static_cast<double>(end_index_) / rate_;
  last_duration_ = duration;
  last_arrival_ = std::max(last_arrival_, arrival);
  return placement;
}

}  // namespace tactile

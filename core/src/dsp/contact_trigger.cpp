#include "tactile/dsp/contact_trigger.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile::dsp {

namespace {

struct ChannelState {
  double baseline = 0.0;
  bool has_baseline = false;
};

void check(const ContactTriggerOptions& options) {
  if (!(options.rate_hz > 0.0)) throw Error("rate", "frame rate must be positive");
  if (!(options.baseline_seconds > 0.0))
    throw Error("baseline_seconds",
                "must be positive, not " + std::to_string(options.baseline_seconds));
  if (!(options.noise_sigmas >= 0.0)) throw Error("noise_sigmas", "must not be negative");
  if (!(options.minimum_threshold >= 0.0)) throw Error("minimum_threshold", "must not be negative");
  if (options.hold_off_frames < 0) throw Error("hold_off_frames", "must not be negative");
}

}  // namespace

ContactTrigger contact_trigger(const SampleMatrix& smoothed,
                               const std::vector<std::vector<int>>& groups,
                               const ContactTriggerOptions& options) {
  check(options);
  const Eigen::Index frames = smoothed.rows();
  const Eigen::Index channels = smoothed.cols();
  std::vector<std::vector<int>> sheets;
  std::vector<char> covered(static_cast<size_t>(channels), 0);
  for (const std::vector<int>& group : groups) {
    for (int column : group) {
      if (column < 0 || column >= channels)
        throw Error("contact trigger", "column " + std::to_string(column) + " outside the " +
                                           std::to_string(channels) + " channels");
      covered[column] = 1;
    }
    if (!group.empty()) sheets.push_back(group);
  }
  for (Eigen::Index column = 0; column < channels; ++column)
    if (!covered[column]) sheets.push_back({static_cast<int>(column)});

  const auto span = std::max<Eigen::Index>(
      1, static_cast<Eigen::Index>(std::lround(options.baseline_seconds * options.rate_hz)));
  const Eigen::Index warm_up = std::min(span, frames);
  const double sign = options.rising ? 1.0 : -1.0;

  ContactTrigger result;
  result.contact = SampleMatrix::Zero(frames, channels);
  result.thresholds.assign(static_cast<size_t>(channels), options.minimum_threshold);
  std::vector<ChannelState> states(static_cast<size_t>(channels));

  // Initial baseline and idle noise from the first span: median and 1.4826·MAD, robust to a
  // touch that covers less than half of it.
  for (Eigen::Index column = 0; column < channels; ++column) {
    std::vector<double> idle;
    for (Eigen::Index frame = 0; frame < warm_up; ++frame)
      if (std::isfinite(smoothed(frame, column))) idle.push_back(smoothed(frame, column));
    if (idle.empty()) continue;
    const double centre = stats::median(idle);
    std::vector<double> deviations;
    for (double value : idle) deviations.push_back(std::abs(value - centre));
    const double sigma = 1.4826 * stats::median(deviations);
    states[column] = {centre, true};
    result.thresholds[column] = std::max(options.minimum_threshold, options.noise_sigmas * sigma);
  }

  const double follow = 1.0 / static_cast<double>(span);
  for (const std::vector<int>& sheet : sheets) {
    int64_t idle_run = options.hold_off_frames;  // the warm-up span counts as idle
    for (Eigen::Index frame = 0; frame < frames; ++frame) {
      bool any_active = false;
      for (int column : sheet) {
        const float value = smoothed(frame, column);
        if (!std::isfinite(value)) {
          result.contact(frame, column) = std::numeric_limits<float>::quiet_NaN();
          continue;
        }
        ChannelState& state = states[column];
        if (!state.has_baseline) state = {value, true};  // first finite frame of a late channel
        const double change = sign * (value - state.baseline);
        if (change > result.thresholds[column]) {
          result.contact(frame, column) = static_cast<float>(change);
          any_active = true;
        }
      }
      idle_run = any_active ? 0 : idle_run + 1;
      if (idle_run <= options.hold_off_frames) continue;
      for (int column : sheet) {
        const float value = smoothed(frame, column);
        if (std::isfinite(value))
          states[column].baseline += follow * (value - states[column].baseline);
      }
    }
  }
  return result;
}

}  // namespace tactile::dsp

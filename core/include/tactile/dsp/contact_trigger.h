#pragma once
// Baseline and per-channel trigger of the TSA front end (paper 001 Sec. II, spec §2.3):
// the contact value of a pad is its smoothed count's change from an idle baseline, kept
// only where it clears the pad's trigger threshold.

#include <cstdint>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile::dsp {

struct ContactTriggerOptions {
  double rate_hz = 8.0;
  // The baseline is first the median of this span (the sheet assumed idle), then follows
  // the signal with this time constant while its sheet is idle (spec: "averaged over >= 2 s
  // with no event").
  double baseline_seconds = 2.0;
  // Trigger threshold: this many robust standard deviations of the idle noise measured over
  // the first span, and never below `minimum_threshold` counts (spec: 5 sigma, 3 LSB).
  double noise_sigmas = 5.0;
  double minimum_threshold = 3.0;
  // Idle frames before the baseline follows again: the smoothed tail of a touch decays over
  // a few frames and must not be learnt as the new baseline.
  int64_t hold_off_frames = 4;
  // True when a touch raises the count (the counts grow with capacitance); false when it
  // lowers it (an LC oscillator's frequency count).
  bool rising = true;
};

struct ContactTrigger {
  // Frames x channels: the change from baseline in the touch's direction where it clears the
  // channel's threshold, else 0; NaN where the smoothed sample is not finite.
  SampleMatrix contact;
  std::vector<double> thresholds;  // per channel, counts
};

// `groups` lists the columns of each sheet: a sheet is idle when none of its channels
// triggers, and only then do its baselines follow. Columns in no group form a group each.
// Throws tactile::Error naming the bad option or column.
ContactTrigger contact_trigger(const SampleMatrix& smoothed,
                               const std::vector<std::vector<int>>& groups,
                               const ContactTriggerOptions& options);

}  // namespace tactile::dsp

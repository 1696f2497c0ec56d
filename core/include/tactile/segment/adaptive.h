#pragma once
// Segmenter "adaptive": for skins with no calibration (grid, strip, other people's
// data). Each channel's rest level and noise band come from the recording itself (the
// skin view's rest scale: median, 3-sigma band from the median absolute deviation); a
// sample is active when any channel is further from its rest than `margin` times its
// noise band; then the threshold segmenter's state machine (quiet_seconds ends a segment,
// max_seconds forces an end). Segments shorter than min_seconds are dropped.
// Parameters: margin (2: six sigma), quiet_seconds (0.25), max_seconds (10), min_seconds (0.05).
// Region: the layout group whose channels moved most over the segment, else "all".

#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters);

}  // namespace tactile

#pragma once
// Proximity segmenter (Kaboli et al., spec §1.1 action window and §1.9 multi-touch split): a body
// part (layout group of kind "side") is touched while any of its cells reads a proximity closer
// than threshold_mm. Each run of contact becomes one label on that body part, so a front and a
// back touch at once give two overlapping labels with different regions.
//
// Parameters (seconds and mm):
//   threshold_mm = 50     the contact distance of eq. (1)
//   pad_s = 0.1           margin added before the first and after the last contact sample
//   merge_gap_s = 0.2     runs closer than this merge into one action: a pat or a tickle lifts the
//                         hand between taps, and a proximity reading flickers across the threshold
//                         as the hand leaves; 0.2 s = twice pad_s, so padded windows of one body
//                         part never overlap
//   min_duration_s = 0.05 runs with less contact than this (a passing hand, one noisy reading)
//                         are dropped
// A non-finite proximity reading counts as no contact.

#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// Labels sorted by start time (then body part in layout order); class "", region the body part,
// source kSegmenter, annotator "segmenter:proximity". Throws tactile::Error naming a bad
// parameter, or the layout or recording when it has no proximity cells grouped by side.
std::vector<Label> segment_proximity(const Recording& recording, const SkinLayout& layout,
                                     const Parameters& parameters);

}  // namespace tactile

#pragma once
// Smart-fur segmentation (paper 002 Sec. 3, spec §3.4): a segment starts when any cell
// rises above a threshold, ends after a quiet second, and is cut at four seconds.

#include <cstdint>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

enum class SegmentEnd { kQuiet, kForced, kOpen };
const char* to_string(SegmentEnd end);  // "quiet", "forced", "open"

struct SampleSegment {
  int64_t first = 0;
  int64_t last = 0;  // inclusive
  SegmentEnd end = SegmentEnd::kQuiet;
};
// Spec §3.4 state machine on activity flags: quiet end after `quiet_samples` inactive samples
// (the quiet tail is not part of the segment), forced end at `max_samples`, and a segment
// still running at the end of the stream returned as kOpen [start, last].
std::vector<SampleSegment> threshold_segments(const std::vector<uint8_t>& active,
                                              int64_t quiet_samples, int64_t max_samples);

// Segmenter "threshold" on a raw smart-fur recording: the fur preprocessing
// (dsp/fur_preprocess.h), active(t) = max_c v_c(t) > threshold, then the state machine.
// Region: the layout's group of kind "region" with the most pressure over the segment, or
// "all" when the layout has none; the note says how the segment ended.
// Parameters: threshold (0.1), quiet_seconds (1), max_seconds (4), keep_open (true), and the
// keys of fur_preprocess_keys(). Throws tactile::Error naming a bad parameter.
std::vector<Label> segment_threshold(const Recording& recording, const SkinLayout& layout,
                                     const Parameters& parameters);

}  // namespace tactile

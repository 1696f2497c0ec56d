#pragma once
// Single-touch events of the TSA skin (paper 001 eq. 4, spec §2.4): an event is a maximal
// run of frames in which some pad of a sheet triggers, bounded by a rising and a falling
// edge of the frame occupancy.

#include <cstdint>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// TSA eq. (4): Ccov^n = f(n+1) - f(n), n = 0..T-2, for frame flags f in {0, 1}.
std::vector<int> occupancy_changes(const std::vector<uint8_t>& active);

struct FrameEvent {
  int64_t first = 0;  // first frame with f = 1
  int64_t last = 0;   // last frame with f = 1 (inclusive)
  bool open = false;  // the stream ended before the falling edge
};
// Maximal runs of active frames; runs separated by at most `gap` inactive frames merge.
// A run still open at the end is returned flagged open only when `keep_open`.
std::vector<FrameEvent> frame_events(const std::vector<uint8_t>& active, int64_t gap,
                                     bool keep_open);

// Segmenter "frame-edge" on a raw TSA recording: eq. (3) smoothing, baseline and trigger
// (dsp/tsa_preprocess.h), then events on the frames of each location group (a palm that
// spills onto the next sheet of the same body part is one event); each event's region is
// the location, its note names the sheet with the most active frames (spec §2.1).
// Parameters: gap (frames, 0), keep_open (false), events_per (location | sheet: one event per
// sheet as spec §2.4 words it), and the preprocessing keys of
// tsa_preprocess_keys(). Throws tactile::Error naming a bad parameter or layout.
std::vector<Label> segment_frame_edge(const Recording& recording, const SkinLayout& layout,
                                      const Parameters& parameters);

}  // namespace tactile

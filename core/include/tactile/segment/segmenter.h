#pragma once
// Contact segmenters: find touch segments in a recording. Each returns labels with
// source kSegmenter, annotator "segmenter:<method>", a region (a layout group id or
// "all") and class "" (unknown) unless the method knows it (scenario time stamps).

#include <functional>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

// proximity | threshold | frame-edge | scenario | excitation | adaptive
std::vector<std::string> segmenter_methods();
// Throws tactile::Error naming the method when unknown, or a parameter when bad.
std::vector<Label> segment_recording(const std::string& method, const Recording& recording,
                                     const SkinLayout& layout, const Parameters& parameters = {});
// The same labels from a source's stream. A method that reads a channel at a time (adaptive)
// never holds the whole recording; the others read it whole first. `step(share)` reports the
// share read and may throw to stop (a cancelled job).
std::vector<Label> segment_source(const std::string& method, const SampleSource& source,
                                  const SkinLayout& layout, const Parameters& parameters = {},
                                  const std::function<void(double)>& step = {});

}  // namespace tactile

#pragma once
// Contact segmenters: find touch segments in a recording. Each returns labels with
// source kSegmenter, annotator "segmenter:<method>", a region (a layout group id or
// "all") and class "" (unknown) unless the method knows it (scenario time stamps).

#include <string>
#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// proximity | threshold | frame-edge | scenario | excitation | adaptive
std::vector<std::string> segmenter_methods();
// Throws tactile::Error naming the method when unknown, or a parameter when bad.
std::vector<Label> segment_recording(const std::string& method, const Recording& recording,
                                     const SkinLayout& layout, const Parameters& parameters = {});

}  // namespace tactile

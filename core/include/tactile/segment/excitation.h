#pragma once
// Excitation segmenter (spec §5.5, flux sensor paper 004): one segment per excitation of
// the top layer, [onset, onset + 5 s), cut short by the end of the recording.

#include <cstdint>
#include <vector>

#include "tactile/dsp/flux.h"
#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// Onset samples of the rows of `deviation` (one column per channel, e of §5.3), watching
// the first `watched_columns` columns with dsp::ExcitationDetector.
std::vector<int64_t> excitation_onsets(const Eigen::MatrixXd& deviation, int64_t watched_columns,
                                       double rate_hz, const dsp::FluxOptions& options);

// Runs the flux preprocessing first unless the recording already went through it
// (dsp::is_flux_preprocessed). Labels: region "all", class "". Parameters: the keys of
// dsp::flux_option_keys().
std::vector<Label> segment_excitation(const Recording& recording, const SkinLayout& layout,
                                      const Parameters& parameters);

}  // namespace tactile

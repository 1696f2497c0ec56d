#pragma once
// Flux sensor features (spec §5.5-5.7, paper 004): six features of each of the four top
// channels and their virtual sum over the 5 s window after an excitation's onset: 30
// values, channel-major.

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "tactile/features/feature_extractor.h"
#include "tactile/parameters.h"

namespace tactile {

inline constexpr int kFluxFeaturesPerChannel = 6;

// Flux §5.6 over the window w = e[n_on .. n_on + L): {max value, max derivative [1/s], min
// derivative [1/s], integral [s], steady value (mean of the last `steady_samples`, or of all
// when the window is shorter), time of the first maximum [s after onset]}. Derivatives
// are first differences times fs; a window of one sample has derivatives 0. All 0 for an
// empty window.
std::array<double, kFluxFeaturesPerChannel> flux_channel_features(std::span<const double> window,
                                                                  double rate_hz,
                                                                  int64_t steady_samples);

// Pipeline "flux": preprocess = dsp::preprocess_flux; extract finds the first sample of the
// segment whose top-layer |e| exceeds θ_on and describes the §5.5 window from there (cut
// short only by the end of the recording); a segment without one is skipped. Columns
// "<channel>.<feature>" for x1..x4, x_sum. Parameters: dsp::flux_option_keys().
std::unique_ptr<FeatureExtractor> make_flux_extractor(const Parameters& parameters);

}  // namespace tactile

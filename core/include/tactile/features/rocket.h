#pragma once
// Random convolutional kernels for any layout: multivariate MiniRocket (Dempster, Schmidt and
// Webb, "MiniRocket", KDD 2021, and its multivariate code), after resampling each segment
// to a fixed length with the raw pipeline's reading (raw.h).
//
// The transform: the 84 kernels of length 9 with weights -1 and three 2s, each at dilations
// spread exponentially up to (length - 1) / 8; each (kernel, dilation) pair sums its
// convolution over a random subset of 1..min(channels, 9) channels; its features are the
// proportions of positive values (PPV) of that output minus biases; every other pair
// (alternating by kernel and dilation) keeps the zero-padded output, the others only its
// central part, as MiniRocket does.
//
// Biases. MiniRocket's fit takes them as quantiles (a low-discrepancy sequence in (0, 1))
// of the convolution output of a random training example. A pipeline turns one segment into
// one row and never sees the training set, and the segment's own quantiles would make PPV
// the quantile again (a constant). So preprocess() fits them on the recording: the
// recording is cut into 16 equal windows, each read as a segment (resampled, referenced,
// scaled); each (kernel, dilation) pair takes its quantiles of one window drawn by seed.
// No label is read: the same biases for train and test rows of a recording, and every
// recording's biases follow its own level of activity (a per-recording normalisation).
//
// Parameters: those of raw (modality, stream, baseline, scale; samples default 64, at
// least 9; series default auto: on more than 64 taxels the kernels read raw_summary's
// layout-driven series, not the channels), features = total count (default 10000; rounded down to a
// multiple of 84, at least 84), seed (default 1). Deterministic by seed.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

inline constexpr int kRocketKernelLength = 9;
inline constexpr int kRocketKernels = 84;

// The 84 kernels: the positions (0..8) of their three weights 2, in lexicographic order
// (MiniRocket's combinations(range(9), 3)); every other weight is -1.
std::vector<std::array<int, 3>> minirocket_kernels();

// The data-free part of the transform, drawn from the length, channel count and seed.
struct RocketPlan {
  int64_t length = 0;                      // samples per channel
  int64_t channels = 0;                    // input channels
  std::vector<int> dilations;              // ascending
  std::vector<int> features_per_dilation;  // per dilation, per kernel
  // Per (dilation, kernel) pair, dilation-major: the channels it sums and the fit window
  // its biases come from.
  std::vector<std::vector<int>> channel_sets;
  std::vector<int> fit_example;
  std::vector<double> quantiles;  // per feature: frac(k * golden ratio), k = 1, 2, ...
  int64_t feature_count() const { return static_cast<int64_t>(quantiles.size()); }
};
// MiniRocket's fit_dilations with at most 32 dilations per kernel; Error when length < 9 or
// features < 84.
RocketPlan plan_rocket(int64_t length, int64_t channels, int64_t features, uint64_t seed,
                       int64_t fit_examples);

// Biases from the fit examples (each length x channels): per pair, the quantiles of the
// full convolution output of its example (linear interpolation, as numpy.quantile).
std::vector<float> rocket_biases(const RocketPlan& plan,
                                 const std::vector<Eigen::MatrixXf>& examples);

// PPV features of one series (length x channels) into `features` (plan.feature_count()).
void rocket_transform(const RocketPlan& plan, const Eigen::MatrixXf& series,
                      std::span<const float> biases, std::span<double> features);

// One kernel's zero-padded ("same" length) convolution of one channel at a dilation, for
// tests: output t = sum_j weight_j x[t + (j - 4) dilation].
std::vector<double> minirocket_convolution(std::span<const double> values, int kernel,
                                           int dilation);

// Throws tactile::Error naming the parameter when unknown or bad.
std::unique_ptr<FeatureExtractor> make_rocket_extractor(const Parameters& parameters);

}  // namespace tactile

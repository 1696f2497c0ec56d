#pragma once
// Feature set "fur" (paper 002, spec §3.5): the 15 segment features of the smart-fur
// pressure matrix (duration; active area, sum pressure and peak pressure: max, mean,
// variance; pressure centre and its variance; translation of the centre).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// Per-sample series of a segment (spec §3.5), T samples each.
struct FurSeries {
  std::vector<double> area;    // A(t) = Σ_c s_c · [v_c(t) > θ]  [cm²]
  std::vector<double> sum;     // S(t) = Σ_c v_c(t)
  std::vector<double> peak;    // P(t) = max_c v_c(t)
  std::vector<Point2> centre;  // pressure- and size-weighted centre of active cells, valid t only
};

// `values`: T x C normalised pressures v in [0, 1] (rows = samples); `sizes` s_c [cm²] and
// `positions` (x_c, y_c) [cm], one per column. Throws tactile::Error when they disagree.
FurSeries fur_series(const Eigen::MatrixXd& values, const std::vector<double>& sizes,
                     const std::vector<Point2>& positions, double threshold);

constexpr int kFurFeatureCount = 15;
// Spec §3.5 order: duration, mean/max/variance area, max/mean/variance sum pressure,
// max/mean/variance peak pressure, centre x, centre y, variance x, variance y, translation.
std::array<double, kFurFeatureCount> fur_segment_features(const Eigen::MatrixXd& values,
                                                          const std::vector<double>& sizes,
                                                          const std::vector<Point2>& positions,
                                                          double threshold);

// Parameters: threshold (0.1), fur_features (15 | 14: var x + var y as one "variance
// centre"), and the preprocessing keys of dsp::fur_preprocess_keys(). Throws tactile::Error
// naming a bad one.
std::unique_ptr<FeatureExtractor> make_fur_extractor(const Parameters& parameters);

}  // namespace tactile

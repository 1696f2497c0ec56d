#pragma once
// Robovie-IIF cross-correlation features (spec §4.2-4.3, paper 003 eqs. 1-3 and 13): the
// Pearson correlation of every pair of piezo films over a segment, after sigma
// suppression. 274 films give 274 * 273 / 2 = 37,401 values per segment.

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "tactile/features/feature_extractor.h"
#include "tactile/parameters.h"

namespace tactile {

// Number of sensor pairs i < j: N (N - 1) / 2.
int64_t robovie_pair_count(int64_t sensors);
// 0-based position of the pair (i, j), 0 <= i < j < sensors, in the row-major upper
// triangle; the spec's q = (i-1)N - (i-1)i/2 + (j-i) - 1 written for 0-based i and j.
int64_t robovie_pair_index(int64_t i, int64_t j, int64_t sensors);

// Robovie eqs. (1)-(2): R_ij = C_ij / sqrt(C_ii C_jj) for the columns of `samples` (one
// column per sensor), as one product Z^T Z of the centred, unit-norm columns. A
// zero-variance column (spec §0) has R = 0 with every sensor, itself included.
Eigen::MatrixXd robovie_correlation_matrix(const Eigen::MatrixXd& samples);

// Robovie eq. (3): the feature vector a = (R_12, R_13, ..., R_{N-1,N}), after eq. (13)
// sigma suppression when `sigma_suppression` is set.
Eigen::VectorXd robovie_xcorr_vector(Eigen::MatrixXd samples, bool sigma_suppression);

// Pipeline "robovie_xcorr". Parameters: sigma_suppression=true|false (default true).
// Uses every channel of the layout, in layout order; columns "xcorr.<film i>.<film j>".
std::unique_ptr<FeatureExtractor> make_robovie_xcorr_extractor(const Parameters& parameters);

}  // namespace tactile

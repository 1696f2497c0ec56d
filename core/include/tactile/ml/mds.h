#pragma once
// Classical (Torgerson) multidimensional scaling (spec §4.8 / §6.8, TV R2), generic:
// dissimilarities in, coordinates out. The Robovie somatosensory map feeds it
// d_ij = -ln |R_ij| (eq. 11) from the sensor correlation matrix.

#include <Eigen/Core>

namespace tactile::ml {

struct MdsResult {
  Eigen::MatrixXd coordinates;  // N x dimensions, columns sign-fixed (largest-|.| entry positive)
  Eigen::VectorXd eigenvalues;  // all N eigenvalues of B, descending
  // Σ |negative eigenvalues| / Σ |eigenvalues|: how far d is from Euclidean (0 = Euclidean).
  double negative_eigenvalue_ratio = 0.0;
};

// B = -½ J D² J with J = I - (1/N) 1 1ᵀ; X[:, a] = v_a sqrt(max(λ_a, 0)). Throws
// tactile::Error unless `dissimilarity` is square, finite, non-negative, symmetric (to 1e-9
// relative) with a zero diagonal, and 1 <= dimensions <= N.
MdsResult classical_mds(const Eigen::MatrixXd& dissimilarity, int dimensions = 2);

// Robovie eq. 11: d_ij = -ln |R_ij| for i != j, d_ii = 0, with |R_ij| below `floor` clamped
// to `floor` (eq. 11 gives +infinity for uncorrelated or constant sensors). With
// `normalise_by_largest`, |R_ij| is first divided by the largest off-diagonal |R| (the map
// of a CLAFIC subspace vector, spec §4.8). Throws tactile::Error on a non-square or
// non-finite matrix.
Eigen::MatrixXd correlation_dissimilarity(const Eigen::MatrixXd& correlation, double floor = 1e-6,
                                          bool normalise_by_largest = false);

}  // namespace tactile::ml

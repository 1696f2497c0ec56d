#include "tactile/ml/mds.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "tactile/error.h"
#include "tactile/ml/pca.h"

namespace tactile::ml {

MdsResult classical_mds(const Eigen::MatrixXd& dissimilarity, int dimensions) {
  const std::string where = "mds";
  const Eigen::Index count = dissimilarity.rows();
  if (count < 1 || dissimilarity.cols() != count)
    throw Error(where, "dissimilarity matrix must be square and non-empty, got " +
                           std::to_string(count) + " x " + std::to_string(dissimilarity.cols()));
  if (dimensions < 1 || dimensions > count)
    throw Error(where,
                std::to_string(dimensions) + " dimensions: expected 1.." + std::to_string(count));
  if (!dissimilarity.allFinite()) throw Error(where, "dissimilarity holds a non-finite value");
  const double scale = std::max(1.0, dissimilarity.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < count; ++i) {
    if (dissimilarity(i, i) != 0.0)
      throw Error(where, "diagonal entry " + std::to_string(i) + " is not 0");
    for (Eigen::Index j = 0; j < count; ++j) {
      if (dissimilarity(i, j) < 0.0)
        throw Error(where,
                    "entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is negative");
      if (std::abs(dissimilarity(i, j) - dissimilarity(j, i)) > 1e-9 * scale)
        throw Error(where,
                    "not symmetric at (" + std::to_string(i) + ", " + std::to_string(j) + ")");
    }
  }

  // Torgerson: B = -½ J D² J, the double-centred squared dissimilarities.
  const Eigen::MatrixXd squared = dissimilarity.array().square();
  const Eigen::VectorXd row_mean = squared.rowwise().mean();
  const Eigen::VectorXd column_mean = squared.colwise().mean().transpose();
  const double grand_mean = squared.mean();
  Eigen::MatrixXd centred = squared;
  centred.colwise() -= row_mean;
  centred.rowwise() -= column_mean.transpose();
  centred.array() += grand_mean;
  const Eigen::MatrixXd b = -0.5 * centred;

  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(b);
  if (solver.info() != Eigen::Success) throw Error(where, "eigendecomposition did not converge");
  MdsResult result;
  result.eigenvalues = solver.eigenvalues().reverse();
  const Eigen::MatrixXd vectors = solver.eigenvectors().rowwise().reverse();
  result.coordinates = vectors.leftCols(dimensions) *
                       result.eigenvalues.head(dimensions).cwiseMax(0.0).cwiseSqrt().asDiagonal();
  fix_column_signs(result.coordinates);
  const double magnitude = result.eigenvalues.cwiseAbs().sum();
  result.negative_eigenvalue_ratio =
      magnitude > 0.0 ? (-result.eigenvalues.cwiseMin(0.0)).sum() / magnitude : 0.0;
  return result;
}

Eigen::MatrixXd correlation_dissimilarity(const Eigen::MatrixXd& correlation, double floor,
                                          bool normalise_by_largest) {
  const std::string where = "dissimilarity";
  const Eigen::Index count = correlation.rows();
  if (correlation.cols() != count) throw Error(where, "correlation matrix must be square");
  if (!correlation.allFinite()) throw Error(where, "correlation matrix holds a non-finite value");
  if (!(floor > 0.0 && floor <= 1.0)) throw Error(where, "floor must be in (0, 1]");
  Eigen::MatrixXd magnitude = correlation.cwiseAbs();
  magnitude.diagonal().setZero();
  if (normalise_by_largest) {
    const double largest = count > 0 ? magnitude.maxCoeff() : 0.0;
    if (largest > 0.0) magnitude /= largest;
  }
  // Robovie eq. 11: d = -ln |R|, clamped where |R| < floor.
  Eigen::MatrixXd dissimilarity = -magnitude.cwiseMax(floor).array().log();
  dissimilarity.diagonal().setZero();
  return dissimilarity;
}

}  // namespace tactile::ml

#include <gtest/gtest.h>

#include "tactile/error.h"
#include "tactile/ml/mds.h"

namespace tactile::ml {
namespace {

Eigen::MatrixXd correlation_r2() {
  Eigen::MatrixXd r(4, 4);
  r << 1, 0.9, 0.2, -0.1,  //
      0.9, 1, 0.3, 0.05,   //
      0.2, 0.3, 1, -0.8,   //
      -0.1, 0.05, -0.8, 1;
  return r;
}

TEST(ClassicalMds, ReproducesTestVectorR2) {
  const Eigen::MatrixXd d = correlation_dissimilarity(correlation_r2());
  Eigen::MatrixXd expected_d(4, 4);
  expected_d << 0, 0.105361, 1.60944, 2.30259,  //
      0.105361, 0, 1.20397, 2.99573,            //
      1.60944, 1.20397, 0, 0.223144,            //
      2.30259, 2.99573, 0.223144, 0;
  EXPECT_LT((d - expected_d).cwiseAbs().maxCoeff(), 6e-6);

  const MdsResult mds = classical_mds(d, 2);
  EXPECT_NEAR(mds.eigenvalues(0), 5.32727, 6e-6);
  EXPECT_NEAR(mds.eigenvalues(1), 0.640045, 6e-7);
  EXPECT_NEAR(mds.eigenvalues(2), 0.0, 1e-12);
  EXPECT_NEAR(mds.eigenvalues(3), -1.37305, 6e-6);
  EXPECT_NEAR(mds.negative_eigenvalue_ratio, 1.37305 / (5.32727 + 0.640045 + 1.37305), 1e-5);
  Eigen::MatrixXd coordinates(4, 2);
  coordinates << -0.809324, 0.573151,  //
      -1.3216, -0.305304,              //
      0.493104, -0.435968,             //
      1.63782, 0.16812;
  EXPECT_LT((mds.coordinates - coordinates).cwiseAbs().maxCoeff(), 6e-6);
  Eigen::MatrixXd distances(4, 4);
  distances << 0, 1.01691, 1.64762, 2.48044,  //
      1.01691, 0, 1.81941, 2.99706,           //
      1.64762, 1.81941, 0, 1.29434,           //
      2.48044, 2.99706, 1.29434, 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR((mds.coordinates.row(i) - mds.coordinates.row(j)).norm(), distances(i, j), 6e-6);
}

TEST(ClassicalMds, EuclideanDistancesAreReproducedExactly) {
  Eigen::MatrixXd points(5, 2);
  points << 0, 0, 3, 0, 3, 4, -1, 2, 5, 5;
  Eigen::MatrixXd d(5, 5);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) d(i, j) = (points.row(i) - points.row(j)).norm();
  const MdsResult mds = classical_mds(d, 2);
  EXPECT_NEAR(mds.negative_eigenvalue_ratio, 0.0, 1e-12);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      EXPECT_NEAR((mds.coordinates.row(i) - mds.coordinates.row(j)).norm(), d(i, j), 1e-9);
  // Sign convention: each column's largest-|.| entry is positive.
  for (int column = 0; column < 2; ++column) {
    Eigen::Index largest = 0;
    mds.coordinates.col(column).cwiseAbs().maxCoeff(&largest);
    EXPECT_GT(mds.coordinates(largest, column), 0.0);
  }
}

TEST(CorrelationDissimilarity, ClampsUncorrelatedPairsAndNormalisesSubspaceWeights) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(3, 3);
  r(0, 1) = r(1, 0) = 0.0;  // uncorrelated: eq. 11 would give +infinity
  r(0, 2) = r(2, 0) = 0.5;
  r(1, 2) = r(2, 1) = -0.25;
  const Eigen::MatrixXd d = correlation_dissimilarity(r);
  EXPECT_NEAR(d(0, 1), 13.8155, 5e-5);
  EXPECT_NEAR(d(0, 2), -std::log(0.5), 1e-12);
  EXPECT_NEAR(d(2, 1), -std::log(0.25), 1e-12);
  EXPECT_EQ(d(1, 1), 0.0);
  const Eigen::MatrixXd weights = correlation_dissimilarity(r, 1e-6, /*normalise_by_largest=*/true);
  EXPECT_NEAR(weights(0, 2), 0.0, 1e-12);  // the largest weight is at distance 0
  EXPECT_NEAR(weights(1, 2), -std::log(0.5), 1e-12);
}

TEST(ClassicalMds, BadInputIsRefused) {
  EXPECT_THROW(classical_mds(Eigen::MatrixXd::Zero(3, 2)), Error);
  EXPECT_THROW(classical_mds(Eigen::MatrixXd::Zero(3, 3), 4), Error);
  Eigen::MatrixXd asymmetric = Eigen::MatrixXd::Zero(3, 3);
  asymmetric(0, 1) = 1.0;
  EXPECT_THROW(classical_mds(asymmetric), Error);
  Eigen::MatrixXd negative = Eigen::MatrixXd::Zero(2, 2);
  negative(0, 1) = negative(1, 0) = -1.0;
  EXPECT_THROW(classical_mds(negative), Error);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(2, 2);
  nan(0, 1) = nan(1, 0) = std::nan("");
  EXPECT_THROW(classical_mds(nan), Error);
  EXPECT_THROW(correlation_dissimilarity(nan), Error);
}

}  // namespace
}  // namespace tactile::ml

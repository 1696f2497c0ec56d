#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/ml/pca.h"

namespace tactile::ml {
namespace {

Matrix toy_x3() {
  Matrix x(6, 3);
  x << 2, 0, 1, 4, 1, 3, 6, 1, 2, 8, 3, 5, 10, 2, 4, 12, 5, 6;
  return x;
}

TEST(Pca, ReproducesTestVectorX3) {
  const Pca pca =
      fit_pca(toy_x3(), {.components = 0, .variance_fraction = 0.90, .standardize = true});
  EXPECT_NEAR(pca.standardizer.mean(0), 7.0, 1e-12);
  EXPECT_NEAR(pca.standardizer.mean(2), 3.5, 1e-12);
  EXPECT_NEAR(pca.standardizer.scale(0), 3.74166, 5e-6);
  EXPECT_NEAR(pca.standardizer.scale(1), 1.78885, 5e-6);
  EXPECT_NEAR(pca.standardizer.scale(2), 1.87083, 5e-6);
  EXPECT_NEAR(pca.eigenvalues(0), 2.8259, 5e-5);
  EXPECT_NEAR(pca.eigenvalues(1), 0.130734, 5e-7);
  EXPECT_NEAR(pca.eigenvalues(2), 0.0433638, 5e-8);
  EXPECT_NEAR(pca.explained_ratio(0), 0.941967, 5e-7);
  EXPECT_NEAR(pca.explained_ratio(1), 0.0435781, 5e-8);
  EXPECT_NEAR(pca.explained_ratio(2), 0.0144546, 5e-8);
  EXPECT_NEAR(pca.cumulative_ratio()(1), 0.985545, 5e-7);
  EXPECT_NEAR(pca.cumulative_ratio()(2), 1.0, 1e-12);
  EXPECT_EQ(pca.kept, 1);
  Matrix loadings(3, 3);
  loadings << 0.568017, 0.820847, -0.059723,  //
      0.583053, -0.350126, 0.733117,          //
      0.580867, -0.451245, -0.677475;
  EXPECT_LT((pca.loadings - loadings).cwiseAbs().maxCoeff(), 1e-6);
  Eigen::VectorXd scores(6);
  scores << -2.18713, -0.936606, -0.943475, 0.943475, 0.61067, 2.51307;
  const Matrix projected = pca.transform(toy_x3());
  ASSERT_EQ(projected.cols(), 1);
  EXPECT_LT((projected.col(0) - scores).cwiseAbs().maxCoeff(), 6e-6);
}

TEST(Pca, KeepsComponentsByFractionOrCount) {
  EXPECT_EQ(fit_pca(toy_x3(), {.variance_fraction = 0.95}).kept, 2);
  EXPECT_EQ(fit_pca(toy_x3(), {.variance_fraction = 0.985545}).kept, 2);
  EXPECT_EQ(fit_pca(toy_x3(), {.variance_fraction = 1.0}).kept, 3);
  const Pca two = fit_pca(toy_x3(), {.components = 2});
  EXPECT_EQ(two.kept, 2);
  EXPECT_EQ(two.transform(toy_x3()).cols(), 2);
  // Scores are uncorrelated with variances equal to the eigenvalues.
  const Matrix scores = two.transform(toy_x3());
  const Matrix covariance = scores.transpose() * scores / 5.0;
  EXPECT_NEAR(covariance(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(covariance(1, 1), two.eigenvalues(1), 1e-12);
}

TEST(Pca, CentringOnlyUsesTheRawCovariance) {
  const Pca pca = fit_pca(toy_x3(), {.components = 3, .standardize = false});
  // Trace of the covariance = total variance of the raw columns (sample variances).
  EXPECT_NEAR(pca.eigenvalues.sum(), 14.0 + 3.2 + 3.5, 1e-9);
  EXPECT_EQ(pca.standardizer.scale, Eigen::Vector3d::Ones());
}

TEST(Pca, ConstantColumnsAndRoundTrip) {
  Matrix x = toy_x3();
  x.col(1).setConstant(3.0);
  const Pca pca = fit_pca(x, {.variance_fraction = 0.9});
  EXPECT_TRUE(pca.transform(x).allFinite());
  EXPECT_NEAR(pca.eigenvalues(2), 0.0, 1e-12);
  Pca restored;
  restored.load(nlohmann::json::parse(pca.save().dump()));
  EXPECT_EQ(restored.transform(x), pca.transform(x));
  EXPECT_EQ(restored.kept, pca.kept);
}

TEST(Pca, BadInputIsRefused) {
  EXPECT_THROW(fit_pca(Matrix::Ones(1, 3)), Error);
  EXPECT_THROW(fit_pca(Matrix::Ones(4, 3)), Error);  // nothing varies
  Matrix x = toy_x3();
  x(2, 2) = std::nan("");
  EXPECT_THROW(fit_pca(x), Error);
  EXPECT_THROW(fit_pca(toy_x3(), {.components = 4}), Error);
  EXPECT_THROW(fit_pca(toy_x3(), {.variance_fraction = 0.0}), Error);
  const Pca pca = fit_pca(toy_x3());
  EXPECT_THROW(pca.transform(Matrix::Ones(2, 2)), Error);
  EXPECT_THROW(Pca().transform(toy_x3()), Error);
}

}  // namespace
// Fewer rows than features: the components come from the N x N Gram matrix; the same
// eigenvalues and scores as the P x P covariance gives, directly computed here.
TEST(Pca, WithFewerRowsThanFeaturesGivesTheCovariancesComponents) {
  Matrix x(12, 30);
  std::srand(5);
  x.setRandom();
  x.col(3) = 2.0 * x.col(1) + 0.1 * x.col(7);
  const Pca pca = fit_pca(x, {.components = 3, .variance_fraction = 0.9, .standardize = true});
  const Matrix z = pca.standardizer.transform(x);
  const Eigen::SelfAdjointEigenSolver<Matrix> direct((z.transpose() * z) / 11.0);
  const Vector eigenvalues = direct.eigenvalues().reverse();
  ASSERT_EQ(pca.eigenvalues.size(), 30);
  for (int k = 0; k < 11; ++k) EXPECT_NEAR(pca.eigenvalues(k), eigenvalues(k), 1e-9) << k;
  for (int k = 11; k < 30; ++k) EXPECT_EQ(pca.eigenvalues(k), 0.0);
  Matrix loadings = direct.eigenvectors().rowwise().reverse().leftCols(3);
  fix_column_signs(loadings);
  EXPECT_LT((pca.transform(x) - z * loadings).cwiseAbs().maxCoeff(), 1e-9);
  // By variance: never more components than have variance.
  const Pca all = fit_pca(x, {.components = 0, .variance_fraction = 1.0, .standardize = true});
  EXPECT_LE(all.kept, 11);
  EXPECT_EQ(all.transform(x).cols(), all.kept);
}

}  // namespace tactile::ml

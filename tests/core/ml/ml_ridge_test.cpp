// The ridge classifier with leave-one-out choice of alpha (issue 26).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/ridge.h"

namespace tactile::ml {
namespace {

// Leave-one-out by refitting: on the z-scores of every row (as the classifier's LOO is),
// ridge with an unpenalised intercept on all rows but one, the squared error of its
// prediction of the one left out, over every row and one-vs-rest target.
double ridge_test_brute_loo(const Matrix& x, const std::vector<int>& y, int classes, double alpha) {
  Standardizer standardizer;
  standardizer.fit(x);
  const Matrix z = standardizer.transform(x);
  const Eigen::Index n = z.rows();
  Matrix targets = Matrix::Constant(n, classes, -1.0);
  for (Eigen::Index row = 0; row < n; ++row) targets(row, y[static_cast<size_t>(row)]) = 1.0;
  double squares = 0.0;
  for (Eigen::Index out = 0; out < n; ++out) {
    Matrix train(n - 1, z.cols());
    Matrix train_targets(n - 1, classes);
    for (Eigen::Index row = 0, kept = 0; row < n; ++row) {
      if (row == out) continue;
      train.row(kept) = z.row(row);
      train_targets.row(kept++) = targets.row(row);
    }
    const Eigen::RowVectorXd column_mean = train.colwise().mean();
    const Eigen::RowVectorXd target_mean = train_targets.colwise().mean();
    const Matrix centred = train.rowwise() - column_mean;
    const Matrix system =
        centred.transpose() * centred + alpha * Matrix::Identity(z.cols(), z.cols());
    const Matrix weights =
        system.ldlt().solve(centred.transpose() * (train_targets.rowwise() - target_mean));
    const Eigen::RowVectorXd predicted = (z.row(out) - column_mean) * weights + target_mean;
    squares += (targets.row(out) - predicted).squaredNorm();
  }
  return squares / static_cast<double>(n * classes);
}

TEST(RidgeClassifier, SeparatesLinearlySeparableClasses) {
  Matrix centres(3, 2);
  centres << 0, 0, 6, 0, 0, 6;
  const toy::LabelledSet train = toy::blobs(centres, 20, 0.7, 1);
  const toy::LabelledSet test = toy::blobs(centres, 20, 0.7, 2);
  RidgeClassifier classifier;
  classifier.fit(train.x, train.y, 3, 0);
  EXPECT_EQ(toy::accuracy(classifier.predict(train.x), train.y), 1.0);
  EXPECT_GE(toy::accuracy(classifier.predict(test.x), test.y), 0.95);
  EXPECT_EQ(classifier.scores(test.x).cols(), 3);
}

// Both ways of computing the hat matrix: columns <= rows (Z'Z) and columns > rows (ZZ').
TEST(RidgeClassifier, ChoosesTheAlphaOfLeastLeaveOneOutErrorByRefitting) {
  for (const Eigen::Index columns : {3, 25}) {
    std::mt19937_64 engine(static_cast<uint64_t>(columns));
    Matrix x(14, columns);
    for (Eigen::Index k = 0; k < x.size(); ++k) x.data()[k] = toy::normal(engine);
    std::vector<int> y;
    for (Eigen::Index row = 0; row < x.rows(); ++row) {
      y.push_back(static_cast<int>(row % 3));
      x(row, 0) += 1.5 * static_cast<double>(row % 3);
    }
    RidgeClassifier classifier(Parameters::parse("alpha_min=0.01,alpha_max=1000,alphas=6", "test"));
    classifier.fit(x, y, 3, 0);
    const std::vector<double> grid = classifier.alpha_grid();
    ASSERT_EQ(grid.size(), 6u);
    size_t best = 0;
    std::vector<double> brute;
    for (size_t index = 0; index < grid.size(); ++index) {
      brute.push_back(ridge_test_brute_loo(x, y, 3, grid[index]));
      EXPECT_NEAR(classifier.loo_errors()[index], brute[index], 1e-9 * brute[index])
          << columns << " columns, alpha " << grid[index];
      if (brute[index] < brute[best]) best = index;
    }
    EXPECT_EQ(classifier.alpha(), grid[best]) << columns << " columns";
  }
}

TEST(RidgeClassifier, SavedModelScoresTheSame) {
  Matrix centres(2, 3);
  centres << 0, 0, 0, 2, 1, 0;
  const toy::LabelledSet set = toy::blobs(centres, 15, 1.0, 4);
  RidgeClassifier classifier;
  classifier.fit(set.x, set.y, 2, 0);
  const std::unique_ptr<Classifier> restored = load_classifier(save_classifier(classifier));
  EXPECT_EQ(restored->name(), "ridge");
  EXPECT_EQ(restored->scores(set.x), classifier.scores(set.x));
  EXPECT_EQ(dynamic_cast<RidgeClassifier&>(*restored).alpha(), classifier.alpha());
  EXPECT_EQ(specification_of(*restored), "ridge:alpha_max=1000,alpha_min=0.001,alphas=10");
}

TEST(RidgeClassifier, BadParametersAreNamed) {
  EXPECT_THROW(make_classifier("ridge:alphas=0"), Error);
  EXPECT_THROW(make_classifier("ridge:alpha_min=-1"), Error);
  EXPECT_THROW(make_classifier("ridge:alpha_min=10,alpha_max=1"), Error);
  try {
    make_classifier("ridge:alpha=1");
    FAIL() << "unknown parameter accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("alpha"), std::string::npos);
  }
  EXPECT_THROW(RidgeClassifier().scores(Matrix::Zero(1, 2)), Error);
}

}  // namespace
}  // namespace tactile::ml

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ml_prob_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/gaussian.h"

namespace tactile::ml {
namespace {

// TV F4: class A = 5 points around (0.5, 0.5), class B = 4 points around (3.5, 4).
void fur_toy(Matrix& x, std::vector<int>& y) {
  x.resize(9, 2);
  x << 0, 0, 1, 0, 0, 1, 1, 1, 0.5, 0.5,  //
      3, 3, 4, 3, 3, 5, 4, 5;
  y = {0, 0, 0, 0, 0, 1, 1, 1, 1};
}

Matrix row(double a, double b) {
  Matrix query(1, 2);
  query << a, b;
  return query;
}

TEST(GaussianMaximumLikelihood, ReproducesFurToyVectorF4) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  const auto& classes = classifier.classes();
  EXPECT_NEAR(classes[0].mean(0), 0.5, 1e-12);
  EXPECT_NEAR(classes[1].mean(1), 4.0, 1e-12);
  // ML covariance (1/N) plus the ridge 1e-6 · trace/d.
  EXPECT_NEAR(classes[0].covariance(0, 0), 0.2 * (1 + 1e-6), 1e-12);
  EXPECT_NEAR(classes[0].covariance(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(classes[1].covariance(0, 0), 0.250001, 5e-7);
  EXPECT_NEAR(classes[1].covariance(1, 1), 1.0, 1e-6);

  const Matrix query = row(2, 2);
  const Matrix log_likelihoods = classifier.log_likelihoods(query);
  EXPECT_NEAR(log_likelihoods(0, 0), -11.4784, 6e-5);
  EXPECT_NEAR(log_likelihoods(0, 1), -7.64472, 6e-6);
  const Matrix posterior = classifier.scores(query);
  EXPECT_NEAR(posterior(0, 0), 0.0211713, 1e-7);
  EXPECT_NEAR(posterior(0, 1), 0.978829, 1e-6);
  EXPECT_NEAR(classifier.significance(query)(0), 0.978829, 1e-6);
  EXPECT_EQ(classifier.predict(query), std::vector<int>{1});
}

TEST(GaussianMaximumLikelihood, PosteriorsSumToOneAndFollowTheNearerClass) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  Matrix queries(3, 2);
  queries << 0.4, 0.6, 3.6, 4.2, 40, -30;
  const Matrix posterior = classifier.scores(queries);
  ASSERT_EQ(posterior.rows(), 3);
  ASSERT_EQ(posterior.cols(), 2);
  for (Eigen::Index r = 0; r < 3; ++r) EXPECT_NEAR(posterior.row(r).sum(), 1.0, 1e-12);
  EXPECT_TRUE(posterior.allFinite());
  EXPECT_EQ(classifier.predict(queries.topRows(2)), (std::vector<int>{0, 1}));
}

// Found by UBSan in the workbench's Train all: a fold with nothing to score handed an empty
// matrix to Eigen's triangular solve.
TEST(GaussianMaximumLikelihood, NoRowsToScoreGiveNoScores) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  const Matrix none(0, 2);
  EXPECT_EQ(classifier.scores(none).rows(), 0);
  EXPECT_TRUE(classifier.predict(none).empty());
}

TEST(GaussianMaximumLikelihood, ClassWithOneSampleGetsTheGlobalVarianceRidge) {
  Matrix x(4, 2);
  x << 0, 0, 2, 0, 0, 4, 10, 10;
  const std::vector<int> y = {0, 0, 0, 1};
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  // Spec §3.6 edge case: Σ = λ I, λ = 1e-6 · mean of the global (population) variances.
  const double variance_x = (0 + 4 + 0 + 100) / 4.0 - std::pow(12 / 4.0, 2);
  const double variance_y = (0 + 0 + 16 + 100) / 4.0 - std::pow(14 / 4.0, 2);
  const double lambda = 1e-6 * (variance_x + variance_y) / 2.0;
  EXPECT_NEAR(classifier.classes()[1].covariance(0, 0), lambda, 1e-15);
  EXPECT_NEAR(classifier.classes()[1].covariance(0, 1), 0.0, 1e-15);
  const Matrix scores = classifier.scores(x);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(classifier.predict(x), y);
}

TEST(GaussianMaximumLikelihood, ConstantFeatureInAClassIsRegularisedNotNaN) {
  // Feature 1 is constant within each class (like a segment duration): Σ singular.
  Matrix x(6, 2);
  x << 0, 5, 1, 5, 2, 5, 10, 7, 11, 7, 12, 7;
  const std::vector<int> y = {0, 0, 0, 1, 1, 1};
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  Matrix queries(2, 2);
  queries << 1.5, 5, 10.5, 6.9;
  const Matrix scores = classifier.scores(queries);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(classifier.predict(queries), (std::vector<int>{0, 1}));
}

TEST(GaussianMaximumLikelihood, MoreFeaturesThanSamplesStillSeparatesTheClasses) {
  std::mt19937_64 random(7);
  Matrix x(6, 12);
  for (Eigen::Index r = 0; r < 6; ++r)
    for (Eigen::Index c = 0; c < 12; ++c)
      x(r, c) = test_data::standard_normal(random) + (r < 3 ? 0.0 : 6.0);
  const std::vector<int> y = {0, 0, 0, 1, 1, 1};
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 2, 0);
  EXPECT_TRUE(classifier.scores(x).allFinite());
  EXPECT_EQ(classifier.predict(x), y);
}

TEST(GaussianMaximumLikelihood, BadInputNamesWhatAndWhere) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  GaussianMaximumLikelihood classifier;
  Matrix bad = x;
  bad(2, 1) = std::nan("");
  try {
    classifier.fit(bad, y, 2, 0);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "gaussian-ml");
    EXPECT_NE(error.message().find("row 2, feature 1"), std::string::npos) << error.what();
  }
  EXPECT_THROW(classifier.fit(Matrix(0, 2), {}, 2, 0), Error);
  EXPECT_THROW(classifier.fit(x, std::vector<int>(9, 2), 2, 0), Error);  // label out of range
  EXPECT_THROW(classifier.fit(x, std::vector<int>(4, 0), 2, 0), Error);  // count mismatch
  EXPECT_THROW(classifier.scores(row(1, 1)), Error);                     // not fitted
  classifier.fit(x, y, 2, 0);
  EXPECT_THROW(classifier.scores(Matrix::Zero(1, 3)), Error);
  EXPECT_THROW(classifier.scores(row(INFINITY, 0)), Error);
  EXPECT_THROW(GaussianMaximumLikelihood(Parameters::parse("ridg=1", "--classifier")), Error);
  EXPECT_THROW(GaussianMaximumLikelihood(Parameters::parse("ridge=-1", "--classifier")), Error);
}

TEST(GaussianMaximumLikelihood, AbsentClassScoresZeroAndIsNeverPredicted) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  for (int& label : y) label *= 2;  // classes 0 and 2 of 3
  GaussianMaximumLikelihood classifier;
  classifier.fit(x, y, 3, 0);
  const Matrix scores = classifier.scores(x);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(scores.col(1).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(classifier.predict(x), y);
}

TEST(GaussianMaximumLikelihood, SaveLoadRoundTripGivesIdenticalScores) {
  Matrix x;
  std::vector<int> y;
  fur_toy(x, y);
  GaussianMaximumLikelihood classifier(Parameters::parse("ridge=1e-4", "test"));
  classifier.fit(x, y, 3, 0);  // class 2 absent
  GaussianMaximumLikelihood restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  Matrix queries(3, 2);
  queries << 2, 2, 0.3, 0.9, 5, 1;
  EXPECT_EQ(restored.scores(queries), classifier.scores(queries));
  EXPECT_EQ(restored.log_likelihoods(queries), classifier.log_likelihoods(queries));
  EXPECT_EQ(classifier.parameters().number("ridge", 0.0), 1e-4);
  EXPECT_THROW(restored.load(nlohmann::json{{"classes", 3}}), Error);
}

//---- qda --------------------------------------------------------------------------------

TEST(QuadraticDiscriminant, PosteriorWeighsUnbiasedDensitiesByEmpiricalPriors) {
  Matrix x(5, 1);
  x << 0, 2, 4, 5, 6;
  const std::vector<int> y = {0, 0, 1, 1, 1};
  QuadraticDiscriminant classifier;
  classifier.fit(x, y, 2, 0);
  // Class 0: mean 1, unbiased variance 2; class 1: mean 5, variance 1; priors 2/5, 3/5;
  // both variances carry the ridge 1e-6 · variance.
  const auto log_joint = [](double prior, double mean, double variance, double value) {
    variance *= 1 + 1e-6;
    return std::log(prior) - 0.5 * std::log(2 * std::numbers::pi * variance) -
           (value - mean) * (value - mean) / (2 * variance);
  };
  const double a = log_joint(0.4, 1, 2, 3);
  const double b = log_joint(0.6, 5, 1, 3);
  Matrix query(1, 1);
  query << 3;
  const Matrix posterior = classifier.scores(query);
  EXPECT_NEAR(posterior(0, 0), 1 / (1 + std::exp(b - a)), 1e-12);
  EXPECT_NEAR(posterior(0, 1), 1 / (1 + std::exp(a - b)), 1e-12);
  EXPECT_EQ(classifier.predict(query), std::vector<int>{0});

  QuadraticDiscriminant uniform(Parameters::parse("priors=uniform", "test"));
  uniform.fit(x, y, 2, 0);
  const double a_uniform = log_joint(0.5, 1, 2, 3);
  const double b_uniform = log_joint(0.5, 5, 1, 3);
  EXPECT_NEAR(uniform.scores(query)(0, 0), 1 / (1 + std::exp(b_uniform - a_uniform)), 1e-12);
}

TEST(QuadraticDiscriminant, AgreesWithTheBayesRuleOnGaussianBlobs) {
  Eigen::MatrixXd covariance_a(2, 2), covariance_b(2, 2);
  covariance_a << 1.0, 0.6, 0.6, 1.0;
  covariance_b << 2.0, -0.5, -0.5, 0.4;
  const std::vector<test_data::Blob> blobs = {{Eigen::Vector2d(0, 0), covariance_a},
                                              {Eigen::Vector2d(1.5, 1.0), covariance_b}};
  std::mt19937_64 random(11);
  Matrix train, test;
  std::vector<int> train_labels, test_labels;
  test_data::draw_classes(blobs, 1500, random, train, train_labels);
  test_data::draw_classes(blobs, 1000, random, test, test_labels);
  QuadraticDiscriminant classifier;
  classifier.fit(train, train_labels, 2, 0);
  const std::vector<int> predicted = classifier.predict(test);
  EXPECT_GE(test_data::agreement(predicted, test_data::bayes_rule(blobs, test)), 0.98);
  const Matrix scores = classifier.scores(test);
  EXPECT_LT((scores.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
}

TEST(QuadraticDiscriminant, SingularAndSingleSampleClassesAreRegularised) {
  // Class 0 lies on a line (rank-1 covariance), class 1 has one sample, and there are more
  // features (3) than class-0 samples could span.
  Matrix x(4, 3);
  x << 0, 0, 1, 1, 1, 1, 2, 2, 1, 9, -3, 4;
  const std::vector<int> y = {0, 0, 0, 1};
  QuadraticDiscriminant classifier;
  classifier.fit(x, y, 2, 0);
  const Matrix scores = classifier.scores(x);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(classifier.predict(x), y);
  QuadraticDiscriminant restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  EXPECT_EQ(restored.scores(x), scores);
  EXPECT_EQ(restored.parameters().text("priors", ""), "empirical");
}

// Found against scikit-learn (bench/compare): a ridge of 1e-6 · tr(Σ)/d on every feature
// buried a feature of small units under one of large units, so a unit change flipped decisions.
TEST(QuadraticDiscriminant, DecisionsDoNotDependOnFeatureUnits) {
  // Feature 0: noise of large units, the same in both classes. Feature 1: small units, and
  // the only one that separates the classes (means 0 and 0.02, deviation 0.004).
  Eigen::MatrixXd covariance(2, 2);
  covariance << 1e6, 0.0, 0.0, 1.6e-5;
  const std::vector<test_data::Blob> blobs = {{Eigen::Vector2d(0, 0), covariance},
                                              {Eigen::Vector2d(0, 0.02), covariance}};
  std::mt19937_64 random(5);
  Matrix train, test;
  std::vector<int> train_labels, test_labels;
  test_data::draw_classes(blobs, 400, random, train, train_labels);
  test_data::draw_classes(blobs, 400, random, test, test_labels);
  QuadraticDiscriminant classifier;
  classifier.fit(train, train_labels, 2, 0);
  const std::vector<int> predicted = classifier.predict(test);
  EXPECT_GE(test_data::agreement(predicted, test_labels), 0.95);

  // The noise feature in a unit 1000 times smaller: the same decisions.
  Matrix train_rescaled = train, test_rescaled = test;
  train_rescaled.col(0) *= 1000.0;
  test_rescaled.col(0) *= 1000.0;
  QuadraticDiscriminant rescaled;
  rescaled.fit(train_rescaled, train_labels, 2, 0);
  EXPECT_EQ(rescaled.predict(test_rescaled), predicted);
}

TEST(QuadraticDiscriminant, RejectsUnknownParametersAndNaN) {
  EXPECT_THROW(QuadraticDiscriminant(Parameters::parse("prior=uniform", "test")), Error);
  EXPECT_THROW(QuadraticDiscriminant(Parameters::parse("priors=flat", "test")), Error);
  Matrix x(2, 1);
  x << 1, std::nan("");
  QuadraticDiscriminant classifier;
  EXPECT_THROW(classifier.fit(x, {0, 1}, 2, 0), Error);
}

}  // namespace
}  // namespace tactile::ml

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ml_prob_test_data.h"
#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/naive_bayes.h"

namespace tactile::ml {
namespace {

double normal_density(double value, double mean, double variance) {
  return std::exp(-(value - mean) * (value - mean) / (2 * variance)) /
         std::sqrt(2 * std::numbers::pi * variance);
}

std::vector<test_data::Blob> independent_blobs() {
  return {{Eigen::Vector2d(0, 0), Eigen::Vector2d(1.0, 0.5).asDiagonal()},
          {Eigen::Vector2d(1.2, 1.0), Eigen::Vector2d(0.3, 2.0).asDiagonal()},
          {Eigen::Vector2d(-1.0, 2.0), Eigen::Vector2d(0.6, 0.6).asDiagonal()}};
}

//---- gaussian-nb --------------------------------------------------------------------------

TEST(GaussianNaiveBayes, PosteriorUsesUnbiasedVariancesAndEmpiricalPriors) {
  const Matrix x = toy::column({0, 2, 4, 5, 6});
  const std::vector<int> y = {0, 0, 1, 1, 1};
  GaussianNaiveBayes classifier;
  classifier.fit(x, y, 2, 0);
  const double smoothing = 1e-9 * 4.64;  // largest population variance of a feature
  EXPECT_NEAR(classifier.variances()(0, 0), 2.0 + smoothing, 1e-15);
  EXPECT_NEAR(classifier.variances()(1, 0), 1.0 + smoothing, 1e-15);
  const double joint_a = 0.4 * normal_density(3, 1, 2 + smoothing);
  const double joint_b = 0.6 * normal_density(3, 5, 1 + smoothing);
  const Matrix posterior = classifier.scores(toy::column({3}));
  EXPECT_NEAR(posterior(0, 0), joint_a / (joint_a + joint_b), 1e-12);
  EXPECT_NEAR(posterior(0, 1), joint_b / (joint_a + joint_b), 1e-12);
}

TEST(GaussianNaiveBayes, MultipliesTheFeatureDensities) {
  Matrix x(4, 2);
  x << 0, 10, 2, 14, 5, 0, 7, 1;
  const std::vector<int> y = {0, 0, 1, 1};
  GaussianNaiveBayes classifier(Parameters::parse("priors=uniform", "test"));
  classifier.fit(x, y, 2, 0);
  const Matrix& variances = classifier.variances();
  Matrix query(1, 2);
  query << 3, 6;
  const double joint_a =
      normal_density(3, 1, variances(0, 0)) * normal_density(6, 12, variances(0, 1));
  const double joint_b =
      normal_density(3, 6, variances(1, 0)) * normal_density(6, 0.5, variances(1, 1));
  EXPECT_NEAR(classifier.scores(query)(0, 1), joint_b / (joint_a + joint_b), 1e-12);
  EXPECT_NEAR(variances(0, 1), 8.0, 1e-6);
}

TEST(GaussianNaiveBayes, AgreesWithTheBayesRuleOnIndependentBlobs) {
  const auto blobs = independent_blobs();
  std::mt19937_64 random(3);
  Matrix train, test;
  std::vector<int> train_labels, test_labels;
  test_data::draw_classes(blobs, 1500, random, train, train_labels);
  test_data::draw_classes(blobs, 700, random, test, test_labels);
  GaussianNaiveBayes classifier;
  classifier.fit(train, train_labels, 3, 0);
  EXPECT_GE(test_data::agreement(classifier.predict(test), test_data::bayes_rule(blobs, test)),
            0.98);
  const Matrix scores = classifier.scores(test);
  EXPECT_LT((scores.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
}

TEST(GaussianNaiveBayes, ConstantFeatureAndSingleSampleClassAreRegularised) {
  Matrix x(5, 2);
  x << 0, 3, 1, 3, 2, 3, 10, 4, 20, 7;
  const std::vector<int> y = {0, 0, 0, 1,
                              2};  // feature 1 constant in class 0; class 1, 2 one sample
  GaussianNaiveBayes classifier;
  classifier.fit(x, y, 3, 0);
  const double global_largest = 57.44;  // population variance of feature 0
  EXPECT_NEAR(classifier.variances()(0, 1), 1e-9 * global_largest, 1e-15);
  // One-sample classes take the pooled within-class variance (class 0: 1 and 0).
  EXPECT_NEAR(classifier.variances()(1, 0), 1.0 + 1e-9 * global_largest, 1e-12);
  const Matrix scores = classifier.scores(x);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(classifier.predict(x), y);
}

TEST(GaussianNaiveBayes, RoundTripAndBadInput) {
  const auto blobs = independent_blobs();
  std::mt19937_64 random(5);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 20, random, x, y);
  GaussianNaiveBayes classifier;
  classifier.fit(x, y, 4, 0);  // class 3 absent
  GaussianNaiveBayes restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  EXPECT_EQ(restored.scores(x), classifier.scores(x));
  EXPECT_EQ(classifier.scores(x).col(3).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_THROW(GaussianNaiveBayes(Parameters::parse("smoothing=1", "test")), Error);
  EXPECT_THROW(GaussianNaiveBayes(Parameters::parse("var_smoothing=0", "test")), Error);
  x(3, 0) = std::nan("");
  EXPECT_THROW(classifier.fit(x, y, 3, 0), Error);
  EXPECT_THROW(classifier.scores(x), Error);
}

//---- kernel-nb ----------------------------------------------------------------------------

TEST(KernelNaiveBayes, DefaultWidthIsMatlabsSilvermanRule) {
  // MATLAB ksdensity([1 3 2 5]) reports bandwidth 1.1901: MAD 1 / 0.6745 · (4/12)^(1/5).
  EXPECT_NEAR(silverman_width(Eigen::Vector4d(1, 3, 2, 5)), 1.1901, 5e-5);
  EXPECT_NEAR(silverman_width(Eigen::Vector4d(1, 3, 2, 5)), std::pow(1.0 / 3.0, 0.2) / 0.6745,
              1e-12);
  EXPECT_EQ(silverman_width(Eigen::Vector3d(2, 2, 7)), 0.0);  // MAD 0
}

TEST(KernelNaiveBayes, DensityIsTheMeanOfNormalKernels) {
  const Matrix x = toy::column({0, 1, 3});
  const std::vector<int> y = {0, 0, 1};
  KernelNaiveBayes classifier(Parameters::parse("width=0.5", "test"));
  classifier.fit(x, y, 2, 0);
  const double density_a = (normal_density(2, 0, 0.25) + normal_density(2, 1, 0.25)) / 2;
  const double density_b = normal_density(2, 3, 0.25);
  const double joint_a = 2.0 / 3.0 * density_a;
  const double joint_b = 1.0 / 3.0 * density_b;
  EXPECT_NEAR(classifier.scores(toy::column({2}))(0, 0), joint_a / (joint_a + joint_b), 1e-12);
}

TEST(KernelNaiveBayes, WidthsFallBackWhenAClassFeatureIsConstant) {
  Matrix x(8, 2);
  x << 1, 4, 3, 4, 2, 4, 5, 4,  //
      10, 0, 11, 1, 12, 3, 14, 2;
  const std::vector<int> y = {0, 0, 0, 0, 1, 1, 1, 1};
  KernelNaiveBayes classifier;
  classifier.fit(x, y, 2, 0);
  EXPECT_NEAR(classifier.widths()(0, 0), std::pow(1.0 / 3.0, 0.2) / 0.6745, 1e-12);
  // Feature 1 is constant in class 0: it takes the width of feature 1 over all rows.
  Eigen::VectorXd all_feature_1 = x.col(1);
  EXPECT_NEAR(classifier.widths()(0, 1), silverman_width(all_feature_1), 1e-12);
  EXPECT_GT(classifier.widths()(0, 1), 0.0);
  EXPECT_EQ(classifier.predict(x), y);
}

TEST(KernelNaiveBayes, AgreesWithTheBayesRuleOnIndependentBlobs) {
  const auto blobs = independent_blobs();
  std::mt19937_64 random(9);
  Matrix train, test;
  std::vector<int> train_labels, test_labels;
  test_data::draw_classes(blobs, 800, random, train, train_labels);
  test_data::draw_classes(blobs, 300, random, test, test_labels);
  KernelNaiveBayes classifier;
  classifier.fit(train, train_labels, 3, 0);
  EXPECT_GE(test_data::agreement(classifier.predict(test), test_data::bayes_rule(blobs, test)),
            0.95);
}

TEST(KernelNaiveBayes, FarQueriesStayFiniteAndRoundTripIsExact) {
  const auto blobs = independent_blobs();
  std::mt19937_64 random(13);
  Matrix x;
  std::vector<int> y;
  test_data::draw_classes(blobs, 30, random, x, y);
  KernelNaiveBayes classifier;
  classifier.fit(x, y, 3, 0);
  Matrix far(2, 2);
  far << 1e4, -1e4, 300, 0;
  const Matrix scores = classifier.scores(far);
  EXPECT_TRUE(scores.allFinite());
  EXPECT_NEAR(scores.row(0).sum(), 1.0, 1e-12);
  KernelNaiveBayes restored;
  restored.load(nlohmann::json::parse(classifier.save().dump()));
  EXPECT_EQ(restored.scores(x), classifier.scores(x));
  EXPECT_EQ(restored.parameters().text("width", ""), "0");
  EXPECT_THROW(KernelNaiveBayes(Parameters::parse("bandwidth=1", "test")), Error);
  EXPECT_THROW(KernelNaiveBayes(Parameters::parse("width=-1", "test")), Error);
  EXPECT_THROW(classifier.fit(Matrix(0, 2), {}, 3, 0), Error);
}

}  // namespace
}  // namespace tactile::ml

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <tuple>

#include "tactile/error.h"
#include "tactile/ml/clafic.h"

namespace tactile::ml {
namespace {

//---- Spec test vector R3 (D = 4, two classes)

// Rows = training vectors (the columns of X_k in the spec).
Matrix class_one_samples() {
  Matrix samples(3, 4);
  samples << 1, 0.9, 0.1, 0,  //
      0.9, 1, 0, 0.1,         //
      1, 1, 0.2, 0.1;
  return samples;
}

Matrix class_two_samples() {
  Matrix samples(3, 4);
  samples << 0.1, 0, 1, 0.8,  //
      0, 0.2, 0.9, 1,         //
      0.2, 0.1, 1, 1;
  return samples;
}

Matrix row_of(std::initializer_list<double> values) {
  Matrix row(1, static_cast<Eigen::Index>(values.size()));
  Eigen::Index column = 0;
  for (const double value : values) row(0, column++) = value;
  return row;
}

ClaficOptions options_with(double c1, double c2 = 0.0) {
  ClaficOptions options;
  options.c1 = c1;
  options.c2 = c2;
  return options;
}

void expect_vector_near(const Vector& actual, std::initializer_list<double> expected,
                        double tolerance) {
  ASSERT_EQ(actual.size(), static_cast<Eigen::Index>(expected.size()));
  Eigen::Index index = 0;
  for (const double value : expected) {
    EXPECT_NEAR(actual(index), value, tolerance) << "entry " << index;
    ++index;
  }
}

TEST(ClaficSubspace, SingularValuesAndRatiosMatchVectorR3) {
  const ClaficSubspace one = fit_clafic_subspace(class_one_samples(), options_with(0.95));
  expect_vector_near(one.singular_values, {2.37796, 0.154181, 0.107381}, 5e-6);
  expect_vector_near(one.cumulative_ratio, {0.993796, 0.997974, 1.0}, 5e-7);
  EXPECT_EQ(one.dimension, 1);
  expect_vector_near(one.basis.col(0), {0.704322, 0.704277, 0.0743157, 0.0490111}, 5e-7);

  const ClaficSubspace two = fit_clafic_subspace(class_two_samples(), options_with(0.95));
  expect_vector_near(two.singular_values, {2.34273, 0.21904, 0.11668}, 5e-6);
  expect_vector_near(two.cumulative_ratio, {0.988902, 0.997547, 1.0}, 5e-7);
  EXPECT_EQ(two.dimension, 1);
  expect_vector_near(two.basis.col(0), {0.0752916, 0.0752115, 0.713944, 0.692069}, 5e-7);
}

TEST(ClaficSubspace, HigherContributionThresholdsKeepMoreDirections) {
  const Matrix x = row_of({0.8, 0.7, 0.3, 0.2});
  for (const auto& [c1, dimension, first, second] :
       {std::tuple{0.995, 2, 1.21702, 0.220013}, std::tuple{1.0, 3, 1.24968, 0.753791}}) {
    const ClaficSubspace one = fit_clafic_subspace(class_one_samples(), options_with(c1));
    const ClaficSubspace two = fit_clafic_subspace(class_two_samples(), options_with(c1));
    EXPECT_EQ(one.dimension, dimension) << "c1 " << c1;
    EXPECT_EQ(two.dimension, dimension) << "c1 " << c1;
    EXPECT_NEAR(clafic_discrimination(x, one.basis)(0), first, 5e-6) << "c1 " << c1;
    EXPECT_NEAR(clafic_discrimination(x, two.basis)(0), second, 5e-7) << "c1 " << c1;
    // The basis stays orthonormal however many directions are kept.
    EXPECT_TRUE((one.basis.transpose() * one.basis)
                    .isApprox(Matrix::Identity(dimension, dimension), 1e-12));
  }
}

TEST(ClaficSubspace, SingularContributionModeSumsSingularValuesNotEnergies) {
  ClaficOptions options = options_with(0.95);
  options.contribution = ClaficOptions::Contribution::kSingular;
  // sum d_j / sum d: class 1 0.9009, 0.9593, 1 -> m = 2 where the energy ratio gives m = 1.
  const ClaficSubspace one = fit_clafic_subspace(class_one_samples(), options);
  expect_vector_near(one.cumulative_ratio, {2.37796 / 2.639522, 2.532141 / 2.639522, 1.0}, 5e-6);
  EXPECT_EQ(one.dimension, 2);
}

TEST(ClaficSubspace, SensorBankThresholdMatchesVectorR3) {
  const ClaficSubspace one = fit_clafic_subspace(class_one_samples(), options_with(0.95, 1.0));
  const ClaficSubspace two = fit_clafic_subspace(class_two_samples(), options_with(0.95, 1.0));
  ASSERT_EQ(one.bank_basis.cols(), 1);
  expect_vector_near(one.bank_basis.col(0), {0.707129, 0.707084, 0, 0}, 5e-7);
  expect_vector_near(two.bank_basis.col(0), {0, 0, 0.718021, 0.696021}, 5e-7);
  EXPECT_EQ(one.needed_features, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(two.needed_features, (std::vector<int64_t>{2, 3}));
  const Matrix x = row_of({0.8, 0.7, 0.3, 0.2});
  EXPECT_NEAR(clafic_discrimination(x, one.bank_basis)(0), 1.125, 5e-6);
  EXPECT_NEAR(clafic_discrimination(x, two.bank_basis)(0), 0.125749, 5e-7);
}

TEST(ClaficSubspace, AllZeroTrainingVectorsSpanNothing) {
  const ClaficSubspace empty = fit_clafic_subspace(Matrix::Zero(3, 5), options_with(0.5));
  EXPECT_EQ(empty.dimension, 0);
  EXPECT_EQ(empty.basis.rows(), 5);
  EXPECT_EQ(empty.basis.cols(), 0);
  EXPECT_TRUE(empty.needed_features.empty());
  EXPECT_EQ(clafic_discrimination(row_of({1, 2, 3, 4, 5}), empty.basis)(0), 0.0);
}

TEST(ClaficDecision, FidelityRatioBelowOneOverTauAnswersUnknown) {
  Vector clear(2), close(2), lonely(3), silent(2);
  clear << 1.18494, 0.21667;    // ratio 5.47 > 1.0526
  close << 0.586699, 0.605685;  // ratio 1.032 < 1.0526 (R3 query x2)
  lonely << 0.0, 0.3, 0.0;      // DF_second = 0 and DF_l > 0 -> accepted
  silent << 0.0, 0.0;
  EXPECT_EQ(clafic_decide(clear, 0.95), 0);
  EXPECT_EQ(clafic_decide(close, 0.95), kUnknownClass);
  EXPECT_EQ(clafic_decide(close, 0.99), 1);  // 1/0.99 = 1.0101 < 1.032
  EXPECT_EQ(clafic_decide(lonely, 0.95), 1);
  EXPECT_EQ(clafic_decide(silent, 0.95), kUnknownClass);
}

//---- The classifier

Matrix r3_training(std::vector<int>& labels) {
  Matrix x(6, 4);
  x << class_one_samples(), class_two_samples();
  labels = {0, 0, 0, 1, 1, 1};
  return x;
}

TEST(ClaficClassifier, ScoresAndDecisionsMatchVectorR3) {
  std::vector<int> labels;
  const Matrix x = r3_training(labels);
  ClaficClassifier clafic(Parameters::parse("c1=0.95", "test"));
  clafic.fit(x, labels, 2, 1);
  Matrix queries(2, 4);
  queries << 0.8, 0.7, 0.3, 0.2, 0.5, 0.5, 0.5, 0.5;
  const Matrix scores = clafic.scores(queries);
  ASSERT_EQ(scores.rows(), 2);
  ASSERT_EQ(scores.cols(), 2);
  EXPECT_NEAR(scores(0, 0), 1.18494, 5e-6);
  EXPECT_NEAR(scores(0, 1), 0.21667, 5e-6);
  EXPECT_NEAR(scores(1, 0), 0.586699, 5e-7);
  EXPECT_NEAR(scores(1, 1), 0.605685, 5e-7);
  EXPECT_EQ(clafic.predict(queries), (std::vector<int>{0, kUnknownClass}));
  EXPECT_EQ(clafic.subspace_dimensions(), (std::vector<int>{1, 1}));
  EXPECT_EQ(clafic.sensor_bank_sizes(), (std::vector<int64_t>{4, 4}));
}

TEST(ClaficClassifier, SensorBanksShrinkTheFeaturesUsed) {
  std::vector<int> labels;
  const Matrix x = r3_training(labels);
  ClaficClassifier clafic(Parameters::parse("c1=0.95,c2=1", "test"));
  clafic.fit(x, labels, 2, 1);
  EXPECT_EQ(clafic.sensor_bank_sizes(), (std::vector<int64_t>{2, 2}));
  EXPECT_EQ(clafic.feature_fractions(), (std::vector<double>{0.5, 0.5}));
  const Matrix scores = clafic.scores(row_of({0.8, 0.7, 0.3, 0.2}));
  EXPECT_NEAR(scores(0, 0), 1.125, 5e-6);
  EXPECT_NEAR(scores(0, 1), 0.125749, 5e-7);
}

TEST(ClaficClassifier, DimensionsOverrideTheContributionThreshold) {
  std::vector<int> labels;
  const Matrix x = r3_training(labels);
  ClaficClassifier clafic(Parameters::parse("dimensions=1|3", "test"));
  clafic.fit(x, labels, 2, 1);
  EXPECT_EQ(clafic.subspace_dimensions(), (std::vector<int>{1, 3}));
  ClaficClassifier clamped(Parameters::parse("dimensions=9", "test"));
  clamped.fit(x, labels, 2, 1);
  EXPECT_EQ(clamped.subspace_dimensions(), (std::vector<int>{3, 3}));  // rank 3 each
  ClaficClassifier mismatched(Parameters::parse("dimensions=1|2|3", "test"));
  EXPECT_THROW(mismatched.fit(x, labels, 2, 1), Error);
}

// Class 0 lives in span(e0, e1), class 1 in span(e2, e3); e4 is orthogonal to both.
Matrix two_subspaces(std::vector<int>& labels) {
  Matrix x(8, 5);
  x << 1, 0.2, 0, 0, 0,   //
      0.3, 1, 0, 0, 0,    //
      0.7, 0.7, 0, 0, 0,  //
      2, -1, 0, 0, 0,     //
      0, 0, 1, 0.5, 0,    //
      0, 0, -0.2, 1, 0,   //
      0, 0, 0.9, 0.9, 0,  //
      0, 0, 3, -2, 0;
  labels = {0, 0, 0, 0, 1, 1, 1, 1};
  return x;
}

TEST(ClaficClassifier, SeparatesTwoSubspacesAndAnswersUnknownOutsideThem) {
  std::vector<int> labels;
  const Matrix x = two_subspaces(labels);
  ClaficClassifier clafic(Parameters::parse("c1=1", "test"));
  clafic.fit(x, labels, 2, 7);
  EXPECT_EQ(clafic.subspace_dimensions(), (std::vector<int>{2, 2}));
  EXPECT_EQ(clafic.predict(x), labels);
  Matrix queries(4, 5);
  queries << 0.5, -3, 0, 0, 0,  // inside class 0's plane
      0, 0, -1, -1, 0,          // inside class 1's plane (sign does not matter)
      0, 0, 0, 0, 4,            // orthogonal to both planes: DF = 0 everywhere
      1, 0, 1, 0, 0;            // equally in both: ratio 1 < 1/tau
  EXPECT_EQ(clafic.predict(queries), (std::vector<int>{0, 1, kUnknownClass, kUnknownClass}));
  const Matrix scores = clafic.scores(queries);
  EXPECT_NEAR(scores(0, 0), 9.25, 1e-12);  // the whole squared length of the query
  EXPECT_NEAR(scores(0, 1), 0.0, 1e-12);
  EXPECT_NEAR(scores(2, 0), 0.0, 1e-12);
}

// The shortcut must give what refitting on every fold gives, under every condition of the
// Robovie experiment and with a class of one sample (held out, that class spans nothing).
TEST(ClaficClassifier, LeaveOneOutEqualsRefittingOnEveryFold) {
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal;
  const std::vector<int> labels = {0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 3};
  Matrix x(static_cast<Eigen::Index>(labels.size()), 40);
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    for (Eigen::Index column = 0; column < x.cols(); ++column)
      x(row, column) = normal(engine) + (column % 4 == labels[row] ? 1.5 : 0.0);
  for (const char* condition : {"c1=1,c2=0", "c1=1,c2=2", "c1=0.15,c2=0", "c1=0.15,c2=1",
                                "c1=0.15,c2=2,tau=0.6", "dimensions=2"}) {
    ClaficClassifier shortcut(Parameters::parse(condition, "test"));
    const std::vector<int> answers = shortcut.leave_one_out(x, labels, 5);
    for (Eigen::Index held = 0; held < x.rows(); ++held) {
      std::vector<Eigen::Index> train;
      std::vector<int> train_labels;
      for (Eigen::Index row = 0; row < x.rows(); ++row)
        if (row != held) {
          train.push_back(row);
          train_labels.push_back(labels[static_cast<size_t>(row)]);
        }
      ClaficClassifier fold(Parameters::parse(condition, "test"));
      fold.fit(x(train, Eigen::all), train_labels, 5, 0);
      EXPECT_EQ(answers[static_cast<size_t>(held)], fold.predict(x.row(held))[0])
          << condition << ", row " << held;
    }
    // Left fitted on every row.
    EXPECT_EQ(shortcut.predict(x).size(), labels.size());
  }
}

TEST(ClaficClassifier, ClassAbsentFromTrainingIsNeverPredicted) {
  std::vector<int> labels;
  const Matrix x = two_subspaces(labels);
  ClaficClassifier clafic;
  clafic.fit(x, labels, 3, 0);
  const Matrix scores = clafic.scores(x);
  EXPECT_EQ(scores.cols(), 3);
  EXPECT_TRUE((scores.col(2).array() == 0.0).all());
  for (const int label : clafic.predict(x)) EXPECT_NE(label, 2);
}

TEST(ClaficClassifier, OneSampleClassesConstantFeaturesAndWideDataAreLearnt) {
  // 2 samples, 6 features (more features than samples), one constant feature, one sample
  // per class.
  Matrix x(2, 6);
  x << 1, 0, 2, 0, 5, 0,  //
      0, 1, 0, 3, 5, 0;
  ClaficClassifier clafic(Parameters::parse("c1=1", "test"));
  clafic.fit(x, {0, 1}, 2, 0);
  EXPECT_EQ(clafic.subspace_dimensions(), (std::vector<int>{1, 1}));
  EXPECT_EQ(clafic.predict(x), (std::vector<int>{0, 1}));
  EXPECT_TRUE(clafic.scores(x).allFinite());
}

TEST(ClaficClassifier, BadInputNamesTheProblem) {
  std::vector<int> labels;
  Matrix x = two_subspaces(labels);
  ClaficClassifier clafic;
  EXPECT_THROW(clafic.fit(Matrix(0, 5), {}, 2, 0), Error);
  EXPECT_THROW(clafic.fit(x, {0, 1}, 2, 0), Error);
  EXPECT_THROW(clafic.fit(x, labels, 1, 0), Error);  // class 1 outside 0..0
  EXPECT_THROW(clafic.scores(x), Error);             // not fitted
  x(3, 2) = std::numeric_limits<double>::quiet_NaN();
  try {
    clafic.fit(x, labels, 2, 0);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("row 3"), std::string::npos) << error.what();
  }
  x(3, 2) = 0.0;
  clafic.fit(x, labels, 2, 0);
  EXPECT_THROW(clafic.scores(Matrix::Zero(1, 4)), Error);  // wrong feature count
  Matrix query = Matrix::Zero(1, 5);
  query(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(clafic.predict(query), Error);
}

TEST(ClaficClassifier, BadParametersAreRejected) {
  EXPECT_THROW(ClaficClassifier(Parameters::parse("c3=1", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("c1=0", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("c1=1.5", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("c2=-1", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("tau=0", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("c1_mode=sum", "test")), Error);
  EXPECT_THROW(ClaficClassifier(Parameters::parse("dimensions=2|x", "test")), Error);
  const Parameters effective = ClaficClassifier(Parameters::parse("c2=2", "test")).parameters();
  EXPECT_EQ(effective.text("c1", ""), "0.15");
  EXPECT_EQ(effective.text("c2", ""), "2");
  EXPECT_EQ(effective.text("tau", ""), "0.95");
}

TEST(ClaficClassifier, SavedModelGivesIdenticalScores) {
  std::vector<int> labels;
  const Matrix x = two_subspaces(labels);
  ClaficClassifier clafic(Parameters::parse("c1=0.9,c2=1,tau=0.9,dimensions=2|1", "test"));
  clafic.fit(x, labels, 2, 0);
  const nlohmann::json text = nlohmann::json::parse(clafic.save().dump());
  ClaficClassifier restored;
  restored.load(text);
  Matrix queries = x;
  queries.row(0) << 0.3, 0.1, 0.2, 0.7, 0.05;
  EXPECT_EQ(restored.scores(queries), clafic.scores(queries));
  EXPECT_EQ(restored.predict(queries), clafic.predict(queries));
  EXPECT_EQ(restored.parameters().values(), clafic.parameters().values());
  EXPECT_EQ(restored.sensor_bank_sizes(), clafic.sensor_bank_sizes());
  nlohmann::json broken = text;
  broken["classes"][0]["basis"]["rows"] = 3;
  EXPECT_THROW(restored.load(broken), Error);
}

//---- Sensor banks and rates

TEST(SensorBank, PairFeaturesMapToTheirSensors) {
  // N = 4: q 0..5 = (0,1) (0,2) (0,3) (1,2) (1,3) (2,3).
  EXPECT_EQ(pair_sensors({5}, 4), (std::vector<int>{2, 3}));
  EXPECT_EQ(pair_sensors({1, 3}, 4), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(pair_sensors({2, 4}, 4), (std::vector<int>{0, 1, 3}));
  // Spec §4.3, N = 274: (i, j) = (3, 10) 1-based -> q = 2*274 - 3 + 7 - 1 = 551.
  EXPECT_EQ(pair_sensors({551}, 274), (std::vector<int>{2, 9}));
  EXPECT_EQ(pair_sensors({37400}, 274), (std::vector<int>{272, 273}));
  EXPECT_THROW(pair_sensors({6}, 4), Error);
  EXPECT_THROW(pair_sensors({-1}, 4), Error);
}

TEST(RecognitionRates, UnknownAnswersAreNeitherCorrectNorFalseAlarms) {
  Eigen::MatrixXi confusion(3, 4);  // last column: unknown
  confusion << 6, 1, 0, 3,          //
      2, 4, 0, 0,                   //
      4, 0, 0, 0;
  const RecognitionRates rates = recognition_rates(confusion);
  EXPECT_DOUBLE_EQ(rates.recognition[0], 0.6);
  EXPECT_DOUBLE_EQ(rates.recognition[1], 4.0 / 6.0);
  EXPECT_DOUBLE_EQ(rates.recognition[2], 0.0);
  EXPECT_DOUBLE_EQ(rates.false_alarm[0], 0.6);  // (2 + 4) / 10
  EXPECT_DOUBLE_EQ(rates.false_alarm[1], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(rates.false_alarm[2], 0.0);
  EXPECT_THROW(recognition_rates(Eigen::MatrixXi::Zero(3, 5)), Error);
}

}  // namespace
}  // namespace tactile::ml

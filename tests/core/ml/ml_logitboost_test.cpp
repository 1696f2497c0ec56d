#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/logitboost.h"

namespace tactile::ml {
namespace {

LogitBoost make(const std::string& parameters = "") {
  return LogitBoost("logitboost", Parameters::parse(parameters, "logitboost"));
}

Matrix overlapping_centres() {
  Matrix centres(3, 2);
  centres << 0, 0, 2, 0, 0, 2;
  return centres;
}

// Mean -log p(true class) over the rows.
double log_loss(const Matrix& scores, const std::vector<int>& y) {
  double total = 0.0;
  for (Eigen::Index row = 0; row < scores.rows(); ++row)
    total -= std::log(scores(row, y[static_cast<size_t>(row)]));
  return total / static_cast<double>(scores.rows());
}

TEST(LogitBoost, FirstRoundOnASeparableLineMatchesFriedmanAlgorithmSix) {
  // p = 1/2 everywhere: z = ±2, w = 1/4; the stump of class 0 cuts at 7 with values +2 / -2.
  Matrix x(8, 1);
  x << 1, 2, 3, 4, 10, 11, 12, 13;
  const std::vector<int> y = {0, 0, 0, 0, 1, 1, 1, 1};
  LogitBoost boost = make("learners=1");
  boost.fit(x, y, 2, 0);
  const RegressionStump& stump = boost.stumps()[0][0];
  EXPECT_EQ(stump.feature, 0);
  EXPECT_EQ(stump.threshold, 7.0);
  EXPECT_DOUBLE_EQ(stump.below, 2.0);
  EXPECT_DOUBLE_EQ(stump.above, -2.0);
  // F_0 = (J-1)/J (f_0 - mean f) = 1/2 (2 - 0) = 1 and F_1 = -1 below the cut.
  const double expected = 1.0 / (1.0 + std::exp(-2.0));
  const Matrix scores = boost.scores(x);
  EXPECT_NEAR(scores(0, 0), expected, 1e-15);
  EXPECT_NEAR(scores(7, 1), expected, 1e-15);
}

TEST(LogitBoost, TrainingErrorAndLossFallAsLearnersAreAdded) {
  const toy::LabelledSet train = toy::blobs(overlapping_centres(), 40, 0.8, 1);
  double previous_loss = INFINITY;
  double first_error = 0.0;
  double last_error = 1.0;
  for (const int learners : {1, 3, 10, 40}) {
    LogitBoost boost = make("learners=" + std::to_string(learners));
    boost.fit(train.x, train.y, 3, 0);
    const double loss = log_loss(boost.scores(train.x), train.y);
    EXPECT_LT(loss, previous_loss) << learners;
    previous_loss = loss;
    const double error = 1.0 - toy::accuracy(boost.predict(train.x), train.y);
    if (learners == 1) first_error = error;
    last_error = error;
  }
  EXPECT_LT(last_error, first_error);
  EXPECT_LT(last_error, 0.15);
}

TEST(LogitBoost, ClassifiesThreeBlobsWithProbabilitiesThatSumToOne) {
  Matrix centres(3, 2);
  centres << 0, 0, 5, 0, 0, 5;
  const toy::LabelledSet train = toy::blobs(centres, 30, 1.0, 2);
  const toy::LabelledSet test = toy::blobs(centres, 30, 1.0, 3);
  LogitBoost boost = make();
  boost.fit(train.x, train.y, 3, 0);
  EXPECT_EQ(boost.stumps().size(), 10u);
  EXPECT_GE(toy::accuracy(boost.predict(test.x), test.y), 0.95);
  const Matrix scores = boost.scores(test.x);
  ASSERT_EQ(scores.cols(), 3);
  for (Eigen::Index row = 0; row < scores.rows(); ++row) {
    EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-12);
    EXPECT_GT(scores.row(row).minCoeff(), 0.0);
  }
}

TEST(LogitBoost, ShrinkageSlowsTheFit) {
  const toy::LabelledSet train = toy::blobs(overlapping_centres(), 30, 0.8, 4);
  LogitBoost full = make("learners=5");
  LogitBoost shrunk = make("learners=5,learning_rate=0.1");
  full.fit(train.x, train.y, 3, 0);
  shrunk.fit(train.x, train.y, 3, 0);
  EXPECT_LT(log_loss(full.scores(train.x), train.y), log_loss(shrunk.scores(train.x), train.y));
  EXPECT_EQ(shrunk.parameters().text("learning_rate", ""), "0.1");
}

TEST(LogitBoost, SaveAndLoadGiveIdenticalScores) {
  const toy::LabelledSet train = toy::blobs(overlapping_centres(), 30, 0.8, 5);
  const toy::LabelledSet test = toy::blobs(overlapping_centres(), 30, 0.8, 6);
  LogitBoost boost = make("learners=12,learning_rate=0.5");
  boost.fit(train.x, train.y, 3, 0);
  LogitBoost restored = make();
  restored.load(nlohmann::json::parse(boost.save().dump()));
  EXPECT_EQ(restored.scores(test.x), boost.scores(test.x));
  EXPECT_EQ(restored.parameters().values(), boost.parameters().values());

  nlohmann::json broken = boost.save();
  broken["stumps"][3][1]["feature"] = 7;
  EXPECT_THROW(restored.load(broken), Error);
  broken = boost.save();
  broken["stumps"][0].erase(2);
  EXPECT_THROW(restored.load(broken), Error);
}

TEST(LogitBoost, ConstantFeaturesAndAbsentClassesGiveFiniteProbabilities) {
  const Matrix flat = Matrix::Constant(6, 3, 2.0);
  LogitBoost boost = make();
  boost.fit(flat, {0, 0, 0, 0, 1, 1}, 3, 0);  // class 2 absent, nothing to split on
  const Matrix scores = boost.scores(flat.topRows(1));
  EXPECT_TRUE(scores.allFinite());
  EXPECT_EQ(boost.predict(flat.topRows(1))[0], 0);
  EXPECT_LT(scores(0, 2), scores(0, 1));
  EXPECT_EQ(boost.stumps()[0][0].feature, -1);

  LogitBoost single = make();
  single.fit(flat, {1, 1, 1, 1, 1, 1}, 2, 0);
  EXPECT_TRUE(single.scores(flat).allFinite());
  EXPECT_EQ(single.predict(flat.topRows(2)), (std::vector<int>{1, 1}));
}

TEST(LogitBoost, ClassWithOneSampleAndWideDataAreLearned) {
  Matrix x = Matrix::Zero(5, 12);  // 5 samples, 12 features
  x.col(3) << 0, 1, 2, 3, 9;
  x.col(8) << 5, 5, 0, 0, 0;
  LogitBoost boost = make("learners=30");
  boost.fit(x, {0, 0, 1, 1, 2}, 3, 0);
  EXPECT_EQ(boost.predict(x), (std::vector<int>{0, 0, 1, 1, 2}));
}

TEST(LogitBoost, BadInputIsAnError) {
  LogitBoost boost = make();
  EXPECT_THROW(boost.fit(Matrix(0, 2), {}, 2, 0), Error);
  Matrix x = Matrix::Zero(3, 2);
  x(1, 1) = std::nan("");
  EXPECT_THROW(boost.fit(x, {0, 1, 0}, 2, 0), Error);
  EXPECT_THROW(boost.scores(Matrix::Zero(1, 2)), Error);  // never fitted
  boost.fit(Matrix::Identity(2, 2), {0, 1}, 2, 0);
  EXPECT_THROW(boost.scores(Matrix::Zero(1, 3)), Error);
  EXPECT_THROW(make("learners=0"), Error);
  EXPECT_THROW(make("learning_rate=0"), Error);
  EXPECT_THROW(make("depth=2"), Error);
  EXPECT_THROW(LogitBoost("adaboost", Parameters()), Error);
}

TEST(LogitBoost, RegistryFactoryReadsItsParameters) {
  const auto boost =
      make_logitboost_classifier(Parameters::parse("learners=30,learning_rate=0.1", "lb"));
  EXPECT_EQ(boost->name(), "logitboost");
  EXPECT_EQ(boost->parameters().integer("learners", 0), 30);
  EXPECT_EQ(make_logitboost_classifier(Parameters())->parameters().number("learning_rate", 0), 1.0);
}

}  // namespace
}  // namespace tactile::ml

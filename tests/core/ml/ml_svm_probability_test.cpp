// SVM class probabilities: Platt's sigmoid per pair and the pairwise coupling, against
// libsvm's own `-b 1` numbers, and what they are for: scores that rank where votes tie.
#include <gtest/gtest.h>
#include <libsvm/svm.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <numbers>
#include <thread>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/svm.h"
#include "tactile/ml/svm_probability.h"
#include "tactile/random.h"

namespace tactile::ml {
namespace {

SupportVectorMachine probability_svm(const std::string& preset,
                                     const std::string& parameters = "") {
  return SupportVectorMachine(preset, Parameters::parse(parameters, preset));
}

// One-feature training set of two overlapping classes: class 0 on -3..1, class 1 on -1..3.
struct OverlapSet {
  Matrix x;
  std::vector<int> y;
};
OverlapSet overlapping_classes() {
  OverlapSet set;
  set.x.resize(82, 1);
  for (int k = 0; k <= 40; ++k) {
    set.x(k, 0) = -3.0 + 0.1 * k;
    set.x(41 + k, 0) = -1.0 + 0.1 * k;
  }
  set.y.assign(41, 0);
  set.y.insert(set.y.end(), 41, 1);
  return set;
}

// Three classes turned 120° from each other, each a short segment leaning the same way round
// (a pinwheel): every pair's boundary passes beside the centre, so around it each class wins
// one pair and the votes tie 1/1/1.
OverlapSet pinwheel() {
  OverlapSet set;
  set.x.resize(63, 2);
  for (int label = 0; label < 3; ++label) {
    const double angle = 2.0 * std::numbers::pi * label / 3.0;
    const double c = std::cos(angle), s = std::sin(angle);
    for (int k = 0; k < 21; ++k) {
      // The segment from (2, 0) to (2, 2), a little zigzag across it.
      const double u = 2.0 + (k % 2 == 0 ? 0.05 : -0.05), v = 0.1 * k;
      set.x(label * 21 + k, 0) = c * u - s * v;
      set.x(label * 21 + k, 1) = s * u + c * v;
      set.y.push_back(label);
    }
  }
  return set;
}

// Our first fit routes libsvm's progress messages away from stdout (svm.h); these tests call
// libsvm directly, so they fit one small model first.
void route_libsvm_messages() {
  SupportVectorMachine svm = probability_svm("linear-svm", "probability=false");
  svm.fit(toy::column({0, 1}), {0, 1}, 2, 1);
}

// A libsvm problem of one-feature-per-column rows.
struct LibsvmProblem {
  std::vector<svm_node> nodes;
  std::vector<svm_node*> rows;
  std::vector<double> labels;
  svm_problem problem{};
};
void fill_problem(LibsvmProblem& libsvm, const Matrix& x, const std::vector<double>& labels) {
  const Eigen::Index features = x.cols();
  libsvm.nodes.resize(static_cast<size_t>(x.rows() * (features + 1)));
  for (Eigen::Index row = 0; row < x.rows(); ++row) {
    svm_node* node = &libsvm.nodes[static_cast<size_t>(row * (features + 1))];
    for (Eigen::Index column = 0; column < features; ++column)
      node[column] = {static_cast<int>(column + 1), x(row, column)};
    node[features] = {-1, 0.0};
    libsvm.rows.push_back(node);
  }
  libsvm.labels = labels;
  libsvm.problem = {static_cast<int>(x.rows()), libsvm.labels.data(), libsvm.rows.data()};
}
svm_parameter gaussian_parameter(bool probability) {
  svm_parameter parameter{};
  parameter.svm_type = C_SVC;
  parameter.kernel_type = RBF;
  parameter.gamma = 0.5;
  parameter.cache_size = 100;
  parameter.eps = 1e-3;
  parameter.C = 1.0;
  parameter.shrinking = 1;
  parameter.probability = probability ? 1 : 0;
  return parameter;
}

//---- The two steps against libsvm ----------------------------------------------------------

TEST(SvmProbability, PlattSigmoidIsLibsvmsOnTheSameHeldOutDecisionValues) {
  // libsvm's -b 1 on a binary problem, then its cross-validation replayed with the same
  // rand() order: the sigmoid fitted to those decision values must be libsvm's probA, probB.
  route_libsvm_messages();
  const OverlapSet set = overlapping_classes();
  std::vector<double> labels;
  for (int label : set.y) labels.push_back(label == 1 ? 1.0 : -1.0);
  LibsvmProblem libsvm;
  // libsvm's first label is the first row's: put class 1 (+1) first.
  Matrix x = set.x.colwise().reverse();
  std::reverse(labels.begin(), labels.end());
  fill_problem(libsvm, x, labels);
  const svm_parameter with_probability = gaussian_parameter(true);
  std::srand(11);
  svm_model* model = svm_train(&libsvm.problem, &with_probability);
  ASSERT_NE(model, nullptr);
  ASSERT_EQ(model->label[0], 1);

  const int rows = libsvm.problem.l;
  std::vector<int> order(static_cast<size_t>(rows));
  for (int row = 0; row < rows; ++row) order[static_cast<size_t>(row)] = row;
  std::srand(11);
  for (int slot = 0; slot < rows; ++slot)  // svm_binary_svc_probability's shuffle
    std::swap(order[static_cast<size_t>(slot)],
              order[static_cast<size_t>(slot + std::rand() % (rows - slot))]);
  std::vector<double> decisions(static_cast<size_t>(rows));
  const svm_parameter plain = gaussian_parameter(false);
  for (int fold = 0; fold < 5; ++fold) {
    const int begin = fold * rows / 5, end = (fold + 1) * rows / 5;
    std::vector<svm_node*> nodes;
    std::vector<double> targets;
    for (int slot = 0; slot < rows; ++slot) {
      if (slot >= begin && slot < end) continue;
      nodes.push_back(libsvm.rows[static_cast<size_t>(order[static_cast<size_t>(slot)])]);
      targets.push_back(labels[static_cast<size_t>(order[static_cast<size_t>(slot)])]);
    }
    svm_problem fold_problem{static_cast<int>(targets.size()), targets.data(), nodes.data()};
    svm_model* fold_model = svm_train(&fold_problem, &plain);
    for (int slot = begin; slot < end; ++slot) {
      const int row = order[static_cast<size_t>(slot)];
      double value = 0.0;
      svm_predict_values(fold_model, libsvm.rows[static_cast<size_t>(row)], &value);
      decisions[static_cast<size_t>(row)] = value * fold_model->label[0];
    }
    svm_free_and_destroy_model(&fold_model);
  }
  std::vector<bool> positive;
  for (double label : labels) positive.push_back(label > 0.0);
  const PlattSigmoid sigmoid = fit_platt_sigmoid(decisions, positive);
  EXPECT_NEAR(sigmoid.a, model->probA[0], 1e-9 * std::abs(model->probA[0]));
  EXPECT_NEAR(sigmoid.b, model->probB[0], 1e-9 + 1e-9 * std::abs(model->probB[0]));
  EXPECT_LT(sigmoid.a, 0.0);  // a larger decision value is more likely the positive class
  svm_free_and_destroy_model(&model);
}

TEST(SvmProbability, CouplingGivesLibsvmsClassProbabilities) {
  // A four-class libsvm model with probability outputs: its sigmoids applied to its decision
  // values and coupled must give what svm_predict_probability gives.
  route_libsvm_messages();
  Matrix centres(4, 2);
  centres << 0, 0, 2, 0, 0, 2, 2, 2;
  Matrix x(80, 2);
  std::vector<double> labels;
  std::mt19937_64 engine(4);
  for (int row = 0; row < 80; ++row) {
    const int label = row / 20;
    for (int column = 0; column < 2; ++column)
      x(row, column) = centres(label, column) + 1.2 * (uniform01(engine) - 0.5) * 2.0;
    labels.push_back(label);
  }
  LibsvmProblem libsvm;
  fill_problem(libsvm, x, labels);
  const svm_parameter parameter = gaussian_parameter(true);
  std::srand(3);
  svm_model* model = svm_train(&libsvm.problem, &parameter);
  ASSERT_NE(model, nullptr);
  for (int label = 0; label < 4; ++label) ASSERT_EQ(model->label[label], label);
  for (const auto& [u, v] : {std::pair{1.0, 1.0}, {0.2, 0.1}, {1.8, 0.5}, {3.0, 3.0}, {1.0, 0.2}}) {
    const svm_node query[3] = {{1, u}, {2, v}, {-1, 0.0}};
    double decision[6];
    svm_predict_values(model, query, decision);
    Matrix pairwise = Matrix::Zero(4, 4);
    int pair = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j, ++pair)
        pairwise(i, j) =
            PlattSigmoid{model->probA[pair], model->probB[pair]}.probability(decision[pair]);
    double theirs[4];
    svm_predict_probability(model, query, theirs);
    const Vector ours = couple_pairwise(pairwise);
    EXPECT_NEAR(ours.sum(), 1.0, 1e-12);
    for (int label = 0; label < 4; ++label) EXPECT_NEAR(ours(label), theirs[label], 1e-12);
  }
  svm_free_and_destroy_model(&model);
}

TEST(SvmProbability, CouplingOfConsistentPairsRecoversTheClassProbabilities) {
  // r_ij = p_i / (p_i + p_j) for a known p: method 2's minimum is p itself.
  const Vector p{{0.5, 0.3, 0.15, 0.05}};
  Matrix pairwise(4, 4);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) pairwise(i, j) = p(i) / (p(i) + p(j));
  EXPECT_LT((couple_pairwise(pairwise) - p).cwiseAbs().maxCoeff(), 1e-3);
}

//---- The classifier's scores -------------------------------------------------------------

TEST(SupportVectorMachine, ProbabilitiesSumToOneAndAnAbsentClassScoresZero) {
  const OverlapSet set = pinwheel();
  for (const std::string preset : {"linear-svm", "medium-gaussian-svm", "quadratic-svm"}) {
    SupportVectorMachine svm = probability_svm(preset);
    svm.fit(set.x, set.y, 4, 3);  // class 3 has no training sample
    ASSERT_TRUE(svm.has_probabilities());
    const Matrix scores = svm.scores(set.x);
    for (Eigen::Index row = 0; row < scores.rows(); ++row) {
      EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-12) << preset;
      EXPECT_EQ(scores(row, 3), 0.0) << preset;
      EXPECT_GT(scores.row(row).minCoeff(), -1e-15) << preset;
    }
  }
}

TEST(SupportVectorMachine, ProbabilitiesRankSamplesWhoseVotesTie) {
  const OverlapSet set = pinwheel();
  SupportVectorMachine votes = probability_svm("linear-svm", "probability=false");
  SupportVectorMachine probabilities = probability_svm("linear-svm");
  votes.fit(set.x, set.y, 3, 5);
  probabilities.fit(set.x, set.y, 3, 5);
  // A small grid round the centre; keep the points where every class wins one pair.
  Matrix grid(121, 2);
  for (int k = 0; k < 121; ++k) grid.row(k) << 0.04 * (k % 11 - 5), 0.04 * (k / 11 - 5);
  const Matrix shares = votes.scores(grid);
  const Matrix scores = probabilities.scores(grid);
  const std::vector<int> predicted = probabilities.predict(grid);
  std::vector<double> margins;
  for (Eigen::Index row = 0; row < grid.rows(); ++row) {
    if ((shares.row(row).array() - 1.0 / 3.0).abs().maxCoeff() > 1e-12) continue;
    EXPECT_EQ(predicted[static_cast<size_t>(row)], 0);  // a tie goes to the lowest class
    margins.push_back(confidence_of(scores.row(row).transpose(), 0).margin);
  }
  ASSERT_GE(margins.size(), 5u) << "the pinwheel no longer ties the votes round its centre";
  const auto [low, high] = std::minmax_element(margins.begin(), margins.end());
  EXPECT_GT(*high - *low, 1e-3);  // vote shares would give every one the same 1/3
}

TEST(SupportVectorMachine, ProbabilityGrowsWithTheDistanceFromTheBoundary) {
  const OverlapSet set = overlapping_classes();
  SupportVectorMachine svm = probability_svm("linear-svm");
  svm.fit(set.x, set.y, 2, 9);
  const Matrix queries = toy::column({0.25, 0.5, 1.0, 1.5, 2.0, 3.0});
  const Matrix right = svm.scores(queries);
  const Matrix left = svm.scores(-queries);
  for (Eigen::Index row = 0; row < queries.rows(); ++row) {
    EXPECT_GT(right(row, 1), 0.5);
    EXPECT_GT(left(row, 0), 0.5);
    if (row == 0) continue;
    EXPECT_GT(right(row, 1), right(row - 1, 1)) << queries(row, 0);
    EXPECT_GT(left(row, 0), left(row - 1, 0)) << -queries(row, 0);
  }
  // Still a probability, not a step: the data overlap on [-1, 1].
  EXPECT_LT(right(0, 1), 0.8);
}

TEST(SupportVectorMachine, TheSameSeedGivesTheSameSigmoidsOnAnyThread) {
  const OverlapSet set = pinwheel();
  const auto fitted = [&](uint64_t seed) {
    SupportVectorMachine svm = probability_svm("quadratic-svm");
    svm.fit(set.x, set.y, 3, seed);
    return svm.save();
  };
  const nlohmann::json serial = fitted(21);
  EXPECT_EQ(fitted(21), serial);
  // Fits on two threads at once (an evaluation's folds) draw nothing from a shared generator.
  nlohmann::json first, second;
  std::thread one([&] { first = fitted(21); });
  std::thread two([&] { second = fitted(21); });
  one.join();
  two.join();
  EXPECT_EQ(first, serial);
  EXPECT_EQ(second, serial);
  // Another seed shuffles the cross-validation otherwise: other sigmoids.
  EXPECT_NE(fitted(22)["learners"][0]["probability_a"], serial["learners"][0]["probability_a"]);
}

TEST(SupportVectorMachine, ProbabilitiesChangeNoDecisionNorPrediction) {
  const OverlapSet set = pinwheel();
  Matrix queries(41, 2);
  for (int k = 0; k < 41; ++k) queries.row(k) << 0.3 * (k % 7 - 3), 0.2 * (k / 7 - 3);
  for (const std::string& preset : svm_preset_names()) {
    SupportVectorMachine with = probability_svm(preset);
    SupportVectorMachine without = probability_svm(preset, "probability=false");
    with.fit(set.x, set.y, 3, 17);
    without.fit(set.x, set.y, 3, 17);
    EXPECT_EQ(with.decision_values(queries), without.decision_values(queries)) << preset;
    EXPECT_EQ(with.predict(queries), without.predict(queries)) << preset;
    EXPECT_EQ(with.decide(queries).classes, without.predict(queries)) << preset;
    EXPECT_EQ(with.decide(queries).scores, with.scores(queries)) << preset;
  }
}

// An evaluation that reports no scores says so before the fit: the sigmoids (five more
// trainings per pair) are left out, the votes and so the predictions stay as they are.
TEST(SupportVectorMachine, SkippedScoresLeaveOutTheSigmoidsButNoPrediction) {
  const OverlapSet set = pinwheel();
  Matrix queries(41, 2);
  for (int k = 0; k < 41; ++k) queries.row(k) << 0.3 * (k % 7 - 3), 0.2 * (k / 7 - 3);
  for (const std::string& preset : svm_preset_names()) {
    SupportVectorMachine with = probability_svm(preset);
    SupportVectorMachine skipped = probability_svm(preset);
    skipped.skip_scores();
    with.fit(set.x, set.y, 3, 17);
    skipped.fit(set.x, set.y, 3, 17);
    EXPECT_TRUE(with.has_probabilities()) << preset;
    EXPECT_FALSE(skipped.has_probabilities()) << preset;
    EXPECT_EQ(skipped.decision_values(queries), with.decision_values(queries)) << preset;
    EXPECT_EQ(skipped.predict(queries), with.predict(queries)) << preset;
    // Its parameters still say what was asked for: the model is the same but for the scores.
    EXPECT_EQ(specification_of(skipped), specification_of(with)) << preset;
  }
}

//---- Save and load -------------------------------------------------------------------------

TEST(SupportVectorMachine, SavedProbabilitiesComeBackExactly) {
  const OverlapSet set = pinwheel();
  SupportVectorMachine svm = probability_svm("medium-gaussian-svm");
  svm.fit(set.x, set.y, 3, 2);
  const nlohmann::json saved = nlohmann::json::parse(svm.save().dump());
  ASSERT_TRUE(saved["learners"][0].contains("probability_a"));
  SupportVectorMachine restored = probability_svm("medium-gaussian-svm");
  restored.load(saved);
  EXPECT_TRUE(restored.has_probabilities());
  EXPECT_EQ(restored.scores(set.x), svm.scores(set.x));
  for (size_t k = 0; k < svm.learners().size(); ++k) {
    EXPECT_EQ(restored.learners()[k].sigmoid.a, svm.learners()[k].sigmoid.a);
    EXPECT_EQ(restored.learners()[k].sigmoid.b, svm.learners()[k].sigmoid.b);
  }
}

TEST(SupportVectorMachine, AModelSavedWithoutSigmoidsLoadsAndScoresVoteShares) {
  const OverlapSet set = pinwheel();
  SupportVectorMachine svm = probability_svm("linear-svm");
  svm.fit(set.x, set.y, 3, 2);
  nlohmann::json old = svm.save();
  for (auto& learner : old["learners"]) {
    learner.erase("probability_a");
    learner.erase("probability_b");
  }
  SupportVectorMachine restored = probability_svm("linear-svm");
  restored.load(old);
  EXPECT_FALSE(restored.has_probabilities());
  EXPECT_EQ(restored.predict(set.x), svm.predict(set.x));
  const Matrix shares = restored.scores(set.x);
  for (Eigen::Index row = 0; row < shares.rows(); ++row)
    for (Eigen::Index column = 0; column < 3; ++column)
      EXPECT_NEAR(shares(row, column) * 3.0, std::round(shares(row, column) * 3.0), 1e-12);
  // Half a model's sigmoids is a broken file, not an old one.
  nlohmann::json half = svm.save();
  half["learners"][0].erase("probability_b");
  EXPECT_THROW(restored.load(half), Error);
  half = svm.save();
  half["learners"][1].erase("probability_a");
  half["learners"][1].erase("probability_b");
  EXPECT_THROW(restored.load(half), Error);
}

}  // namespace
}  // namespace tactile::ml

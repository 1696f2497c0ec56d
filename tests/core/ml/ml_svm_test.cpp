#include <gtest/gtest.h>
#include <libsvm/svm.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/svm.h"

namespace tactile::ml {
namespace {

Matrix three_centres() {
  Matrix centres(3, 2);
  centres << 0, 0, 6, 0, 0, 6;
  return centres;
}

SupportVectorMachine make_svm(const std::string& preset, const std::string& parameters = "") {
  return SupportVectorMachine(preset, Parameters::parse(parameters, preset));
}

//---- Known answers on toy sets ------------------------------------------------------------

TEST(SupportVectorMachine, SeparatesTwoDistantBlobsWithALinearKernel) {
  Matrix centres(2, 2);
  centres << -3, 0, 3, 0;
  const toy::LabelledSet train = toy::blobs(centres, 40, 0.7, 1);
  const toy::LabelledSet test = toy::blobs(centres, 40, 0.7, 2);
  SupportVectorMachine svm = make_svm("linear-svm");
  svm.fit(train.x, train.y, 2, 7);
  EXPECT_EQ(toy::accuracy(svm.predict(test.x), test.y), 1.0);
  // The separating direction is the first feature: w = Σ coef_i sv_i points from class 1 to 0.
  const PairwiseSvm& learner = svm.learners().at(0);
  const Vector direction =
      svm.support_vectors()(learner.support, Eigen::all).transpose() * learner.coefficients;
  EXPECT_LT(direction(0), 0.0);
  EXPECT_GT(std::abs(direction(0)), 5.0 * std::abs(direction(1)));
}

// A fit for a cancelled job stops between learners; a linear one keeps one direction each.
TEST(SupportVectorMachine, AFitForACancelledJobStopsAndALinearLearnerKeepsOneDirection) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 30, 1.0, 3);
  SupportVectorMachine svm = make_svm("linear-svm");
  svm.fit(train.x, train.y, 3, 11);
  for (const PairwiseSvm& learner : svm.learners()) {
    EXPECT_EQ(learner.support.size(), 1u);
    EXPECT_EQ(learner.coefficients.size(), 1);
  }
  std::atomic<bool> cancelled{true};
  const CancelScope scope(&cancelled);
  EXPECT_THROW(svm.fit(train.x, train.y, 3, 11), Error);
}

TEST(SupportVectorMachine, EveryPresetClassifiesThreeBlobs) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 30, 1.0, 3);
  const toy::LabelledSet test = toy::blobs(three_centres(), 30, 1.0, 4);
  for (const std::string& preset : svm_preset_names()) {
    SupportVectorMachine svm = make_svm(preset);
    svm.fit(train.x, train.y, 3, 11);
    EXPECT_EQ(svm.learners().size(), 3u) << preset;
    EXPECT_GE(toy::accuracy(svm.predict(test.x), test.y), 0.95) << preset;
  }
}

TEST(SupportVectorMachine, NonLinearKernelsLearnExclusiveOrAndTheLinearOneCannot) {
  const toy::LabelledSet train = toy::exclusive_or(25, 0.25, 5);
  const toy::LabelledSet test = toy::exclusive_or(25, 0.25, 6);
  for (const std::string preset :
       {"quadratic-svm", "cubic-svm", "medium-gaussian-svm", "fine-gaussian-svm"}) {
    SupportVectorMachine svm = make_svm(preset);
    svm.fit(train.x, train.y, 2, 13);
    EXPECT_GE(toy::accuracy(svm.predict(test.x), test.y), 0.95) << preset;
  }
  SupportVectorMachine linear = make_svm("linear-svm");
  linear.fit(train.x, train.y, 2, 13);
  EXPECT_LE(toy::accuracy(linear.predict(test.x), test.y), 0.75);
}

TEST(SupportVectorMachine, WithoutProbabilitiesScoresAreVoteFractionsThatSumToOne) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 20, 1.0, 8);
  SupportVectorMachine svm = make_svm("medium-gaussian-svm", "probability=false");
  svm.fit(train.x, train.y, 4, 1);  // class 3 has no training sample
  EXPECT_FALSE(svm.has_probabilities());
  const Matrix scores = svm.scores(train.x);
  ASSERT_EQ(scores.rows(), train.x.rows());
  ASSERT_EQ(scores.cols(), 4);
  for (Eigen::Index row = 0; row < scores.rows(); ++row) {
    EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-12);
    EXPECT_EQ(scores(row, 3), 0.0);
    // Three pairs: every fraction is a whole number of votes out of 3.
    for (Eigen::Index column = 0; column < 3; ++column)
      EXPECT_NEAR(scores(row, column) * 3.0, std::round(scores(row, column) * 3.0), 1e-12);
  }
}

//---- Agreement with libsvm's own multi-class C-SVC ----------------------------------------

struct LibsvmModel {
  std::vector<svm_node> nodes;
  std::vector<svm_node*> rows;
  std::vector<double> labels;
  svm_problem problem{};
  svm_model* model = nullptr;
  ~LibsvmModel() { svm_free_and_destroy_model(&model); }
};

// libsvm's multi-class C-SVC on already standardised rows sorted by class, so its labels are
// 0, 1, 2 in that order and its pairs come in our order.
void train_libsvm(LibsvmModel& libsvm, const Matrix& z, const std::vector<int>& y, int kernel,
                  int degree, double gamma, double coef0) {
  const Eigen::Index features = z.cols();
  libsvm.nodes.resize(static_cast<size_t>(z.rows() * (features + 1)));
  for (Eigen::Index row = 0; row < z.rows(); ++row) {
    svm_node* node = &libsvm.nodes[static_cast<size_t>(row * (features + 1))];
    for (Eigen::Index column = 0; column < features; ++column)
      node[column] = {static_cast<int>(column + 1), z(row, column)};
    node[features] = {-1, 0.0};
    libsvm.rows.push_back(node);
    libsvm.labels.push_back(y[static_cast<size_t>(row)]);
  }
  libsvm.problem = {static_cast<int>(z.rows()), libsvm.labels.data(), libsvm.rows.data()};
  svm_parameter parameter{};
  parameter.svm_type = C_SVC;
  parameter.kernel_type = kernel;
  parameter.degree = degree;
  parameter.gamma = gamma;
  parameter.coef0 = coef0;
  parameter.cache_size = 100;
  parameter.eps = 1e-3;
  parameter.C = 1.0;
  parameter.shrinking = 1;
  libsvm.model = svm_train(&libsvm.problem, &parameter);
}

// `noise_features` columns of noise after the two informative ones: 62 or more make rows
// long enough for our precomputed kernel, the fold's shared Gram matrix and the prediction
// from the distinct support vectors.
toy::LabelledSet with_noise_features(toy::LabelledSet set, int noise_features, uint64_t seed) {
  if (noise_features == 0) return set;
  std::mt19937_64 engine(seed);
  Matrix padded(set.x.rows(), set.x.cols() + noise_features);
  padded.leftCols(set.x.cols()) = set.x;
  for (Eigen::Index row = 0; row < padded.rows(); ++row)
    for (Eigen::Index column = set.x.cols(); column < padded.cols(); ++column)
      padded(row, column) = toy::normal(engine);
  set.x = padded;
  return set;
}

void expect_same_decisions_as_libsvm(const std::string& preset, const std::string& parameters,
                                     int kernel, int degree, double gamma, double coef0,
                                     int noise_features = 0) {
  const toy::LabelledSet train =
      with_noise_features(toy::blobs(three_centres(), 25, 2.0, 21), noise_features, 23);
  const toy::LabelledSet test =
      with_noise_features(toy::blobs(three_centres(), 25, 2.5, 22), noise_features, 24);
  SupportVectorMachine svm = make_svm(preset, parameters);
  svm.fit(train.x, train.y, 3, 5);

  Standardizer standardizer;
  standardizer.fit(train.x);
  LibsvmModel libsvm;
  train_libsvm(libsvm, standardizer.transform(train.x), train.y, kernel, degree, gamma, coef0);
  ASSERT_NE(libsvm.model, nullptr);
  ASSERT_EQ(libsvm.model->label[0], 0);
  ASSERT_EQ(libsvm.model->label[1], 1);

  const Matrix ours = svm.decision_values(test.x);
  const std::vector<int> predicted = svm.predict(test.x);
  const Matrix z = standardizer.transform(test.x);
  for (Eigen::Index row = 0; row < z.rows(); ++row) {
    std::vector<svm_node> node(static_cast<size_t>(z.cols() + 1));
    for (Eigen::Index column = 0; column < z.cols(); ++column)
      node[static_cast<size_t>(column)] = {static_cast<int>(column + 1), z(row, column)};
    node[static_cast<size_t>(z.cols())] = {-1, 0.0};
    double theirs[3];
    const double label = svm_predict_values(libsvm.model, node.data(), theirs);
    EXPECT_EQ(predicted[static_cast<size_t>(row)], static_cast<int>(label))
        << preset << " row " << row;
    for (int pair = 0; pair < 3; ++pair) EXPECT_NEAR(ours(row, pair), theirs[pair], 1e-8) << preset;
  }
}

TEST(SupportVectorMachine, LinearDecisionEqualsLibsvmPredict) {
  expect_same_decisions_as_libsvm("linear-svm", "", LINEAR, 1, 0.0, 0.0);
}

TEST(SupportVectorMachine, PolynomialDecisionEqualsLibsvmPredict) {
  // Quadratic with a fixed s = 2: (1 + x'z/4)².
  expect_same_decisions_as_libsvm("quadratic-svm", "scale=2", POLY, 2, 0.25, 1.0);
}

TEST(SupportVectorMachine, GaussianDecisionEqualsLibsvmPredict) {
  // Medium Gaussian on P = 2 features: s = sqrt(2), gamma = 1/2.
  expect_same_decisions_as_libsvm("medium-gaussian-svm", "", RBF, 1, 0.5, 0.0);
}

TEST(SupportVectorMachine, LongRowDecisionsEqualLibsvmPredict) {
  // 80 features: the kernel is precomputed from one Gram matrix of the training set, and the
  // decisions come from one product with the distinct support vectors of all pairs.
  expect_same_decisions_as_libsvm("medium-gaussian-svm", "", RBF, 1, 1.0 / 80.0, 0.0, 78);
  expect_same_decisions_as_libsvm("quadratic-svm", "scale=sqrtP", POLY, 2, 1.0 / 80.0, 1.0, 78);
}

//---- Kernel scales -----------------------------------------------------------------------------

TEST(AutoKernelScale, IsTheMedianDistanceToTheNearestNegativePoint) {
  Matrix positive(3, 2);
  positive << 0, 0, 0, 2, 5, 5;
  Matrix negative(2, 2);
  negative << 1, 0, 0, 4;
  // Nearest negatives: 1, 2, sqrt(26); median 2; all points used, so no shrink factor.
  std::mt19937_64 engine(1);
  EXPECT_DOUBLE_EQ(auto_kernel_scale(positive, negative, engine), 2.0);
}

TEST(AutoKernelScale, ShrinksBySampledFractionWhenAClassHasOverAHundredPoints) {
  // 150 positive points on a circle of radius 3 around 120 negative points at the origin:
  // every drawn positive point is 3 from a negative one whatever is drawn.
  Matrix positive(150, 2);
  for (int row = 0; row < 150; ++row)
    positive.row(row) << 3.0 * std::cos(row * 0.1), 3.0 * std::sin(row * 0.1);
  const Matrix negative = Matrix::Zero(120, 2);
  std::mt19937_64 engine(9);
  const double expected = 3.0 * std::pow(std::sqrt(100.0 / 120.0 * 100.0 / 150.0), 1.0 / 2.0);
  EXPECT_NEAR(auto_kernel_scale(positive, negative, engine), expected, 1e-12);
}

TEST(AutoKernelScale, FallsBackToOneWhenPositivePointsSitOnNegativeOnes) {
  const Matrix points = Matrix::Ones(4, 3);
  std::mt19937_64 engine(2);
  EXPECT_EQ(auto_kernel_scale(points, points, engine), 1.0);
}

TEST(SupportVectorMachine, QuadraticPresetChoosesTheAutoScalePerPair) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 20, 1.0, 30);
  SupportVectorMachine svm = make_svm("quadratic-svm");
  svm.fit(train.x, train.y, 3, 4);
  Standardizer standardizer;
  standardizer.fit(train.x);
  const Matrix z = standardizer.transform(train.x);
  // 20 points per class: nothing is drawn, so each pair's scale is the deterministic median.
  const auto rows_of = [&](int label) { return Matrix(z.middleRows(label * 20, 20)); };
  ASSERT_EQ(svm.learners().size(), 3u);
  std::mt19937_64 engine(0);
  EXPECT_DOUBLE_EQ(svm.learners()[0].scale, auto_kernel_scale(rows_of(0), rows_of(1), engine));
  EXPECT_DOUBLE_EQ(svm.learners()[1].scale, auto_kernel_scale(rows_of(0), rows_of(2), engine));
  EXPECT_DOUBLE_EQ(svm.learners()[2].scale, auto_kernel_scale(rows_of(1), rows_of(2), engine));
  EXPECT_NE(svm.learners()[0].scale, svm.learners()[2].scale);
}

TEST(SupportVectorMachine, AutoScaleIsReproducibleFromTheSeed) {
  Matrix centres(2, 3);
  centres << 0, 0, 0, 2, 2, 2;
  const toy::LabelledSet train = toy::blobs(centres, 160, 1.0, 31);  // over 100 per class
  SupportVectorMachine first = make_svm("cubic-svm");
  SupportVectorMachine again = make_svm("cubic-svm");
  SupportVectorMachine other = make_svm("cubic-svm");
  first.fit(train.x, train.y, 2, 77);
  again.fit(train.x, train.y, 2, 77);
  other.fit(train.x, train.y, 2, 78);
  EXPECT_EQ(first.learners()[0].scale, again.learners()[0].scale);
  EXPECT_EQ(first.decision_values(train.x), again.decision_values(train.x));
  EXPECT_NE(first.learners()[0].scale, other.learners()[0].scale);
}

TEST(SupportVectorMachine, GaussianPresetsScaleWithTheSquareRootOfTheFeatureCount) {
  Matrix centres(2, 4);
  centres << 0, 0, 0, 0, 3, 3, 3, 3;
  const toy::LabelledSet train = toy::blobs(centres, 10, 1.0, 40);
  const std::pair<const char*, double> expected[] = {
      {"fine-gaussian-svm", 0.5}, {"medium-gaussian-svm", 2.0}, {"coarse-gaussian-svm", 8.0}};
  for (const auto& [preset, scale] : expected) {
    SupportVectorMachine svm = make_svm(preset);
    svm.fit(train.x, train.y, 2, 1);
    EXPECT_DOUBLE_EQ(svm.learners()[0].scale, scale) << preset;
  }
  SupportVectorMachine fixed = make_svm("medium-gaussian-svm", "scale=3");
  fixed.fit(train.x, train.y, 2, 1);
  EXPECT_DOUBLE_EQ(fixed.learners()[0].scale, 3.0);
}

//---- Balanced class weights ---------------------------------------------------------------------

// Two overlapping classes, `common` rows of class 0 around (0, 0) and `rare` of class 1
// around (1.5, 0).
toy::LabelledSet imbalanced_pair(int common, int rare, uint64_t seed) {
  Matrix centres(2, 2);
  centres << 0, 0, 1.5, 0;
  const toy::LabelledSet both = toy::blobs(centres, common, 1.0, seed);
  toy::LabelledSet kept;
  std::vector<Eigen::Index> rows;
  int rare_kept = 0;
  for (size_t row = 0; row < both.y.size(); ++row)
    if (both.y[row] == 0 || rare_kept++ < rare) rows.push_back(static_cast<Eigen::Index>(row));
  kept.x.resize(static_cast<Eigen::Index>(rows.size()), 2);
  for (size_t row = 0; row < rows.size(); ++row) {
    kept.x.row(static_cast<Eigen::Index>(row)) = both.x.row(rows[row]);
    kept.y.push_back(both.y[static_cast<size_t>(rows[row])]);
  }
  return kept;
}

double recall_of(const std::vector<int>& predicted, const std::vector<int>& truth, int label) {
  int hits = 0;
  int total = 0;
  for (size_t row = 0; row < truth.size(); ++row) {
    if (truth[row] != label) continue;
    ++total;
    if (predicted[row] == label) ++hits;
  }
  return total == 0 ? 0.0 : static_cast<double>(hits) / total;
}

TEST(SupportVectorMachine, BalancedWeightsAreScikitLearnsAndFavourTheRareClass) {
  const toy::LabelledSet train = imbalanced_pair(200, 20, 60);
  const toy::LabelledSet test = imbalanced_pair(200, 200, 61);
  for (const std::string preset : {"linear-svm", "medium-gaussian-svm"}) {
    SupportVectorMachine plain = make_svm(preset, "probability=false");
    SupportVectorMachine balanced = make_svm(preset, "probability=false,weights=balanced");
    plain.fit(train.x, train.y, 2, 62);
    balanced.fit(train.x, train.y, 2, 62);
    // n / (k n_c): 220 / (2 * 200) and 220 / (2 * 20).
    EXPECT_EQ(plain.class_weights(), (std::vector<double>{1.0, 1.0})) << preset;
    ASSERT_EQ(balanced.class_weights().size(), 2u) << preset;
    EXPECT_DOUBLE_EQ(balanced.class_weights()[0], 0.55) << preset;
    EXPECT_DOUBLE_EQ(balanced.class_weights()[1], 5.5) << preset;
    // Unweighted, the 20 rare rows barely move the boundary: most rare test rows are lost.
    // Weighted, each rare error costs ten times a common one, and the boundary moves over.
    const double plain_recall = recall_of(plain.predict(test.x), test.y, 1);
    const double balanced_recall = recall_of(balanced.predict(test.x), test.y, 1);
    EXPECT_LT(plain_recall, 0.5) << preset;
    EXPECT_GT(balanced_recall, plain_recall + 0.2) << preset;
    EXPECT_GT(balanced_recall, 0.6) << preset;
  }
}

TEST(SupportVectorMachine, BalancedWeightsOnBalancedClassesChangeNothing) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 30, 2.0, 63);
  const toy::LabelledSet test = toy::blobs(three_centres(), 30, 2.0, 64);
  for (const std::string preset : {"linear-svm", "quadratic-svm", "fine-gaussian-svm"}) {
    SupportVectorMachine plain = make_svm(preset);
    SupportVectorMachine balanced = make_svm(preset, "weights=balanced");
    plain.fit(train.x, train.y, 3, 65);
    balanced.fit(train.x, train.y, 3, 65);
    EXPECT_EQ(balanced.class_weights(), (std::vector<double>{1.0, 1.0, 1.0})) << preset;
    EXPECT_EQ(balanced.decision_values(test.x), plain.decision_values(test.x)) << preset;
    EXPECT_EQ(balanced.scores(test.x), plain.scores(test.x)) << preset;
  }
}

TEST(SupportVectorMachine, BalancedWeightsAreAParameterAndSavedInTheModel) {
  EXPECT_EQ(make_svm("linear-svm").parameters().text("weights", ""), "none");
  EXPECT_EQ(make_svm("cubic-svm", "weights=balanced").parameters().text("weights", ""), "balanced");
  EXPECT_THROW(make_svm("linear-svm", "weights=inverse"), Error);
  const toy::LabelledSet train = imbalanced_pair(60, 15, 66);
  SupportVectorMachine svm = make_svm("coarse-gaussian-svm", "weights=balanced");
  svm.fit(train.x, train.y, 2, 67);
  const nlohmann::json saved = nlohmann::json::parse(svm.save().dump());
  ASSERT_TRUE(saved.contains("class_weights"));
  SupportVectorMachine restored = make_svm("coarse-gaussian-svm", "weights=balanced");
  restored.load(saved);
  EXPECT_EQ(restored.class_weights(), svm.class_weights());
  EXPECT_EQ(restored.decision_values(train.x), svm.decision_values(train.x));
  nlohmann::json broken = saved;
  broken["class_weights"] = {1.0};
  EXPECT_THROW(restored.load(broken), Error);
  broken["class_weights"] = {1.0, -2.0};
  EXPECT_THROW(restored.load(broken), Error);
}

//---- Parameters, save and load -----------------------------------------------------------------

TEST(SupportVectorMachine, ParametersNameDefaultsAndRejectUnknownKeys) {
  EXPECT_EQ(make_svm("quadratic-svm").parameters().text("scale", ""), "auto");
  EXPECT_EQ(make_svm("fine-gaussian-svm").parameters().text("scale", ""), "0.25sqrtP");
  EXPECT_EQ(make_svm("coarse-gaussian-svm").parameters().text("scale", ""), "4sqrtP");
  EXPECT_EQ(make_svm("linear-svm", "c=10").parameters().text("c", ""), "10");
  EXPECT_EQ(make_svm("linear-svm").parameters().text("probability", ""), "true");
  EXPECT_EQ(make_svm("linear-svm", "probability=false").parameters().text("probability", ""),
            "false");
  EXPECT_THROW(make_svm("linear-svm", "probability=maybe"), Error);
  EXPECT_THROW(make_svm("linear-svm", "gamma=1"), Error);
  EXPECT_THROW(make_svm("linear-svm", "c=0"), Error);
  EXPECT_THROW(make_svm("linear-svm", "c=-1"), Error);
  EXPECT_THROW(make_svm("cubic-svm", "scale=wide"), Error);
  EXPECT_THROW(make_svm("cubic-svm", "scale=-2sqrtP"), Error);
  EXPECT_THROW(make_svm("sigmoid-svm"), Error);
  // What parameters() prints parses back to the same settings.
  const SupportVectorMachine fine = make_svm("fine-gaussian-svm", "c=2.5");
  const Parameters printed = fine.parameters();
  std::string text;
  for (const auto& [key, value] : printed.values()) text += key + "=" + value + ",";
  EXPECT_EQ(make_svm("fine-gaussian-svm", text).parameters().values(), printed.values());
}

TEST(SupportVectorMachine, SaveAndLoadGiveIdenticalScores) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 30, 2.0, 50);
  const toy::LabelledSet test = toy::blobs(three_centres(), 30, 2.0, 51);
  for (const std::string preset : {"quadratic-svm", "fine-gaussian-svm", "linear-svm"}) {
    SupportVectorMachine svm = make_svm(preset);
    svm.fit(train.x, train.y, 3, 52);
    SupportVectorMachine restored = make_svm(preset);
    restored.load(nlohmann::json::parse(svm.save().dump()));
    EXPECT_EQ(restored.decision_values(test.x), svm.decision_values(test.x)) << preset;
    EXPECT_EQ(restored.scores(test.x), svm.scores(test.x)) << preset;
  }
}

// The pairs share their support vectors: a training row that serves several pairs is kept
// once (Robovie's 105 pairs of 37,401 features held 0.8 GB of copies).
TEST(SupportVectorMachine, PairsShareEachSupportVectorOnce) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 20, 1.5, 61);
  SupportVectorMachine svm = make_svm("medium-gaussian-svm");
  svm.fit(train.x, train.y, 3, 1);
  size_t named = 0;
  std::vector<int> uses(static_cast<size_t>(svm.support_vectors().rows()), 0);
  for (const PairwiseSvm& learner : svm.learners()) {
    named += learner.support.size();
    for (const Eigen::Index row : learner.support) ++uses[static_cast<size_t>(row)];
  }
  EXPECT_LE(svm.support_vectors().rows(), train.x.rows());
  EXPECT_GT(named, static_cast<size_t>(svm.support_vectors().rows()));  // some serve two pairs
  for (const int count : uses) EXPECT_GE(count, 1);                     // none kept unused
  for (Eigen::Index a = 0; a < svm.support_vectors().rows(); ++a)
    for (Eigen::Index b = a + 1; b < svm.support_vectors().rows(); ++b)
      EXPECT_NE(svm.support_vectors().row(a), svm.support_vectors().row(b));
}

// A model saved when each pair kept its own support vectors loads and decides the same.
TEST(SupportVectorMachine, AModelWithEachPairsOwnSupportVectorsLoads) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 15, 1.0, 62);
  SupportVectorMachine svm = make_svm("quadratic-svm");
  svm.fit(train.x, train.y, 3, 2);
  nlohmann::json old = svm.save();
  for (auto& learner : old["learners"]) {
    nlohmann::json own = nlohmann::json::array();
    for (const auto& row : learner["support"])
      own.push_back(old["support_vectors"][row.get<size_t>()]);
    learner["support_vectors"] = own;
    learner.erase("support");
  }
  old.erase("support_vectors");
  SupportVectorMachine restored = make_svm("quadratic-svm");
  restored.load(old);
  EXPECT_EQ(restored.predict(train.x), svm.predict(train.x));
  EXPECT_LT(
      (restored.decision_values(train.x) - svm.decision_values(train.x)).cwiseAbs().maxCoeff(),
      1e-12);
}

TEST(SupportVectorMachine, LoadRejectsAModelOfAnotherKernelOrBrokenShape) {
  const toy::LabelledSet train = toy::blobs(three_centres(), 10, 1.0, 53);
  SupportVectorMachine svm = make_svm("cubic-svm");
  svm.fit(train.x, train.y, 3, 1);
  const nlohmann::json model = svm.save();
  SupportVectorMachine linear = make_svm("linear-svm");
  EXPECT_THROW(linear.load(model), Error);
  nlohmann::json broken = model;
  broken["support_vectors"][0] = {1.0};
  SupportVectorMachine cubic = make_svm("cubic-svm");
  EXPECT_THROW(cubic.load(broken), Error);
  broken = model;
  broken["learners"][0]["support"][0] = model["support_vectors"].size();  // past the last
  EXPECT_THROW(cubic.load(broken), Error);
  broken = model;
  broken.erase("standardizer");
  EXPECT_THROW(cubic.load(broken), Error);
  EXPECT_THROW(cubic.scores(train.x), Error);  // a failed load leaves no half model
}

//---- Bad input ---------------------------------------------------------------------------------

TEST(SupportVectorMachine, NotANumberInTrainingOrTestDataNamesTheRow) {
  toy::LabelledSet train = toy::blobs(three_centres(), 10, 1.0, 60);
  SupportVectorMachine svm = make_svm("linear-svm");
  train.x(13, 1) = std::nan("");
  try {
    svm.fit(train.x, train.y, 3, 1);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("row 13, feature 1"), std::string::npos)
        << error.what();
  }
  train.x(13, 1) = 0.0;
  svm.fit(train.x, train.y, 3, 1);
  Matrix test = train.x.topRows(3);
  test(2, 0) = INFINITY;
  EXPECT_THROW(svm.scores(test), Error);
  EXPECT_THROW(svm.scores(Matrix::Zero(2, 5)), Error);
}

TEST(SupportVectorMachine, ZeroSamplesOrLabelsOutOfRangeAreErrors) {
  SupportVectorMachine svm = make_svm("linear-svm");
  EXPECT_THROW(svm.fit(Matrix(0, 2), {}, 2, 1), Error);
  EXPECT_THROW(svm.fit(Matrix::Zero(2, 2), {0, 2}, 2, 1), Error);
  EXPECT_THROW(svm.fit(Matrix::Zero(2, 2), {0}, 2, 1), Error);
  EXPECT_THROW(svm.scores(Matrix::Zero(1, 2)), Error);  // never fitted
}

TEST(SupportVectorMachine, AClassWithOneSampleIsStillLearned) {
  toy::LabelledSet train = toy::blobs(three_centres().topRows(2), 15, 0.5, 61);
  Matrix x(31, 2);
  x << train.x, Matrix::Constant(1, 2, 0.0);
  x.row(30) << 0, 6;
  std::vector<int> y = train.y;
  y.push_back(2);
  SupportVectorMachine svm = make_svm("linear-svm");
  svm.fit(x, y, 3, 1);
  Matrix probe(1, 2);
  probe << 0, 6.5;
  EXPECT_EQ(svm.predict(probe)[0], 2);
}

TEST(SupportVectorMachine, ConstantFeaturesAndMoreFeaturesThanSamplesGiveFiniteScores) {
  // 6 samples, 10 features, of which 8 are constant.
  Matrix x = Matrix::Constant(6, 10, 4.0);
  x.col(0) << 0, 1, 2, 10, 11, 12;
  x.col(5) << 1, 0, 1, 7, 8, 7;
  const std::vector<int> y = {0, 0, 0, 1, 1, 1};
  for (const std::string& preset : svm_preset_names()) {
    SupportVectorMachine svm = make_svm(preset);
    svm.fit(x, y, 2, 3);
    EXPECT_TRUE(svm.scores(x).allFinite()) << preset;
    EXPECT_EQ(svm.predict(x), y) << preset;
  }
  // Every feature constant: the auto scale falls back to 1 and nothing is NaN.
  SupportVectorMachine flat = make_svm("quadratic-svm");
  flat.fit(Matrix::Constant(6, 3, 2.0), y, 2, 3);
  EXPECT_EQ(flat.learners()[0].scale, 1.0);
  EXPECT_TRUE(flat.scores(Matrix::Constant(2, 3, 2.0)).allFinite());
}

TEST(SupportVectorMachine, ASingleTrainingClassAlwaysWins) {
  SupportVectorMachine svm = make_svm("medium-gaussian-svm");
  svm.fit(Matrix::Random(5, 2), {1, 1, 1, 1, 1}, 3, 1);
  const Matrix scores = svm.scores(Matrix::Random(4, 2));
  EXPECT_EQ(scores.col(1), Vector::Ones(4));
  EXPECT_EQ(scores.col(0).sum() + scores.col(2).sum(), 0.0);
  SupportVectorMachine restored = make_svm("medium-gaussian-svm");
  restored.load(svm.save());
  EXPECT_EQ(restored.predict(Matrix::Zero(2, 2)), (std::vector<int>{1, 1}));
}

TEST(SupportVectorMachine, RegistryFactoriesBuildTheNamedPresets) {
  const Parameters none;
  const std::pair<const char*, std::unique_ptr<Classifier> (*)(const Parameters&)> factories[] = {
      {"linear-svm", make_linear_svm_classifier},
      {"quadratic-svm", make_quadratic_svm_classifier},
      {"cubic-svm", make_cubic_svm_classifier},
      {"fine-gaussian-svm", make_fine_gaussian_svm_classifier},
      {"medium-gaussian-svm", make_medium_gaussian_svm_classifier},
      {"coarse-gaussian-svm", make_coarse_gaussian_svm_classifier}};
  for (const auto& [name, factory] : factories) {
    const std::unique_ptr<Classifier> classifier = factory(none);
    EXPECT_EQ(classifier->name(), name);
    EXPECT_EQ(classifier->parameters().values(), make_svm(name).parameters().values());
  }
  EXPECT_THROW(make_cubic_svm_classifier(Parameters::parse("order=4", "cubic-svm")), Error);
}

}  // namespace
}  // namespace tactile::ml

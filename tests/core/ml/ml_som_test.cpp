#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "tactile/error.h"
#include "tactile/ml/som.h"
#include "tactile/random.h"

namespace tactile::ml {
namespace {

//---- Spec test vector X4: one step on a 3 x 3 grid

SomMap three_by_three() {
  SomMap map;
  map.rows = 3;
  map.columns = 3;
  map.weights.resize(9, 2);
  map.weights << 0.1, 0.1, 0.5, 0.1, 0.9, 0.1,  //
      0.1, 0.5, 0.5, 0.5, 0.9, 0.5,             //
      0.1, 0.9, 0.5, 0.9, 0.9, 0.9;
  return map;
}

TEST(SomStep, NeighbourhoodAndUpdateMatchVectorX4) {
  SomMap map = three_by_three();
  Vector x(2);
  x << 0.6, 0.45;
  EXPECT_EQ(som_winner(map, x), 4);
  const Vector theta = som_neighbourhood(map, 4, 1.5);
  const double corner = 0.263597, edge = 0.513417;
  const double expected_theta[] = {corner, edge, corner, edge, 1, edge, corner, edge, corner};
  for (int neuron = 0; neuron < 9; ++neuron)
    EXPECT_NEAR(theta(neuron), expected_theta[neuron], 5e-7) << "neuron " << neuron;

  EXPECT_EQ(som_step(map, x, 1.5, 0.5), 4);
  Matrix after(9, 2);
  after << 0.165899, 0.146129, 0.525671, 0.189848, 0.86046, 0.146129,  //
      0.228354, 0.487165, 0.55, 0.475, 0.822987, 0.487165,             //
      0.165899, 0.840691, 0.525671, 0.784481, 0.86046, 0.840691;
  EXPECT_LT((map.weights - after).cwiseAbs().maxCoeff(), 5e-7);
}

TEST(SomStep, NeuronsOutsideTheBubbleStayPut) {
  SomMap map = three_by_three();
  Vector x(2);
  x << 0.1, 0.1;  // winner 0 at the corner
  const Matrix before = map.weights;
  // r = 1: only the winner itself has grid distance < 1.
  EXPECT_EQ(som_step(map, x, 1.0, 0.5), 0);
  EXPECT_EQ(map.weights.bottomRows(8), before.bottomRows(8));
  const Vector theta = som_neighbourhood(map, 0, 2.0);
  EXPECT_EQ(theta(8), 0.0);  // distance sqrt(8) >= 2
  EXPECT_NEAR(theta(4), std::exp(-2.0 / 2.0), 1e-15);
}

TEST(SomSchedule, DefaultSchedulesMatchVectorX4) {
  const SomSchedule schedule;
  const std::tuple<int, double, double> expected[] = {{0, 7, 0.5},
                                                      {1, 6.99349, 0.498046},
                                                      {499, 3.75325, 0.0708493},
                                                      {998, 0.506507, 0.0100392},
                                                      {999, 0.5, 0.01}};
  for (const auto& [epoch, radius, rate] : expected) {
    EXPECT_NEAR(schedule.radius(epoch), radius, 5e-6) << "epoch " << epoch;
    EXPECT_NEAR(schedule.rate(epoch), rate, rate * 5e-6) << "epoch " << epoch;
  }
}

//---- Training and labelling

Matrix two_blobs(int per_class, uint64_t seed, std::vector<int>& labels) {
  Random random{std::mt19937_64(seed)};
  Matrix x(2 * per_class, 2);
  labels.clear();
  for (int row = 0; row < 2 * per_class; ++row) {
    const int label = row % 2;
    x(row, 0) = (label ? 5.0 : 0.0) + random.normal(0.0, 0.5);
    x(row, 1) = (label ? 3.0 : -1.0) + random.normal(0.0, 0.5);
    labels.push_back(label);
  }
  return x;
}

TEST(SomClassifier, OrdersAOneDimensionalRampAlongTheChain) {
  const int count = 50;
  Matrix ramp(count, 1);
  for (int row = 0; row < count; ++row) ramp(row, 0) = row / (count - 1.0);
  SomClassifier som(Parameters::parse("rows=1,columns=10,epochs=200", "test"));
  som.fit(ramp, std::vector<int>(count, 0), 1, 3);
  const Vector weights = som.map().weights.col(0);
  const bool increasing = ((weights.tail(9) - weights.head(9)).array() > 0.0).all();
  const bool decreasing = ((weights.tail(9) - weights.head(9)).array() < 0.0).all();
  EXPECT_TRUE(increasing || decreasing) << weights.transpose();
  // The chain spreads over the ramp instead of collapsing onto its middle.
  EXPECT_LT(weights.minCoeff(), 0.1);
  EXPECT_GT(weights.maxCoeff(), 0.9);
  ASSERT_EQ(som.training_errors().size(), 200u);
  EXPECT_LT(som.training_errors().back().mean, som.training_errors().front().mean);
}

TEST(SomClassifier, LabelsTwoBlobsIntoTwoRegions) {
  std::vector<int> labels;
  const Matrix train = two_blobs(40, 11, labels);
  SomClassifier som(Parameters::parse("rows=5,columns=5,epochs=100", "test"));
  som.fit(train, labels, 2, 5);
  const SomMap& map = som.map();
  EXPECT_EQ(map.rows, 5);
  EXPECT_EQ(map.columns, 5);
  ASSERT_EQ(map.weights.rows(), 25);
  int hits = 0;
  std::set<int> classes;
  for (int neuron = 0; neuron < 25; ++neuron) {
    hits += map.hits[neuron];
    classes.insert(map.neuron_class[neuron]);
  }
  EXPECT_EQ(hits, 80);
  EXPECT_EQ(classes, (std::set<int>{0, 1}));  // every neuron labelled, both regions present
  EXPECT_EQ(som.predict(train), labels);

  std::vector<int> test_labels;
  const Matrix test = two_blobs(20, 99, test_labels);
  const std::vector<int> predicted = som.predict(test);
  EXPECT_EQ(predicted, test_labels);
  const Matrix scores = som.scores(test);
  ASSERT_EQ(scores.rows(), 40);
  ASSERT_EQ(scores.cols(), 2);
  for (Eigen::Index row = 0; row < scores.rows(); ++row) {
    Eigen::Index best = 0;
    scores.row(row).maxCoeff(&best);
    EXPECT_EQ(best, predicted[static_cast<size_t>(row)]);
    EXPECT_LE(scores(row, best), 0.0);  // minus a distance
  }
}

TEST(SomClassifier, EmptyNeuronsTakeTheNearestLabelledNeuronOrStayUnknown) {
  Matrix x(2, 2);
  x << 0, 0, 1, 1;
  const std::vector<int> labels{0, 1};
  SomClassifier nearest(Parameters::parse("epochs=50", "test"));
  nearest.fit(x, labels, 2, 2);
  const SomMap& map = nearest.map();
  ASSERT_EQ(map.weights.rows(), 49);
  std::vector<int> winners;
  for (int neuron = 0; neuron < 49; ++neuron)
    if (map.hits[neuron] > 0) winners.push_back(neuron);
  ASSERT_EQ(winners.size(), 2u);  // two inputs, two distinct winners
  for (int neuron = 0; neuron < 49; ++neuron) {
    ASSERT_NE(map.neuron_class[neuron], kUnknownClass);
    if (map.hits[neuron] > 0) continue;
    // Its label is that of a winner at the smallest grid distance.
    int best = std::numeric_limits<int>::max();
    for (const int winner : winners) {
      const int dx = neuron % 7 - winner % 7, dy = neuron / 7 - winner / 7;
      best = std::min(best, dx * dx + dy * dy);
    }
    bool found = false;
    for (const int winner : winners) {
      const int dx = neuron % 7 - winner % 7, dy = neuron / 7 - winner / 7;
      found |= dx * dx + dy * dy == best && map.neuron_class[winner] == map.neuron_class[neuron];
    }
    EXPECT_TRUE(found) << "neuron " << neuron;
  }

  SomClassifier unknown(Parameters::parse("epochs=50,empty=unknown", "test"));
  unknown.fit(x, labels, 2, 2);
  int unlabelled = 0;
  for (int neuron = 0; neuron < 49; ++neuron)
    unlabelled += unknown.map().neuron_class[neuron] == kUnknownClass;
  EXPECT_EQ(unlabelled, 47);
  // The same weights (same seed): a query won by an empty neuron is answered unknown.
  EXPECT_EQ(unknown.map().weights, nearest.map().weights);
  bool answered_unknown = false;
  for (int neuron = 0; neuron < 49 && !answered_unknown; ++neuron) {
    if (unknown.map().hits[neuron] > 0) continue;
    const Matrix query = unknown.map().weights.row(neuron);  // scale: x in [0, 1] maps to itself
    answered_unknown = unknown.predict(query)[0] == kUnknownClass;
  }
  EXPECT_TRUE(answered_unknown);
}

TEST(SomClassifier, SameSeedSameMapOtherSeedOtherMap) {
  std::vector<int> labels;
  const Matrix x = two_blobs(10, 4, labels);
  SomClassifier first(Parameters::parse("epochs=20", "test"));
  SomClassifier second(Parameters::parse("epochs=20", "test"));
  SomClassifier other(Parameters::parse("epochs=20", "test"));
  first.fit(x, labels, 2, 8);
  second.fit(x, labels, 2, 8);
  other.fit(x, labels, 2, 9);
  EXPECT_EQ(first.map().weights, second.map().weights);
  EXPECT_NE(first.map().weights, other.map().weights);
}

TEST(SomClassifier, InputsAreMinMaxScaledWithoutClipping) {
  Matrix x(3, 3);
  x << 0, 10, 4,  //
      2, 20, 4,   //
      4, 30, 4;   // the last feature is constant
  SomClassifier som(Parameters::parse("epochs=5", "test"));
  som.fit(x, {0, 1, 1}, 2, 1);
  Matrix query(1, 3);
  query << 6, 15, 9;
  const Matrix scaled = som.scale(query);
  EXPECT_DOUBLE_EQ(scaled(0, 0), 1.5);  // beyond the training maximum, kept
  EXPECT_DOUBLE_EQ(scaled(0, 1), 0.25);
  EXPECT_DOUBLE_EQ(scaled(0, 2), 0.0);  // constant in training -> 0
  EXPECT_TRUE(som.scores(query).allFinite());
  SomClassifier raw(Parameters::parse("epochs=5,scale=false", "test"));
  raw.fit(x, {0, 1, 1}, 2, 1);
  EXPECT_EQ(raw.scale(query), query);
}

TEST(SomClassifier, OneSampleClassOwnsItsWinner) {
  std::vector<int> labels;
  Matrix x = two_blobs(10, 6, labels);
  Matrix extended(21, 2);
  extended << x, (Matrix(1, 2) << 10.0, -6.0).finished();
  labels.push_back(2);
  SomClassifier som(Parameters::parse("epochs=100", "test"));
  som.fit(extended, labels, 3, 3);
  EXPECT_EQ(som.predict(extended.bottomRows(1))[0], 2);
}

TEST(SomClassifier, BadInputNamesTheProblem) {
  std::vector<int> labels;
  Matrix x = two_blobs(5, 1, labels);
  SomClassifier som(Parameters::parse("epochs=3", "test"));
  EXPECT_THROW(som.fit(Matrix(0, 2), {}, 2, 0), Error);
  EXPECT_THROW(som.fit(x, {0, 1}, 2, 0), Error);
  EXPECT_THROW(som.fit(x, labels, 1, 0), Error);
  EXPECT_THROW(som.predict(x), Error);  // not fitted
  x(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(som.fit(x, labels, 2, 0), Error);
  x(2, 1) = 0.0;
  som.fit(x, labels, 2, 0);
  EXPECT_THROW(som.scores(Matrix::Zero(1, 3)), Error);
  Matrix query = Matrix::Zero(1, 2);
  query(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(som.predict(query), Error);
}

TEST(SomClassifier, BadParametersAreRejected) {
  EXPECT_THROW(SomClassifier(Parameters::parse("size=7", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("rows=0", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("epochs=0", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("radius_end=0", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("rate_start=-1", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("initial=gauss", "test")), Error);
  EXPECT_THROW(SomClassifier(Parameters::parse("empty=drop", "test")), Error);
  const Parameters effective = SomClassifier(Parameters::parse("rows=4", "test")).parameters();
  EXPECT_EQ(effective.text("radius_start", ""), "7");  // max(rows, columns)
  EXPECT_EQ(effective.text("epochs", ""), "1000");
}

TEST(SomClassifier, TruncatedNormalInitialWeightsStayInsideTheirRange) {
  std::vector<int> labels;
  const Matrix x = two_blobs(5, 2, labels);
  // rate_start tiny: training barely moves the weights away from their initial values.
  SomClassifier som(Parameters::parse("epochs=1,initial=normal,rate_start=1e-12,rows=20", "test"));
  som.fit(x, labels, 2, 4);
  const Matrix& weights = som.map().weights;  // 140 neurons x 2 = 280 draws
  EXPECT_GE(weights.minCoeff(), 0.1 - 1e-9);
  EXPECT_LE(weights.maxCoeff(), 0.9 + 1e-9);
  EXPECT_NEAR(weights.mean(), 0.5, 0.04);
  // N(0.5, 0.2^2) cut at +-2 sigma has std 0.176; uniform on [0.1, 0.9] would give 0.231.
  const double deviation = std::sqrt((weights.array() - weights.mean()).square().mean());
  EXPECT_LT(deviation, 0.205);
  EXPECT_GT(deviation, 0.15);
}

TEST(SomClassifier, SavedModelGivesIdenticalScores) {
  std::vector<int> labels;
  const Matrix x = two_blobs(15, 3, labels);
  SomClassifier som(Parameters::parse("rows=4,columns=6,epochs=30,empty=unknown", "test"));
  som.fit(x, labels, 2, 12);
  SomClassifier restored;
  restored.load(nlohmann::json::parse(som.save().dump()));
  std::vector<int> test_labels;
  const Matrix test = two_blobs(10, 77, test_labels);
  EXPECT_EQ(restored.scores(test), som.scores(test));
  EXPECT_EQ(restored.predict(test), som.predict(test));
  EXPECT_EQ(restored.map().weights, som.map().weights);
  EXPECT_EQ(restored.map().neuron_class, som.map().neuron_class);
  EXPECT_EQ(restored.map().hits, som.map().hits);
  EXPECT_EQ(restored.parameters().values(), som.parameters().values());
  nlohmann::json broken = som.save();
  broken["hits"].erase(0);
  EXPECT_THROW(restored.load(broken), Error);
}

}  // namespace
}  // namespace tactile::ml

namespace tactile::ml {
namespace {

// A table much wider than long, as Robovie's pair correlations (183 x 37,401): rows near one
// of three centres in 400 columns.
Matrix wide_table(std::vector<int>& labels) {
  Random random{std::mt19937_64(3)};
  Matrix centres(3, 400);
  for (Eigen::Index k = 0; k < centres.size(); ++k) centres.data()[k] = random.uniform(0.0, 1.0);
  Matrix x(30, 400);
  labels.clear();
  for (int row = 0; row < 30; ++row) {
    labels.push_back(row % 3);
    for (int column = 0; column < 400; ++column)
      x(row, column) = centres(row % 3, column) + random.uniform(-0.2, 0.2);
  }
  return x;
}

TEST(SomClassifier, AWideTableTrainedInTheSpanOfItsRowsGivesTheSameMap) {
  std::vector<int> labels;
  const Matrix x = wide_table(labels);
  SomClassifier reduced(Parameters::parse("epochs=60", "test"));
  SomClassifier whole(Parameters::parse("epochs=60,subspace=false", "test"));
  reduced.fit(x, labels, 3, 7);
  whole.fit(x, labels, 3, 7);
  ASSERT_EQ(reduced.map().weights.cols(), 400);
  EXPECT_LT((reduced.map().weights - whole.map().weights).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(reduced.map().hits, whole.map().hits);
  EXPECT_EQ(reduced.map().neuron_class, whole.map().neuron_class);
  ASSERT_EQ(reduced.training_errors().size(), whole.training_errors().size());
  for (size_t epoch = 0; epoch < whole.training_errors().size(); ++epoch)
    EXPECT_NEAR(reduced.training_errors()[epoch].mean, whole.training_errors()[epoch].mean, 1e-9);
  EXPECT_EQ(reduced.predict(x), whole.predict(x));
  EXPECT_EQ(reduced.parameters().text("subspace", ""), "true");
}

TEST(SomQuality, QuantisationAndTopographicErrorOfAKnownMap) {
  // A 1 x 3 chain at 0, 1, 2 on a line.
  SomMap map;
  map.rows = 1;
  map.columns = 3;
  map.weights = Matrix{{0.0}, {1.0}, {2.0}};
  // 0.25: winner 0 (0.25), then 1: neighbours. 1.9: winner 2 (0.1), then 1: neighbours.
  const SomQuality good = som_quality(map, Matrix{{0.25}, {1.9}});
  EXPECT_NEAR(good.quantisation_error, (0.25 + 0.1) / 2, 1e-12);
  EXPECT_EQ(good.topographic_error, 0.0);
  // Folded: neurons 0 and 2 hold 0 and 1. 0.4: winner 0, then 2, two steps apart; 1.9:
  // winner 1, then 2: neighbours.
  map.weights = Matrix{{0.0}, {2.0}, {1.0}};
  const SomQuality folded = som_quality(map, Matrix{{0.4}, {1.9}});
  EXPECT_NEAR(folded.quantisation_error, (0.4 + 0.1) / 2, 1e-12);
  EXPECT_EQ(folded.topographic_error, 0.5);
}

}  // namespace
}  // namespace tactile::ml

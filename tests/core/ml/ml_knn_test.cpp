// k-NN and its presets: known neighbours on tiny sets, weights, ties, the subspace
// ensemble, bad input and the save/load round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <tuple>

#include "tactile/error.h"
#include "tactile/ml/classifier.h"
#include "tactile/ml/knn.h"

namespace tactile::ml {
namespace {

Matrix rows(std::initializer_list<std::initializer_list<double>> values) {
  Matrix matrix(static_cast<Eigen::Index>(values.size()),
                static_cast<Eigen::Index>(values.begin()->size()));
  Eigen::Index row = 0;
  for (const auto& line : values) {
    Eigen::Index column = 0;
    for (double value : line) matrix(row, column++) = value;
    ++row;
  }
  return matrix;
}

// Two Gaussian blobs in `dimensions` dimensions, `per_class` rows each, centres 6 apart.
void blobs(int per_class, int dimensions, uint64_t seed, Matrix& x, std::vector<int>& y) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  x.resize(2 * per_class, dimensions);
  y.clear();
  for (int row = 0; row < 2 * per_class; ++row) {
    const int label = row % 2;
    for (int column = 0; column < dimensions; ++column)
      x(row, column) = normal(random) + (label == 1 ? 6.0 : 0.0);
    y.push_back(label);
  }
}

TEST(KnnClassifier, OneNeighbourTakesTheClassOfTheClosestSample) {
  auto knn = make_classifier("knn:k=1");
  knn->fit(rows({{0, 0}, {10, 0}, {0, 10}}), {0, 1, 2}, 3, 1);
  const auto predicted = knn->predict(rows({{1, 1}, {9, 2}, {-1, 8}}));
  EXPECT_EQ(predicted, (std::vector<int>{0, 1, 2}));
  const Matrix scores = knn->scores(rows({{9, 2}}));
  EXPECT_DOUBLE_EQ(scores(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(scores(0, 0), 0.0);
}

TEST(KnnClassifier, NeighboursAreOrderedByDistanceThenTrainingOrder) {
  KnnClassifier knn("knn", {3, KnnMetric::kEuclidean, KnnWeights::kEqual, false});
  // Rows 1 and 3 are both at distance 2 from the origin; row 1 comes first.
  knn.fit(rows({{5, 0}, {2, 0}, {1, 0}, {0, 2}}), {0, 1, 1, 0}, 2, 1);
  const auto nearest = knn.neighbours(rows({{0, 0}}))[0];
  ASSERT_EQ(nearest.size(), 3u);
  EXPECT_EQ(nearest[0].row, 2);
  EXPECT_EQ(nearest[1].row, 1);
  EXPECT_EQ(nearest[2].row, 3);
  EXPECT_DOUBLE_EQ(nearest[1].distance, 2.0);
}

TEST(KnnClassifier, EqualVotesDecideAndInverseDistancesScore) {
  // Neighbours of 0.5: 0 and 1 (class 0, both at 1/2), 2 (class 1, at 3/2). The votes 2 : 1
  // decide; the scores weigh each by 1/d: 2 + 2 against 2/3, i.e. 6/7 and 1/7.
  auto knn = make_classifier("knn:k=3");
  knn->fit(rows({{0}, {1}, {2}, {10}}), {0, 0, 1, 1}, 2, 1);
  const Matrix scores = knn->scores(rows({{0.5}}));
  EXPECT_NEAR(scores(0, 0), 6.0 / 7.0, 1e-15);
  EXPECT_NEAR(scores(0, 1), 1.0 / 7.0, 1e-15);
  EXPECT_NEAR(scores.row(0).sum(), 1.0, 1e-15);
  EXPECT_EQ(knn->predict(rows({{0.5}}))[0], 0);
  EXPECT_EQ(knn->decide(rows({{0.5}})).scores, scores);
  // Two queries with the same 2 : 1 votes rank by their distances: 0.9's neighbours of class
  // 0 are at 0.9 and 0.1, its class-1 neighbour at 1.1 (shares 1/0.9 + 10 against 1/1.1).
  const Matrix closer = knn->scores(rows({{0.9}}));
  EXPECT_NEAR(closer(0, 0), (1 / 0.9 + 10) / (1 / 0.9 + 10 + 1 / 1.1), 1e-12);
  EXPECT_GT(closer(0, 0), scores(0, 0));
}

TEST(KnnClassifier, AMajorityOfFarNeighboursWinsWithMarginZero) {
  // Neighbours of 0: 1 (class 1), 2 and -3 (class 0). The votes say 0 (spec §4.9: majority);
  // the scores weigh 1 against 1/2 + 1/3, so class 1 holds 6/11 and the prediction is the
  // least sure there is.
  auto knn = make_classifier("knn:k=3");
  knn->fit(rows({{1}, {2}, {-3}, {50}}), {1, 0, 0, 1}, 2, 1);
  const Classifier::Decisions decisions = knn->decide(rows({{0}}));
  EXPECT_EQ(decisions.classes[0], 0);
  EXPECT_NEAR(decisions.scores(0, 1), 6.0 / 11.0, 1e-15);
  EXPECT_NEAR(decisions.scores(0, 0), 5.0 / 11.0, 1e-15);
  EXPECT_EQ(confidence_of(decisions.scores.row(0).transpose(), 0).margin, 0.0);
}

TEST(KnnClassifier, ANeighbourAtDistanceZeroTakesTheWholeScoreUnderEqualVotes) {
  auto knn = make_classifier("knn:k=3");
  knn->fit(rows({{0}, {0}, {0.1}, {5}}), {1, 0, 0, 1}, 2, 1);
  const Matrix scores = knn->scores(rows({{0}}));
  EXPECT_TRUE(scores.allFinite());
  EXPECT_DOUBLE_EQ(scores(0, 0), 0.5);  // the two exact matches share it
  EXPECT_DOUBLE_EQ(scores(0, 1), 0.5);
}

TEST(KnnClassifier, SquaredInverseWeightsFavourTheCloseMinority) {
  // Neighbours at distances 1 (class 1), 2 and 2 (class 0): equal votes say 0,
  // 1/d^2 says 1 (weight 1 against 1/4 + 1/4).
  const Matrix train = rows({{1}, {2}, {-2}, {50}});
  const std::vector<int> labels = {1, 0, 0, 1};
  auto equal = make_classifier("knn:k=3,weights=equal");
  auto weighted = make_classifier("knn:k=3,weights=squared-inverse");
  equal->fit(train, labels, 2, 1);
  weighted->fit(train, labels, 2, 1);
  EXPECT_EQ(equal->predict(rows({{0}}))[0], 0);
  EXPECT_EQ(weighted->predict(rows({{0}}))[0], 1);
  EXPECT_NEAR(weighted->scores(rows({{0}}))(0, 1), 1.0 / 1.5, 1e-12);
  auto inverse = make_classifier("knn:k=3,weights=inverse");
  inverse->fit(train, labels, 2, 1);
  EXPECT_NEAR(inverse->scores(rows({{0}}))(0, 1), 1.0 / 2.0, 1e-12);  // 1 against 1/2 + 1/2
}

TEST(KnnClassifier, ASampleAtDistanceZeroTakesTheWholeWeightedVote) {
  auto weighted = make_classifier("knn:k=3,weights=squared-inverse");
  weighted->fit(rows({{0}, {0.1}, {-0.1}}), {1, 0, 0}, 2, 1);
  const Matrix scores = weighted->scores(rows({{0}}));
  EXPECT_TRUE(scores.allFinite());
  EXPECT_DOUBLE_EQ(scores(0, 1), 1.0);
}

TEST(KnnClassifier, TiedVotesGoToTheNearestNeighboursClass) {
  // Spec §4.9: k = 2 with one vote each; class 1 owns the nearest neighbour, although
  // argmax-first would answer class 0.
  auto knn = make_classifier("knn:k=2");
  knn->fit(rows({{3}, {1}}), {0, 1}, 2, 1);
  EXPECT_EQ(knn->predict(rows({{0}}))[0], 1);
}

TEST(KnnClassifier, CosineDistanceIgnoresLengthAndPutsTheZeroVectorAtOne) {
  KnnClassifier knn("knn", {2, KnnMetric::kCosine, KnnWeights::kEqual, false});
  knn.fit(rows({{10, 0}, {0, 1}, {0, 0}}), {0, 1, 1}, 2, 1);
  const auto nearest = knn.neighbours(rows({{1, 0.1}}))[0];
  EXPECT_EQ(nearest[0].row, 0);  // far away but in the same direction
  EXPECT_NEAR(nearest[0].distance, 1.0 - 1.0 / std::sqrt(1.01), 1e-12);
  const auto from_zero = knn.neighbours(rows({{0, 0}}))[0];
  EXPECT_DOUBLE_EQ(from_zero[0].distance, 1.0);
  EXPECT_DOUBLE_EQ(from_zero[1].distance, 1.0);
}

TEST(KnnClassifier, StandardisingLetsASmallScaleFeatureCount) {
  // Feature 1 separates the classes but spans 0.01; feature 0 spans 110 and misleads.
  const Matrix train = rows({{0, 0.00}, {10, 0.01}, {100, 0.00}, {110, 0.01}});
  const std::vector<int> labels = {0, 1, 0, 1};
  auto raw = make_classifier("knn:k=1");
  auto standardised = make_classifier("knn:k=1,standardize=true");
  raw->fit(train, labels, 2, 1);
  standardised->fit(train, labels, 2, 1);
  EXPECT_EQ(raw->predict(rows({{3, 0.01}}))[0], 0);
  EXPECT_EQ(standardised->predict(rows({{3, 0.01}}))[0], 1);
}

TEST(KnnClassifier, RangeScalingMapsEachFeaturesTrainingRangeOntoZeroToOne) {
  // Weka's normalisation (spec §1.15): (x - min) / (max - min) of the training rows, a
  // constant feature left as it is. Training {2, 10, 5}, {6, 30, 5} become {0, 0, 0}, {1, 1, 0};
  // the query {3, 20, 5} becomes {0.25, 0.5, 0}.
  auto classifier = make_classifier("knn:k=2,standardize=range");
  EXPECT_EQ(classifier->parameters().text("standardize", ""), "range");
  classifier->fit(rows({{2, 10, 5}, {6, 30, 5}}), {0, 1}, 2, 1);
  const auto* knn = dynamic_cast<const KnnClassifier*>(classifier.get());
  ASSERT_NE(knn, nullptr);
  const auto nearest = knn->neighbours(rows({{3, 20, 5}}));
  ASSERT_EQ(nearest[0].size(), 2u);
  EXPECT_EQ(nearest[0][0].row, 0);
  EXPECT_NEAR(nearest[0][0].distance, std::sqrt(0.25 * 0.25 + 0.5 * 0.5), 1e-12);
  EXPECT_NEAR(nearest[0][1].distance, std::sqrt(0.75 * 0.75 + 0.5 * 0.5), 1e-12);
  // Saved and loaded, the same scaling.
  const auto restored = load_classifier(nlohmann::json::parse(save_classifier(*classifier).dump()));
  EXPECT_EQ(specification_of(*restored), specification_of(*classifier));
  EXPECT_EQ(restored->scores(rows({{3, 20, 5}})), classifier->scores(rows({{3, 20, 5}})));
  try {
    make_classifier("knn:standardize=sometimes");
    ADD_FAILURE() << "standardize=sometimes was taken";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("expected true, false or range"), std::string::npos)
        << error.what();
  }
}

TEST(KnnClassifier, PresetsCarryTheirMatlabSettings) {
  const auto cosine = make_classifier("cosine-knn");
  EXPECT_EQ(cosine->parameters().text("metric", ""), "cosine");
  EXPECT_EQ(cosine->parameters().integer("k", 0), 10);
  EXPECT_EQ(cosine->parameters().text("weights", ""), "equal");
  EXPECT_TRUE(cosine->parameters().flag("standardize", false));
  const auto weighted = make_classifier("weighted-knn");
  EXPECT_EQ(weighted->parameters().text("metric", ""), "euclidean");
  EXPECT_EQ(weighted->parameters().text("weights", ""), "squared-inverse");
  EXPECT_EQ(make_classifier("weighted-knn:k=4")->parameters().integer("k", 0), 4);
}

TEST(KnnClassifier, MoreNeighboursThanSamplesUsesThemAll) {
  auto knn = make_classifier("knn:k=10");
  knn->fit(rows({{0}, {1}, {2}}), {0, 1, 1}, 2, 1);
  // All three count: 1/d of 0.5 for class 0, of 0.5 and 1.5 for class 1: 2 against 8/3.
  EXPECT_NEAR(knn->scores(rows({{0.5}}))(0, 1), 4.0 / 7.0, 1e-15);
  EXPECT_EQ(knn->predict(rows({{0.5}}))[0], 1);
}

TEST(KnnClassifier, BadParametersNameTheKey) {
  EXPECT_THROW(make_classifier("knn:k=0"), Error);
  EXPECT_THROW(make_classifier("knn:metric=manhattan"), Error);
  EXPECT_THROW(make_classifier("knn:weights=linear"), Error);
  try {
    make_classifier("knn:neighbours=3");
    FAIL() << "an unknown key was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("neighbours"), std::string::npos);
  }
}

TEST(KnnClassifier, RejectsNaNZeroSamplesAndWrongWidth) {
  auto knn = make_classifier("knn");
  Matrix bad = rows({{0, 1}, {1, 2}});
  bad(1, 0) = std::nan("");
  EXPECT_THROW(knn->fit(bad, {0, 1}, 2, 1), Error);
  EXPECT_THROW(knn->fit(Matrix(0, 2), {}, 2, 1), Error);
  EXPECT_THROW(knn->fit(rows({{0}, {1}}), {0, 2}, 2, 1), Error);
  EXPECT_THROW(knn->predict(rows({{0}})), Error);  // not fitted
  knn->fit(rows({{0, 1}, {1, 2}}), {0, 1}, 2, 1);
  EXPECT_THROW(knn->predict(rows({{0, 1, 2}})), Error);
  Matrix query = rows({{0, 1}});
  query(0, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(knn->scores(query), Error);
}

TEST(KnnClassifier, ConstantFeaturesAndOneSampleClassesGiveFiniteScores) {
  // Constant column 1, more features than samples, class 2 with one sample.
  const Matrix train = rows({{0, 5, 1, 2, 3}, {1, 5, 1, 2, 3}, {9, 5, 1, 2, 3}});
  for (const char* name : {"knn:standardize=true", "cosine-knn", "weighted-knn", "subspace-knn"}) {
    auto classifier = make_classifier(name);
    classifier->fit(train, {0, 0, 1}, 3, 7);
    const Matrix scores = classifier->scores(rows({{8, 5, 1, 2, 3}, {0, 0, 0, 0, 0}}));
    EXPECT_TRUE(scores.allFinite()) << name;
    EXPECT_NEAR(scores.row(0).sum(), 1.0, 1e-12) << name;
  }
}

TEST(SubspaceKnn, LearnersUseHalfThePredictorsDrawnFromTheSeed) {
  Matrix x;
  std::vector<int> y;
  blobs(20, 7, 3, x, y);
  SubspaceKnnClassifier first(30, 0, KnnMetric::kEuclidean, true);
  SubspaceKnnClassifier second(30, 0, KnnMetric::kEuclidean, true);
  SubspaceKnnClassifier other(30, 0, KnnMetric::kEuclidean, true);
  first.fit(x, y, 2, 11);
  second.fit(x, y, 2, 11);
  other.fit(x, y, 2, 12);
  ASSERT_EQ(first.subspaces().size(), 30u);
  for (const auto& subspace : first.subspaces()) {
    EXPECT_EQ(subspace.size(), 4u);  // ceil(7 / 2)
    EXPECT_TRUE(std::is_sorted(subspace.begin(), subspace.end()));
    EXPECT_TRUE(std::adjacent_find(subspace.begin(), subspace.end()) == subspace.end());
  }
  EXPECT_EQ(first.subspaces(), second.subspaces());
  EXPECT_NE(first.subspaces(), other.subspaces());
}

TEST(SubspaceKnn, ScoresAreLearnerVoteFractions) {
  Matrix x;
  std::vector<int> y;
  blobs(15, 6, 5, x, y);
  auto ensemble = make_classifier("subspace-knn");
  ensemble->fit(x, y, 2, 1);
  Matrix queries(2, 6);
  queries.row(0).setConstant(0.0);
  queries.row(1).setConstant(6.0);
  const Matrix scores = ensemble->scores(queries);
  EXPECT_DOUBLE_EQ(scores(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(scores(1, 1), 1.0);
  // Votes of 30 learners come in steps of 1/30.
  const Matrix mixed = ensemble->scores(x.topRows(10).array() * 0.5 + 1.5);
  for (Eigen::Index row = 0; row < mixed.rows(); ++row) {
    EXPECT_NEAR(mixed.row(row).sum(), 1.0, 1e-12);
    const double thirtieths = mixed(row, 0) * 30.0;
    EXPECT_NEAR(thirtieths, std::round(thirtieths), 1e-9);
  }
}

TEST(KnnClassifier, SaveLoadRoundTripGivesIdenticalScores) {
  Matrix x;
  std::vector<int> y;
  blobs(12, 3, 9, x, y);
  const Matrix queries = x.array() * 0.7 + 1.1;
  for (const char* name : {"knn:k=3", "cosine-knn", "weighted-knn", "subspace-knn:learners=5"}) {
    auto classifier = make_classifier(name);
    classifier->fit(x, y, 2, 4);
    const nlohmann::json document = nlohmann::json::parse(save_classifier(*classifier).dump());
    const auto restored = load_classifier(document);
    EXPECT_EQ(restored->name(), classifier->name());
    EXPECT_EQ(specification_of(*restored), specification_of(*classifier));
    const Matrix before = classifier->scores(queries);
    const Matrix after = restored->scores(queries);
    EXPECT_EQ(before, after) << name;
  }
}

// The block search (a single-precision product picks candidates, exact distances decide)
// finds exactly the neighbours a one-query-at-a-time exact search finds, ties included:
// integer features give many samples at equal distance, large offsets stress rounding.
TEST(KnnClassifier, BlockSearchMatchesExactSearchIncludingTies) {
  std::mt19937_64 random(11);
  std::uniform_int_distribution<int> small(0, 3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& [dimensions, offset, metric] :
       {std::tuple{3, 0.0, "euclidean"}, std::tuple{40, 1e4, "euclidean"},
        std::tuple{5, 0.0, "cosine"}, std::tuple{300, 50.0, "euclidean"}}) {
    const int samples = 700, queries = 300;  // more queries than one block
    Matrix x(samples, dimensions), q(queries, dimensions);
    for (Eigen::Index r = 0; r < samples; ++r)
      for (Eigen::Index c = 0; c < dimensions; ++c)
        x(r, c) = offset + (dimensions <= 5 ? small(random) : normal(random));
    for (Eigen::Index r = 0; r < queries; ++r)
      for (Eigen::Index c = 0; c < dimensions; ++c)
        q(r, c) =
            r % 3 == 0 ? x(r, c) : offset + (dimensions <= 5 ? small(random) : normal(random));
    std::vector<int> y(samples);
    for (int r = 0; r < samples; ++r) y[static_cast<size_t>(r)] = r % 3;
    KnnClassifier knn(
        "knn",
        KnnSettings{7, std::string(metric) == "cosine" ? KnnMetric::kCosine : KnnMetric::kEuclidean,
                    KnnWeights::kEqual, false});
    knn.fit(x, y, 3, 1);
    const auto found = knn.neighbours(q);
    for (Eigen::Index r = 0; r < queries; ++r) {
      std::vector<std::pair<double, int64_t>> all;
      for (Eigen::Index s = 0; s < samples; ++s) {
        double distance;
        if (std::string(metric) == "cosine") {
          const double product = q.row(r).norm() * x.row(s).norm();
          distance = product > 0 ? std::max(0.0, 1.0 - x.row(s).dot(q.row(r)) / product) : 1.0;
        } else {
          distance = (x.row(s) - q.row(r)).norm();
        }
        all.emplace_back(distance, s);
      }
      std::sort(all.begin(), all.end());
      ASSERT_EQ(found[static_cast<size_t>(r)].size(), 7u);
      for (size_t k = 0; k < 7; ++k) {
        EXPECT_EQ(found[static_cast<size_t>(r)][k].row, all[k].second)
            << metric << " " << dimensions << " query " << r << " rank " << k;
        EXPECT_NEAR(found[static_cast<size_t>(r)][k].distance, all[k].first,
                    1e-9 * (1 + all[k].first));
      }
    }
  }
}

}  // namespace
}  // namespace tactile::ml

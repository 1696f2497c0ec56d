#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/tree.h"

namespace tactile::ml {
namespace {

DecisionTree make_tree(const std::string& preset, const std::string& parameters = "") {
  return DecisionTree(preset, Parameters::parse(parameters, preset));
}

TEST(DecisionTree, SplitsOneFeatureAtTheMidpointOfTheGap) {
  const Matrix x = toy::column({1, 2, 3, 4, 10, 11, 12, 13});
  DecisionTree tree = make_tree("tree", "min_parent=2");
  tree.fit(x, {0, 0, 0, 0, 1, 1, 1, 1}, 2, 0);
  ASSERT_EQ(tree.nodes().size(), 3u);
  EXPECT_EQ(tree.nodes()[0].feature, 0);
  EXPECT_EQ(tree.nodes()[0].threshold, 7.0);
  EXPECT_EQ(tree.nodes()[1].class_fractions, (std::vector<double>{1.0, 0.0}));
  EXPECT_EQ(tree.nodes()[2].class_fractions, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(tree.predict(toy::column({6.99, 7.0})), (std::vector<int>{0, 1}));
}

TEST(DecisionTree, EqualGiniCutsGoToTheLowerThreshold) {
  // Cuts 2.5 and 5.5 both leave a Gini of 1/3; the lower wins, then the right child splits.
  const Matrix x = toy::column({0, 1, 2, 3, 4, 5, 6, 7, 8});
  DecisionTree tree = make_tree("tree", "min_parent=2");
  tree.fit(x, {0, 0, 0, 1, 1, 1, 2, 2, 2}, 3, 0);
  ASSERT_EQ(tree.split_count(), 2);
  EXPECT_EQ(tree.nodes()[0].threshold, 2.5);
  EXPECT_EQ(tree.nodes()[1].feature, -1);
  EXPECT_EQ(tree.nodes()[2].threshold, 5.5);
  EXPECT_EQ(tree.predict(x), (std::vector<int>{0, 0, 0, 1, 1, 1, 2, 2, 2}));
}

TEST(DecisionTree, TheLastSplitGoesToTheNodeWithTheLargestGain) {
  // Root cut 51 separates {0, 1, 1} from {2, 2, 2, 2, 3, 3}; with one split left the right
  // node (gain 8/27) is split before the left one (gain 4/27).
  const Matrix x = toy::column({0, 1, 2, 100, 101, 102, 103, 104, 105});
  const std::vector<int> y = {0, 1, 1, 2, 2, 2, 2, 3, 3};
  DecisionTree tree = make_tree("tree", "max_splits=2,min_parent=2");
  tree.fit(x, y, 4, 0);
  ASSERT_EQ(tree.split_count(), 2);
  EXPECT_EQ(tree.nodes()[0].threshold, 51.0);
  EXPECT_EQ(tree.nodes()[1].feature, -1);
  EXPECT_EQ(tree.nodes()[2].threshold, 103.5);
  EXPECT_NEAR(tree.nodes()[1].class_fractions[1], 2.0 / 3.0, 1e-15);
  DecisionTree full = make_tree("tree", "min_parent=2");
  full.fit(x, y, 4, 0);
  EXPECT_EQ(full.split_count(), 3);
  EXPECT_EQ(full.predict(x), y);
}

TEST(DecisionTree, MediumTreeStopsAtTwentySplits) {
  const toy::LabelledSet train = toy::exclusive_or(100, 1.0, 1);  // heavily overlapping corners
  DecisionTree medium = make_tree("medium-tree");
  medium.fit(train.x, train.y, 2, 0);
  EXPECT_EQ(medium.split_count(), 20);
  DecisionTree fine = make_tree("tree");
  fine.fit(train.x, train.y, 2, 0);
  EXPECT_GT(fine.split_count(), 20);
  EXPECT_LE(fine.split_count(), 100);
  DecisionTree stump = make_tree("tree", "max_splits=0");
  stump.fit(train.x, train.y, 2, 0);
  EXPECT_EQ(stump.nodes().size(), 1u);
  EXPECT_EQ(stump.nodes()[0].class_fractions, (std::vector<double>{0.5, 0.5}));
}

TEST(DecisionTree, LearnsExclusiveOrAndThreeBlobs) {
  const toy::LabelledSet train = toy::exclusive_or(30, 0.2, 2);
  const toy::LabelledSet test = toy::exclusive_or(30, 0.2, 3);
  // Grown until pure: fitctree's MinParentSize 10 would leave mixed leaves of nine points.
  DecisionTree tree = make_tree("tree", "min_parent=2");
  tree.fit(train.x, train.y, 2, 0);
  EXPECT_EQ(toy::accuracy(tree.predict(train.x), train.y), 1.0);
  EXPECT_GE(toy::accuracy(tree.predict(test.x), test.y), 0.95);

  Matrix centres(3, 2);
  centres << 0, 0, 5, 0, 0, 5;
  const toy::LabelledSet blobs = toy::blobs(centres, 30, 1.0, 4);
  const toy::LabelledSet fresh = toy::blobs(centres, 30, 1.0, 5);
  DecisionTree medium = make_tree("medium-tree");
  medium.fit(blobs.x, blobs.y, 3, 0);
  EXPECT_GE(toy::accuracy(medium.predict(fresh.x), fresh.y), 0.9);
}

TEST(DecisionTree, MinimumParentSizeStopsSmallNodes) {
  const Matrix x = toy::column({1, 2, 3, 4, 10, 11, 12, 13});
  DecisionTree tree = make_tree("medium-tree");  // fitctree's MinParentSize 10 > 8 samples
  tree.fit(x, {0, 0, 0, 0, 1, 1, 1, 1}, 2, 0);
  EXPECT_EQ(tree.split_count(), 0);
}

TEST(DecisionTree, ScoresAreTheLeafClassFractions) {
  // Equal values cannot be cut apart: the leaf at x = 1 keeps two of class 0, one of class 1.
  const Matrix x = toy::column({1, 1, 1, 2, 2});
  DecisionTree tree = make_tree("tree", "min_parent=2");
  tree.fit(x, {0, 0, 1, 1, 1}, 2, 0);
  const Matrix scores = tree.scores(toy::column({0.0, 5.0}));
  EXPECT_NEAR(scores(0, 0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(scores(0, 1), 1.0 / 3.0, 1e-15);
  EXPECT_EQ(scores(1, 1), 1.0);
  for (Eigen::Index row = 0; row < scores.rows(); ++row)
    EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-15);
}

TEST(DecisionTree, SaveAndLoadGiveIdenticalScores) {
  const toy::LabelledSet train = toy::exclusive_or(40, 0.5, 6);
  const toy::LabelledSet test = toy::exclusive_or(40, 0.5, 7);
  DecisionTree tree = make_tree("medium-tree");
  tree.fit(train.x, train.y, 2, 0);
  DecisionTree restored = make_tree("medium-tree");
  restored.load(nlohmann::json::parse(tree.save().dump()));
  EXPECT_EQ(restored.scores(test.x), tree.scores(test.x));

  nlohmann::json looped = tree.save();
  looped["nodes"][0]["left"] = 0;  // a child pointing back at its parent
  EXPECT_THROW(restored.load(looped), Error);
  nlohmann::json short_fractions = tree.save();
  short_fractions["nodes"][1]["class_fractions"] = {1.0};
  EXPECT_THROW(restored.load(short_fractions), Error);
}

TEST(DecisionTree, BadInputIsAnError) {
  DecisionTree tree = make_tree("tree");
  EXPECT_THROW(tree.fit(Matrix(0, 1), {}, 2, 0), Error);
  Matrix x = toy::column({1, 2, std::nan(""), 4});
  EXPECT_THROW(tree.fit(x, {0, 0, 1, 1}, 2, 0), Error);
  EXPECT_THROW(tree.scores(toy::column({1})), Error);  // never fitted
  tree.fit(toy::column({1, 2, 3, 4}), {0, 0, 1, 1}, 2, 0);
  EXPECT_THROW(tree.scores(Matrix::Zero(1, 3)), Error);
  EXPECT_THROW(tree.scores(toy::column({NAN})), Error);
  EXPECT_THROW(make_tree("tree", "depth=3"), Error);
  EXPECT_THROW(make_tree("tree", "max_splits=-1"), Error);
  EXPECT_THROW(make_tree("tree", "min_leaf=0"), Error);
  EXPECT_THROW(make_tree("big-tree"), Error);
}

TEST(DecisionTree, ConstantFeaturesOneSampleClassesAndWideDataAreFine) {
  // 4 samples, 6 features, only feature 4 varies; class 2 has one sample.
  Matrix x = Matrix::Constant(4, 6, 3.0);
  x.col(4) << 0, 1, 5, 9;
  DecisionTree tree = make_tree("tree", "min_parent=2");
  tree.fit(x, {0, 0, 1, 2}, 3, 0);
  EXPECT_EQ(tree.predict(x), (std::vector<int>{0, 0, 1, 2}));
  DecisionTree flat = make_tree("tree", "min_parent=2");
  flat.fit(Matrix::Constant(4, 2, 1.0), {0, 1, 1, 1}, 2, 0);
  EXPECT_EQ(flat.split_count(), 0);
  EXPECT_NEAR(flat.scores(Matrix::Zero(1, 2))(0, 1), 0.75, 1e-15);
}

TEST(DecisionTree, ParametersListTheEffectiveSettings) {
  const Parameters medium = make_tree("medium-tree").parameters();
  EXPECT_EQ(medium.integer("max_splits", 0), 20);
  EXPECT_EQ(medium.integer("min_parent", 0), 10);
  EXPECT_EQ(medium.integer("min_leaf", 0), 1);
  EXPECT_EQ(make_tree("tree").parameters().integer("max_splits", 0), 100);
}

TEST(DecisionTree, RegistryFactoriesBuildTheNamedPresets) {
  EXPECT_EQ(make_tree_classifier(Parameters())->name(), "tree");
  const auto medium = make_medium_tree_classifier(Parameters::parse("max_splits=4", "medium-tree"));
  EXPECT_EQ(medium->name(), "medium-tree");
  EXPECT_EQ(medium->parameters().integer("max_splits", 0), 4);
}

}  // namespace
}  // namespace tactile::ml

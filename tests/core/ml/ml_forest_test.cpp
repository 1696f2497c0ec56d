#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "ml_toy_sets.h"
#include "tactile/error.h"
#include "tactile/ml/boosted_trees.h"
#include "tactile/ml/forest.h"

namespace tactile::ml {
namespace {

TreeEnsemble make_ensemble(const std::string& preset, const std::string& parameters = "") {
  return TreeEnsemble(preset, Parameters::parse(parameters, preset));
}

// Three blobs in the first two columns, then `noise` columns of pure noise.
toy::LabelledSet blobs_with_noise(int per_class, int noise, uint64_t seed) {
  Matrix centres(3, 2);
  centres << 0, 0, 4, 0, 0, 4;
  toy::LabelledSet set = toy::blobs(centres, per_class, 1.0, seed);
  std::mt19937_64 engine(seed + 1);
  Matrix x(set.x.rows(), 2 + noise);
  x.leftCols(2) = set.x;
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    for (int column = 0; column < noise; ++column) x(row, 2 + column) = toy::normal(engine);
  set.x = x;
  return set;
}

TEST(TreeEnsemble, PresetsTakeMatlabsAndScikitLearnsDefaults) {
  EXPECT_EQ(make_ensemble("bagged-trees").parameters().values(),
            (std::map<std::string, std::string>{
                {"trees", "30"}, {"predictors", "all"}, {"max_splits", "n-1"}, {"min_leaf", "1"}}));
  EXPECT_EQ(
      make_ensemble("random-forest").parameters().values(),
      (std::map<std::string, std::string>{
          {"trees", "100"}, {"predictors", "sqrt"}, {"max_splits", "n-1"}, {"min_leaf", "1"}}));
  EXPECT_EQ(make_classifier("random-forest:predictors=7,max_splits=20")
                ->parameters()
                .values()
                .at("predictors"),
            "7");
}

TEST(TreeEnsemble, BadParametersAreRefusedByName) {
  const auto message = [](const std::string& specification) {
    try {
      make_classifier(specification);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("random-forest:trees=0").find("trees"), std::string::npos);
  EXPECT_NE(message("random-forest:predictors=half").find("predictors"), std::string::npos);
  EXPECT_NE(message("random-forest:predictors=0").find("predictors"), std::string::npos);
  EXPECT_NE(message("bagged-trees:max_splits=-2").find("max_splits"), std::string::npos);
  EXPECT_NE(message("bagged-trees:min_leaf=0").find("min_leaf"), std::string::npos);
  EXPECT_NE(message("bagged-trees:depth=3").find("depth"), std::string::npos);
  EXPECT_NE(message("boosted-trees:rounds=0").find("rounds"), std::string::npos);
  EXPECT_NE(message("boosted-trees:eta=2").find("eta"), std::string::npos);
  EXPECT_NE(message("boosted-trees:subsample=0").find("subsample"), std::string::npos);
  EXPECT_NE(message("boosted-trees:trees=5").find("trees"), std::string::npos);
}

TEST(TreeEnsemble, TheModelIsTheSameForAnyThreadCount) {
  const toy::LabelledSet train = blobs_with_noise(30, 20, 3);
  for (const std::string preset : {"random-forest", "bagged-trees"}) {
    TreeEnsemble one = make_ensemble(preset, "trees=12");
    one.set_threads(1);
    one.fit(train.x, train.y, 3, 42);
    TreeEnsemble two = make_ensemble(preset, "trees=12");
    two.set_threads(2);
    two.fit(train.x, train.y, 3, 42);
    TreeEnsemble five = make_ensemble(preset, "trees=12");
    five.set_threads(5);
    five.fit(train.x, train.y, 3, 42);
    EXPECT_EQ(one.save(), two.save()) << preset;
    EXPECT_EQ(one.save(), five.save()) << preset;
    TreeEnsemble other_seed = make_ensemble(preset, "trees=12");
    other_seed.fit(train.x, train.y, 3, 43);
    EXPECT_NE(one.save(), other_seed.save()) << preset << ": the seed must matter";
  }
}

TEST(TreeEnsemble, LearnsSeparableClassesAndScoresAreProbabilities) {
  const toy::LabelledSet train = blobs_with_noise(40, 5, 5);
  const toy::LabelledSet test = blobs_with_noise(40, 5, 6);
  for (const std::string preset : {"random-forest", "bagged-trees"}) {
    const auto forest = make_classifier(preset);
    forest->fit(train.x, train.y, 3, 1);
    EXPECT_GE(toy::accuracy(forest->predict(test.x), test.y), 0.9) << preset;
    const Matrix scores = forest->scores(test.x);
    EXPECT_TRUE((scores.array() >= 0.0).all()) << preset;
    for (Eigen::Index row = 0; row < scores.rows(); ++row)
      EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-12) << preset;
    // Deep trees on their own bootstrap fit their training rows: the forest does too.
    EXPECT_EQ(forest->predict(train.x), train.y) << preset;
  }
}

TEST(TreeEnsemble, ImportancesRankTheInformativeFeaturesOverNoise) {
  const toy::LabelledSet train = blobs_with_noise(40, 10, 7);
  for (const std::string preset : {"random-forest", "bagged-trees", "boosted-trees"}) {
    const auto model = make_classifier(preset);
    model->fit(train.x, train.y, 3, 2);
    const std::vector<double> importances = model->feature_importances();
    ASSERT_EQ(importances.size(), 12u) << preset;
    double sum = 0.0;
    for (const double value : importances) sum += value;
    EXPECT_NEAR(sum, 1.0, 1e-9) << preset;
    const double noise = *std::max_element(importances.begin() + 2, importances.end());
    EXPECT_GT(std::min(importances[0], importances[1]), noise) << preset;
  }
}

TEST(TreeEnsemble, SavedAndLoadedModelsGiveTheSameScores) {
  const toy::LabelledSet train = blobs_with_noise(20, 4, 9);
  const toy::LabelledSet test = blobs_with_noise(10, 4, 10);
  for (const std::string preset : {"random-forest", "bagged-trees", "boosted-trees"}) {
    const auto model = make_classifier(
        preset + std::string(preset == "boosted-trees" ? ":rounds=20" : ":trees=10"));
    model->fit(train.x, train.y, 3, 4);
    const nlohmann::json saved = save_classifier(*model);
    const auto loaded = load_classifier(nlohmann::json::parse(saved.dump()));
    EXPECT_EQ(loaded->name(), preset);
    EXPECT_EQ(loaded->scores(test.x), model->scores(test.x)) << preset;
    EXPECT_EQ(loaded->feature_importances(), model->feature_importances()) << preset;
  }
}

TEST(TreeEnsemble, MalformedModelsAreRefused) {
  const toy::LabelledSet train = blobs_with_noise(10, 1, 11);
  for (const std::string preset : {"random-forest", "boosted-trees"}) {
    const auto model = make_classifier(preset);
    model->fit(train.x, train.y, 3, 4);
    nlohmann::json saved = save_classifier(*model);
    saved["model"]["feature_count"] = 2;  // the importances hold 3
    EXPECT_THROW(load_classifier(saved), Error) << preset;
  }
  const auto boosted = make_classifier("boosted-trees");
  boosted->fit(train.x, train.y, 3, 4);
  nlohmann::json saved = save_classifier(*boosted);
  saved["model"]["xgboost"] = "{not a model";
  EXPECT_THROW(load_classifier(saved), Error);
}

TEST(BoostedTrees, LearnsSeparableClassesDeterministically) {
  const toy::LabelledSet train = blobs_with_noise(40, 5, 12);
  const toy::LabelledSet test = blobs_with_noise(40, 5, 13);
  BoostedTrees one("boosted-trees", Parameters::parse("subsample=0.8,colsample=0.8", "boosted"));
  one.set_threads(1);
  one.fit(train.x, train.y, 3, 5);
  BoostedTrees two("boosted-trees", Parameters::parse("subsample=0.8,colsample=0.8", "boosted"));
  two.set_threads(2);
  two.fit(train.x, train.y, 3, 5);
  EXPECT_EQ(one.scores(test.x), two.scores(test.x));
  EXPECT_GE(toy::accuracy(one.predict(test.x), test.y), 0.9);
  const Matrix scores = one.scores(test.x);
  for (Eigen::Index row = 0; row < scores.rows(); ++row)
    EXPECT_NEAR(scores.row(row).sum(), 1.0, 1e-5);
}

TEST(BoostedTrees, AClassMissingFromTheTrainingFoldGetsAColumnOfScores) {
  const toy::LabelledSet train = blobs_with_noise(20, 1, 14);
  const auto model = make_classifier("boosted-trees:rounds=5");
  model->fit(train.x, train.y, 4, 0);  // class 3 never seen
  const Matrix scores = model->scores(train.x);
  EXPECT_EQ(scores.cols(), 4);
  EXPECT_LT(scores.col(3).maxCoeff(), 0.5);
}

}  // namespace
}  // namespace tactile::ml

// evaluate() end to end with k-NN: separable blobs, confusion sums, the misclassified
// segments, thread-count independence, progress, cancel, bad input, grid search.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>

#include "ml_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/grid_search.h"

namespace tactile::ml {
namespace {

TEST(Evaluate, SeparableBlobsAreClassifiedPerfectly) {
  const Dataset dataset = blob_dataset({20, 15, 10}, 3, 5);
  const EvaluationResult result = evaluate(dataset, "knn:k=3", Protocol::parse("kfold:5x2"), 1);
  EXPECT_DOUBLE_EQ(result.accuracy, 1.0);
  EXPECT_EQ(result.classes, (std::vector<std::string>{"c0", "c1", "c2"}));
  ASSERT_EQ(result.confusion.rows(), 3);
  ASSERT_EQ(result.confusion.cols(), 4);  // the extra "unknown" column
  EXPECT_EQ(result.confusion(0, 0), 40);
  EXPECT_EQ(result.confusion(1, 1), 30);
  EXPECT_EQ(result.confusion(2, 2), 20);
  EXPECT_EQ(result.predictions, 90);
  EXPECT_TRUE(result.misclassified.empty());
  EXPECT_EQ(result.fold_models.size(), 10u);
  for (const ClassFigures& figure : result.per_class) {
    EXPECT_DOUBLE_EQ(figure.precision, 1.0);
    EXPECT_DOUBLE_EQ(figure.recall, 1.0);
  }
}

TEST(Evaluate, ConfusionSumsToPredictionsAndListsEveryWrongAnswer) {
  const Dataset dataset = blob_dataset({30, 30, 30}, 2, 8, 6.0);  // heavily overlapping
  const EvaluationResult result = evaluate(dataset, "knn:k=1", Protocol::parse("kfold:3x2"), 3);
  EXPECT_EQ(result.confusion.sum(), 180);
  EXPECT_EQ(result.predictions, 180);
  const int correct = result.confusion.leftCols(3).trace();
  EXPECT_EQ(static_cast<int>(result.misclassified.size()), 180 - correct);
  EXPECT_GT(result.misclassified.size(), 10u);
  EXPECT_NEAR(result.accuracy, correct / 180.0, 1e-15);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(result.confusion.row(k).sum(), 60);
  for (const Misclassified& wrong : result.misclassified) {
    EXPECT_EQ(wrong.segment_id, 1000 + wrong.row);
    EXPECT_EQ(wrong.true_class, dataset.classes[static_cast<size_t>(wrong.row)]);
    EXPECT_NE(wrong.predicted_class, wrong.true_class);
  }
  const nlohmann::json json = to_json(result);
  EXPECT_NEAR(json["accuracy"].get<double>(), result.accuracy, 1e-15);
  EXPECT_EQ(json["confusion"].size(), 3u);
  EXPECT_EQ(json["confusion"][0].size(), 3u);
  EXPECT_EQ(json["confusion"][1][2].get<int>(), result.confusion(1, 2));
  EXPECT_EQ(json["per_class"].size(), 3u);
  EXPECT_EQ(json["misclassified_predictions"].size(), result.misclassified.size());
  EXPECT_LE(json["misclassified"].size(), result.misclassified.size());  // distinct segments
  EXPECT_TRUE(json.contains("seconds"));
}

TEST(Evaluate, ResultDoesNotDependOnTheThreadCount) {
  const Dataset dataset = blob_dataset({25, 25}, 6, 2, 5.0);
  EvaluationControl one;
  one.threads = 1;
  EvaluationControl three;
  three.threads = 3;
  const Protocol protocol = Protocol::parse("kfold:5x2");
  const auto first = evaluate(dataset, "subspace-knn:learners=7", protocol, 9, one);
  const auto second = evaluate(dataset, "subspace-knn:learners=7", protocol, 9, three);
  EXPECT_EQ(first.confusion, second.confusion);
  ASSERT_EQ(first.misclassified.size(), second.misclassified.size());
  for (size_t i = 0; i < first.misclassified.size(); ++i)
    EXPECT_EQ(first.misclassified[i].row, second.misclassified[i].row);
  EXPECT_EQ(first.fold_models, second.fold_models);
}

TEST(Evaluate, LeaveOneOutAndLeaveOneSubjectOutPredictEveryRowOnce) {
  const Dataset dataset = blob_dataset({8, 8}, 2, 4);
  EXPECT_EQ(evaluate(dataset, "knn", Protocol::parse("loo"), 1).predictions, 16);
  const auto loso = evaluate(dataset, "knn", Protocol::parse("loso"), 1);
  EXPECT_EQ(loso.predictions, 16);
  EXPECT_EQ(loso.fold_models.size(), 4u);
  EXPECT_DOUBLE_EQ(loso.accuracy, 1.0);
}

// Without scores to report the SVM skips its sigmoids (Classifier::skip_scores): the same
// predictions row by row, and the scores only when asked for.
TEST(Evaluate, AnSvmPredictsTheSameWithAndWithoutScores) {
  const Dataset dataset = blob_dataset({25, 25, 25}, 2, 9);
  EvaluationControl control;
  control.scores = true;
  const Protocol protocol = Protocol::parse("kfold:5");
  const EvaluationResult with = evaluate(dataset, "medium-gaussian-svm", protocol, 3, control);
  control.scores = false;
  const EvaluationResult without = evaluate(dataset, "medium-gaussian-svm", protocol, 3, control);
  EXPECT_EQ(with.confusion, without.confusion);
  ASSERT_EQ(with.rows.size(), without.rows.size());
  bool some_score = false;
  for (size_t row = 0; row < with.rows.size(); ++row) {
    EXPECT_EQ(with.rows[row].predicted, without.rows[row].predicted) << row;
    some_score = some_score || with.rows[row].score > 0.0;
    EXPECT_EQ(without.rows[row].score, 0.0) << row;
  }
  EXPECT_TRUE(some_score);
}

TEST(Evaluate, ProgressCountsEveryFold) {
  const Dataset dataset = blob_dataset({10, 10}, 2, 4);
  std::vector<int> reported;
  EvaluationControl control;
  control.progress = [&](int done, int total) {
    EXPECT_EQ(total, 8);
    reported.push_back(done);
  };
  evaluate(dataset, "knn", Protocol::parse("kfold:4x2"), 1, control);
  EXPECT_EQ(reported, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8}));
}

TEST(Evaluate, CancelStopsWithAnError) {
  const Dataset dataset = blob_dataset({30, 30}, 2, 4);
  std::atomic<bool> cancel{false};
  int folds_run = 0;
  EvaluationControl control;
  control.cancel = &cancel;
  control.threads = 1;
  control.progress = [&](int done, int) {
    folds_run = done;
    if (done == 2) cancel = true;
  };
  try {
    evaluate(dataset, "knn", Protocol::parse("loo"), 1, control);
    FAIL() << "a cancelled evaluation returned";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "evaluation");
    EXPECT_EQ(error.message(), "cancelled");
  }
  EXPECT_EQ(folds_run, 2);
}

TEST(Evaluate, BadInputIsNamed) {
  Dataset dataset = blob_dataset({5, 5}, 2, 4);
  EXPECT_THROW(evaluate(dataset, "no-such-classifier", Protocol::parse("loo"), 1), Error);
  EXPECT_THROW(evaluate(dataset, "knn:k=x", Protocol::parse("loo"), 1), Error);
  dataset.features(3, 1) = std::nan("");
  try {
    evaluate(dataset, "knn", Protocol::parse("loo"), 1);
    FAIL() << "NaN accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("row 3, feature f1"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(evaluate(Dataset{}, "knn", Protocol::parse("loo"), 1), Error);
}

//---- Grid search

// 30 rows of class a around 0 and 3 tight rows of class b around 10: with inner kfold:3 each
// inner training part holds 2 b rows, so k=5 outvotes them, k=3 and k=1 do not.
Dataset minority_dataset() {
  Dataset dataset = blob_dataset({30}, 1, 6);
  dataset.features.conservativeResize(33, 1);
  for (int64_t row = 30; row < 33; ++row) {
    dataset.features(row, 0) = 10.0 + 0.1 * static_cast<double>(row - 31);
    dataset.classes.push_back("b");
    dataset.subjects.push_back("s0");
    dataset.recordings.push_back("rec.h5");
    dataset.segment_ids.push_back(2000 + row);
    dataset.metadata.push_back({});
  }
  return dataset;
}

TEST(GridSearch, ChoosesTheFirstBestByInnerCrossValidation) {
  const Dataset dataset = minority_dataset();
  std::vector<int> labels;
  for (const std::string& name : dataset.classes) labels.push_back(name == "b" ? 1 : 0);
  auto grid = make_classifier("grid:base=knn,k=5|3|1,inner=kfold:3");
  grid->fit(dataset.features, labels, 2, 17);
  const auto& search = dynamic_cast<const GridSearchClassifier&>(*grid);
  ASSERT_EQ(search.candidates().size(), 3u);
  EXPECT_EQ(search.candidates()[0].specification, "knn:k=5");
  EXPECT_NEAR(search.candidates()[0].inner_accuracy, 30.0 / 33.0, 1e-12);
  EXPECT_DOUBLE_EQ(search.candidates()[1].inner_accuracy, 1.0);
  EXPECT_DOUBLE_EQ(search.candidates()[2].inner_accuracy, 1.0);
  EXPECT_EQ(search.chosen_specification(),
            "knn:k=3,metric=euclidean,standardize=false,weights=equal");
}

TEST(GridSearch, CombinesEveryAxisAndRejectsBadGrids) {
  const auto grid =
      make_classifier("grid-search:base=knn,k=1|3|5,metric=euclidean|cosine,inner=kfold:3");
  const auto& search = dynamic_cast<const GridSearchClassifier&>(*grid);
  ASSERT_EQ(search.candidates().size(), 6u);
  EXPECT_EQ(search.candidates()[1].specification, "knn:k=1,metric=cosine");
  EXPECT_THROW(make_classifier("grid:k=1|3"), Error);                    // no base
  EXPECT_THROW(make_classifier("grid:base=knn,neighbours=1|3"), Error);  // unknown key of the base
  EXPECT_THROW(make_classifier("grid:base=knn,k=1||3"), Error);
  EXPECT_THROW(make_classifier("grid:base=knn,k=1,inner=loso"), Error);
  EXPECT_THROW(make_classifier("grid:base=grid,k=1"), Error);
}

TEST(GridSearch, EvaluationRecordsTheChoiceOfEveryFold) {
  const Dataset dataset = minority_dataset();
  const auto result =
      evaluate(dataset, "grid:base=knn,k=5|1,inner=kfold:3", Protocol::parse("kfold:3"), 2);
  ASSERT_EQ(result.fold_models.size(), 3u);
  // Each outer training fold keeps 2 rows of b: inner k=5 loses them, k=1 does not.
  for (const std::string& model : result.fold_models)
    EXPECT_EQ(model.rfind("knn:k=1,", 0), 0u) << model;
  EXPECT_DOUBLE_EQ(result.accuracy, 1.0);
}

TEST(GridSearch, SaveLoadRoundTripGivesIdenticalScores) {
  const Dataset dataset = blob_dataset({12, 12}, 2, 3, 3.0);
  std::vector<int> labels;
  for (const std::string& name : dataset.classes) labels.push_back(name == "c1" ? 1 : 0);
  auto grid = make_classifier("grid:base=weighted-knn,k=1|5,inner=kfold:3");
  grid->fit(dataset.features, labels, 2, 5);
  const auto restored = load_classifier(nlohmann::json::parse(save_classifier(*grid).dump()));
  EXPECT_EQ(grid->scores(dataset.features), restored->scores(dataset.features));
  EXPECT_EQ(dynamic_cast<const GridSearchClassifier&>(*restored).chosen_specification(),
            dynamic_cast<const GridSearchClassifier&>(*grid).chosen_specification());
}

TEST(AutoClassifier, PicksAmongWholeClassifiersInsideTheTrainingFold) {
  const Dataset dataset = minority_dataset();
  std::vector<int> labels;
  for (const std::string& name : dataset.classes) labels.push_back(name == "b" ? 1 : 0);
  auto picker = make_classifier("auto:candidates=knn:k=5|knn:k=1;standardize=true,inner=kfold:3");
  picker->fit(dataset.features, labels, 2, 17);
  const auto& search = dynamic_cast<const GridSearchClassifier&>(*picker);
  ASSERT_EQ(search.candidates().size(), 2u);
  EXPECT_EQ(search.candidates()[1].specification, "knn:k=1,standardize=true");
  EXPECT_DOUBLE_EQ(search.candidates()[1].inner_accuracy, 1.0);
  EXPECT_EQ(search.chosen_specification().rfind("knn:k=1,", 0), 0u);
  // Every outer fold chose on its own training rows (the choices are recorded per fold).
  const auto result = evaluate(dataset, "auto:candidates=knn:k=5|knn:k=1,inner=kfold:3",
                               Protocol::parse("kfold:3"), 2);
  ASSERT_EQ(result.fold_models.size(), 3u);
  for (const std::string& model : result.fold_models)
    EXPECT_EQ(model.rfind("knn:k=1,", 0), 0u) << model;
  // Saved and loaded, it answers the same.
  const auto restored = load_classifier(nlohmann::json::parse(save_classifier(*picker).dump()));
  EXPECT_EQ(picker->scores(dataset.features), restored->scores(dataset.features));
}

TEST(AutoClassifier, TheDefaultListIsEveryPresetAndAKnnGridButNoSearch) {
  const std::vector<std::string> candidates = auto_candidates();
  EXPECT_GT(candidates.size(), 15u);
  for (const std::string& candidate : candidates) {
    EXPECT_NE(candidate.rfind("grid", 0), 0u);
    EXPECT_NE(candidate, "auto");
  }
  EXPECT_NE(std::find(candidates.begin(), candidates.end(), "knn:k=5,standardize=true"),
            candidates.end());
  EXPECT_THROW(make_classifier("auto:candidates=grid:base=knn"), Error);
  EXPECT_THROW(make_classifier("auto:candidates=knn:neighbours=3"), Error);
  EXPECT_THROW(make_classifier("auto:inner=loso"), Error);
  EXPECT_THROW(make_classifier("auto:speed=fast"), Error);
  // Train all leaves auto out (it would run every preset again inside each fold).
  const std::vector<std::string> presets = preset_names();
  EXPECT_EQ(std::find(presets.begin(), presets.end(), "auto"), presets.end());
}

}  // namespace
}  // namespace tactile::ml

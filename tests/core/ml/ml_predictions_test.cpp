// Per-row predictions of an evaluation (where each tested segment is, what was answered,
// how sure), their JSON round trip, confusion cells, "train all", and confidence_of.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <nlohmann/json.hpp>
#include <set>

#include "ml_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/train_all.h"

namespace tactile::ml {
namespace {

Dataset located_blobs(double spread) {
  Dataset dataset = blob_dataset({12, 12, 12}, 2, 7, spread);
  for (int64_t row = 0; row < dataset.rows(); ++row) {
    Metadata& metadata = dataset.metadata[static_cast<size_t>(row)];
    metadata["t0"] = std::to_string(row) + ".5";
    metadata["t1"] = std::to_string(row + 1) + ".25";
    metadata["region"] = row % 2 ? "front" : "back";
  }
  return dataset;
}

TEST(ConfidenceOf, VotesAreSharesAlreadyOtherScoresGoThroughASoftmax) {
  const Confidence votes = confidence_of(Vector{{0.2, 0.5, 0.3}}, 1);
  EXPECT_DOUBLE_EQ(votes.score, 0.5);
  EXPECT_NEAR(votes.margin, 0.2, 1e-15);
  const Confidence tie = confidence_of(Vector{{0.5, 0.5}}, 0);
  EXPECT_DOUBLE_EQ(tie.margin, 0.0);
  // Distances (SOM: minus the distance) and decision values: softmax, ordered the same.
  const Confidence distances = confidence_of(Vector{{-1.0, -3.0, -1.0 - std::log(2.0)}}, 0);
  EXPECT_NEAR(distances.score, 1.0 / (1.0 + std::exp(-2.0) + 0.5), 1e-12);
  EXPECT_NEAR(distances.margin, distances.score / 2.0, 1e-12);
  // A class that owns nothing scores lowest(); unknown answers are the least sure.
  const Confidence lowest = confidence_of(Vector{{-0.5, std::numeric_limits<double>::lowest()}}, 0);
  EXPECT_DOUBLE_EQ(lowest.score, 1.0);
  EXPECT_DOUBLE_EQ(confidence_of(Vector{{0.4, 0.6}}, kUnknownClass).score, 0.0);
}

TEST(EvaluateRows, EveryTestPredictionIsARowWithItsSegmentAndScore) {
  const Dataset dataset = located_blobs(5.0);  // overlapping: some wrong answers
  EvaluationControl control;
  control.scores = true;
  const EvaluationResult result =
      evaluate(dataset, "knn:k=3", Protocol::parse("kfold:3x2"), 2, control);
  ASSERT_EQ(static_cast<int64_t>(result.rows.size()), result.predictions);
  std::set<int64_t> seen;
  for (const RowPrediction& row : result.rows) {
    const auto index = static_cast<size_t>(row.row);
    seen.insert(row.row);
    EXPECT_EQ(row.segment_id, 1000 + row.row);
    EXPECT_EQ(row.recording, dataset.recordings[index]);
    EXPECT_DOUBLE_EQ(row.t0, static_cast<double>(row.row) + 0.5);
    EXPECT_DOUBLE_EQ(row.t1, static_cast<double>(row.row) + 1.25);
    EXPECT_EQ(row.region, row.row % 2 ? "front" : "back");
    EXPECT_EQ(result.classes[static_cast<size_t>(row.truth)], dataset.classes[index]);
    // k-NN scores weigh its votes by 1/d: the majority that predicts can hold under a third
    // of the three classes' shares, and is then not the largest: margin 0.
    EXPECT_GT(row.score, 0.0);
    EXPECT_LE(row.score, 1.0);
    EXPECT_LE(row.margin, row.score);
    if (row.score < 1.0 / 3.0) {
      EXPECT_EQ(row.margin, 0.0);
    }
  }
  EXPECT_EQ(static_cast<int64_t>(seen.size()), dataset.rows());
  // Each cell of the confusion matrix is exactly its rows.
  for (int truth = 0; truth < 3; ++truth)
    for (int predicted = 0; predicted < 3; ++predicted)
      EXPECT_EQ(static_cast<int>(rows_in_cell(result, truth, predicted).size()),
                result.confusion(truth, predicted));
  EXPECT_GT(result.misclassified.size(), 0u);
  // Without scores asked for, the rows are there with score 0 and the same answers.
  const EvaluationResult plain = evaluate(dataset, "knn:k=3", Protocol::parse("kfold:3x2"), 2);
  ASSERT_EQ(plain.rows.size(), result.rows.size());
  for (size_t k = 0; k < plain.rows.size(); ++k) {
    EXPECT_EQ(plain.rows[k].predicted, result.rows[k].predicted);
    EXPECT_EQ(plain.rows[k].score, 0.0);
  }
}

TEST(EvaluateRows, JsonRoundTripKeepsConfusionAndRows) {
  const Dataset dataset = located_blobs(5.0);
  EvaluationControl control;
  control.scores = true;
  const EvaluationResult result =
      evaluate(dataset, "knn:k=3", Protocol::parse("kfold:4"), 3, control);
  const nlohmann::json json = to_json(result, true);
  ASSERT_EQ(json["rows"].size(), result.rows.size());
  EXPECT_NEAR(json["mean_recall"].get<double>(), mean_recall(result), 1e-15);
  const EvaluationResult back = evaluation_from_json(json, "result.json");
  EXPECT_EQ(back.classes, result.classes);
  EXPECT_EQ(back.confusion, result.confusion);
  EXPECT_DOUBLE_EQ(back.accuracy, result.accuracy);
  ASSERT_EQ(back.rows.size(), result.rows.size());
  for (size_t k = 0; k < back.rows.size(); ++k) {
    EXPECT_EQ(back.rows[k].recording, result.rows[k].recording);
    EXPECT_EQ(back.rows[k].truth, result.rows[k].truth);
    EXPECT_EQ(back.rows[k].predicted, result.rows[k].predicted);
    EXPECT_DOUBLE_EQ(back.rows[k].score, result.rows[k].score);
    EXPECT_DOUBLE_EQ(back.rows[k].t0, result.rows[k].t0);
  }
  // Damage is named with the place.
  nlohmann::json broken = json;
  broken["rows"][3]["true"] = "nonsense";
  try {
    evaluation_from_json(broken, "result.json");
    FAIL() << "accepted an unknown class";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("result.json: rows[3]"), std::string::npos)
        << error.what();
  }
  broken = json;
  broken["confusion"].erase(1);
  EXPECT_THROW(evaluation_from_json(broken, "result.json"), Error);
  broken = json;
  broken.erase("classes");
  EXPECT_THROW(evaluation_from_json(broken, "result.json"), Error);
}

TEST(EvaluateAll, EveryPresetRunsOnTheSameFoldsAndMisfitsAreSkipped) {
  const Dataset dataset = located_blobs(1.0);
  std::atomic<int> calls{0};
  EvaluationControl control;
  int last_done = 0, last_total = 0;
  control.progress = [&](int done, int total) {
    EXPECT_GE(done, last_done);  // thousandths of the estimated work, never back
    last_done = done, last_total = total;
  };
  const std::vector<PresetOutcome> outcomes =
      evaluate_all(dataset, Protocol::parse("kfold:3"), 1, control,
                   [&](const PresetOutcome&, int index, int total) {
                     EXPECT_EQ(index, calls.load());
                     EXPECT_EQ(total, static_cast<int>(preset_names().size()));
                     ++calls;
                   });
  ASSERT_EQ(outcomes.size(), preset_names().size());
  EXPECT_EQ(last_done, 1000);
  EXPECT_EQ(last_total, 1000);
  int fitted = 0;
  for (const PresetOutcome& outcome : outcomes) {
    EXPECT_NE(outcome.classifier, "grid");
    if (!outcome.result) {
      EXPECT_FALSE(outcome.skipped.empty()) << outcome.classifier;
      continue;
    }
    ++fitted;
    EXPECT_EQ(outcome.result->predictions, dataset.rows()) << outcome.classifier;
  }
  EXPECT_GE(fitted, 15);
  // Well separated blobs: the k-NN presets are perfect.
  for (const PresetOutcome& outcome : outcomes)
    if (outcome.classifier == "knn") {
      EXPECT_DOUBLE_EQ(outcome.result->accuracy, 1.0);
    }
}

TEST(TrainAllPlan, EveryPresetOnceTheQuickOnesFirst) {
  const std::vector<TrainAllStep> plan = train_all_plan(600, 20, 5);
  ASSERT_EQ(plan.size(), preset_names().size());
  for (size_t k = 1; k < plan.size(); ++k) EXPECT_LE(plan[k - 1].cost, plan[k].cost);
  std::vector<std::string> names;
  for (const TrainAllStep& step : plan) names.push_back(step.classifier);
  std::vector<std::string> presets = preset_names();
  std::sort(names.begin(), names.end());
  std::sort(presets.begin(), presets.end());
  EXPECT_EQ(names, presets);  // narrow: every preset on every column, as itself
  const auto at = [&plan](const std::string& name) {
    for (size_t k = 0; k < plan.size(); ++k)
      if (plan[k].classifier == name) return k;
    return plan.size();
  };
  EXPECT_EQ(plan.front().classifier, "gaussian-nb");
  EXPECT_LT(at("knn"), at("boosted-trees"));
  EXPECT_LT(at("tree"), at("bagged-trees"));
  EXPECT_LT(at("linear-svm"), at("som"));
}

TEST(TrainAllPlan, OnAWideTableBoostingBaggingAndCovariancesLearnFromChosenColumns) {
  // Robovie's pair correlations: 183 segments x 37,401 columns.
  const std::vector<TrainAllStep> plan = train_all_plan(183, 37401, 15);
  std::vector<std::string> names;
  for (const TrainAllStep& step : plan) names.push_back(step.classifier);
  const auto has = [&names](const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  EXPECT_TRUE(has("select:k=500,base=boosted-trees"));
  EXPECT_TRUE(has("select:k=2000,base=bagged-trees"));
  EXPECT_TRUE(has("select:k=500,base=qda"));
  EXPECT_TRUE(has("select:k=500,base=gaussian-ml"));
  EXPECT_TRUE(has("select:k=500,base=em"));
  EXPECT_TRUE(has("som"));  // trained in the span of its rows: whole
  EXPECT_TRUE(has("linear-svm"));
  for (const std::string& name : names) EXPECT_NO_THROW(make_classifier(name)) << name;
}

TEST(EvaluateAll, CancelStopsEveryPreset) {
  const Dataset dataset = located_blobs(1.0);
  std::atomic<bool> cancel{true};
  EvaluationControl control;
  control.cancel = &cancel;
  EXPECT_THROW(evaluate_all(dataset, Protocol::parse("kfold:3"), 1, control), Error);
}

}  // namespace
}  // namespace tactile::ml

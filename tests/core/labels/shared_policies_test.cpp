// Policies the command line and the workbench share, one place each: the train-all result
// (written by `tactile evaluate --classifier all`, opened by the workbench) and online
// decisions into a lane.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/features/dataset.h"
#include "tactile/labels/predict.h"
#include "tactile/live/online_classifier.h"
#include "tactile/ml/train_all.h"

namespace tactile {
namespace {

ml::PresetOutcome outcome(const std::string& classifier, double accuracy) {
  ml::EvaluationResult result;
  result.classifier = classifier;
  result.classes = {"pat", "slap"};
  result.confusion = Eigen::MatrixXi::Zero(2, 3);
  result.confusion(0, 0) = 3;
  result.confusion(1, 1) = 1;
  result.accuracy = accuracy;
  result.per_class = {{1.0, 1.0, 0.0, 3}, {1.0, 1.0, 0.0, 1}};
  return {classifier, result, ""};
}

TEST(TrainAllResult, IsSortedBestFirstAndReadsBackAsWritten) {
  ml::TrainAllResult all{
      "kfold:5",
      7,
      "table.csv",
      {outcome("knn", 0.5), {"gmm", std::nullopt, "too few rows"}, outcome("linear-svm", 0.75)}};
  EXPECT_EQ(ml::best_outcome(all.outcomes), 2);
  ml::sort_best_first(all.outcomes);
  ASSERT_EQ(all.outcomes.size(), 3u);
  EXPECT_EQ(all.outcomes[0].classifier, "linear-svm");
  EXPECT_EQ(all.outcomes[2].classifier, "gmm");  // did not fit: last
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("train_all_" + std::to_string(::getpid()) + ".json");
  ml::write_train_all_file(path.string(), all);
  const ml::TrainAllResult read = ml::read_train_all_file(path.string());
  EXPECT_EQ(read.protocol, "kfold:5");
  EXPECT_EQ(read.seed, 7u);
  EXPECT_EQ(read.features, "table.csv");
  ASSERT_EQ(read.outcomes.size(), 3u);
  EXPECT_EQ(read.outcomes[0].classifier, "linear-svm");
  EXPECT_DOUBLE_EQ(read.outcomes[0].result->accuracy, 0.75);
  EXPECT_FALSE(read.outcomes[2].result);
  EXPECT_EQ(read.outcomes[2].skipped, "too few rows");
  // One evaluation alone reads as a train-all of one.
  std::ofstream(path) << ml::to_json(*all.outcomes[1].result, true).dump();
  EXPECT_EQ(ml::read_train_all_file(path.string()).outcomes.size(), 1u);
  std::ofstream(path) << "{\"evaluations\": 3}";
  EXPECT_THROW(ml::read_train_all_file(path.string()), Error);
  std::filesystem::remove(path);
  EXPECT_THROW(ml::read_train_all_file(path.string()), Error);
}

OnlineDecision decision(double t0, double t1, const std::string& class_name, bool final = false) {
  return {t0, t1, class_name, 0.8, final, 0.0};
}

TEST(OnlineLane, AnAnswerThatGoesOnGrowsOneLabelAndTheFinalOneReplacesTheProvisional) {
  std::vector<Label> lane;
  add_online_decision(lane, decision(0.0, 1.0, "pat"), "live", 0.0);
  add_online_decision(lane, decision(0.5, 1.5, "pat"), "live", 0.0);
  ASSERT_EQ(lane.size(), 1u);
  EXPECT_DOUBLE_EQ(lane[0].t1, 1.5);
  EXPECT_EQ(lane[0].annotator, kOnlineAnnotator);
  EXPECT_EQ(lane[0].note, "provisional");
  add_online_decision(lane, decision(1.0, 2.0, "slap"), "live", 0.0);
  ASSERT_EQ(lane.size(), 2u);
  EXPECT_DOUBLE_EQ(lane[1].t0, 1.5);  // where the one before ends: the windows overlap
  add_online_decision(lane, decision(0.0, 2.0, "slap", true), "live", 0.0);
  ASSERT_EQ(lane.size(), 1u);
  EXPECT_EQ(lane[0].note, "final");
  EXPECT_EQ(lane[0].class_name, "slap");
  // What the buffer no longer holds goes.
  add_online_decision(lane, decision(10.0, 11.0, "pat"), "live", 5.0);
  ASSERT_EQ(lane.size(), 1u);
  EXPECT_DOUBLE_EQ(lane[0].t0, 10.0);
}

Label prediction(double t0, double t1, double margin) {
  Label label;
  label.recording = "r";
  label.t0 = t0;
  label.t1 = t1;
  label.source = LabelSource::kModel;
  label.note = "margin=" + std::to_string(margin) + " model=knn";
  return label;
}

TEST(LeastSurePrediction, IsTheSmallestMarginNoOwnLabelCovers) {
  const std::vector<Label> predictions = {prediction(0, 1, 0.5), prediction(2, 3, 0.1),
                                          prediction(4, 5, 0.3)};
  EXPECT_EQ(least_sure_prediction(predictions, {}), &predictions[1]);
  std::vector<Label> own = {prediction(2.5, 2.8, 1.0)};
  EXPECT_EQ(least_sure_prediction(predictions, own), &predictions[2]);
  own.push_back(prediction(0, 10, 1.0));
  EXPECT_EQ(least_sure_prediction(predictions, own), nullptr);
}

TEST(DatasetMetadata, IsSharedOnlyWhenEveryRowCarriesTheSameValue) {
  Dataset table;
  table.metadata = {{{"layout", "fur"}}, {{"layout", "fur"}}};
  EXPECT_EQ(table.shared_metadata("layout"), "fur");
  table.metadata.push_back({{"layout", "nao"}});
  EXPECT_EQ(table.shared_metadata("layout"), "");
  table.metadata = {{{"layout", "fur"}}, {}};
  EXPECT_EQ(table.shared_metadata("layout"), "");
  EXPECT_EQ(Dataset{}.shared_metadata("layout"), "");
}

}  // namespace
}  // namespace tactile

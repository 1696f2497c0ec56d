// TrainingJob: a workspace's labelled segments of one skin -> features -> evaluation on a
// worker thread; the caller only polls. Cancel ends it; failures are reported, not thrown.
#include "tactile/labels/training_job.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tactile/labels/predict.h"
#include "tactile/skins/workspace.h"

namespace tactile::ml {
namespace {

class TrainingJobTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: ctest runs each test in its own, at the same time.
    folder_ = (std::filesystem::temp_directory_path() /
               ("training-job-test-" + std::to_string(::getpid())))
                  .string();
    std::filesystem::remove_all(folder_);
    SimulationOptions options;
    options.subjects = 2;
    options.repetitions = 3;
    write_simulation(folder_, "flux", options);
    write_simulation(folder_, "fur", options);  // another skin in the same store
  }
  static void TearDownTestSuite() { std::filesystem::remove_all(folder_); }

  TrainingRequest request(const std::string& classifier) const {
    TrainingRequest request;
    request.database = folder_ + "/labels.db";
    request.layout = "flux";
    request.pipeline = "flux";
    request.classifier = classifier;
    request.protocol = "kfold:3";
    request.threads = 1;
    return request;
  }
  static std::string folder_;
};
std::string TrainingJobTest::folder_;

TEST_F(TrainingJobTest, OneClassifierOnOneSkinWithAModel) {
  TrainingRequest asked = request("knn:k=1");
  asked.save_model = folder_ + "/flux-model.json";
  const std::unique_ptr<TrainingJob> started = start_training_job(asked);
  TrainingJob& job = *started;
  job.wait();
  ASSERT_EQ(job.status(), JobStatus::kDone) << job.error();
  EXPECT_DOUBLE_EQ(job.progress(), 1.0);
  const std::optional<TrainingOutcome> outcome = job.take();
  ASSERT_TRUE(outcome);
  EXPECT_FALSE(job.take());  // moved out once
  EXPECT_EQ(outcome->pipeline, "flux");
  ASSERT_EQ(outcome->results.size(), 1u);
  ASSERT_TRUE(outcome->results[0].result);
  const EvaluationResult& result = *outcome->results[0].result;
  EXPECT_EQ(result.predictions, outcome->dataset->rows());
  EXPECT_EQ(static_cast<int64_t>(result.rows.size()), outcome->dataset->rows());
  for (const Metadata& metadata : outcome->dataset->metadata)
    EXPECT_EQ(metadata.at("layout"), "flux");
  for (const RowPrediction& row : result.rows) {
    EXPECT_LT(row.t0, row.t1);
    EXPECT_GT(row.score, 0.0);  // scores were asked for
  }
  const SavedModel model = read_model_file(asked.save_model);
  EXPECT_EQ(model.pipeline, "flux");
  EXPECT_EQ(model.layout, "flux");
}

TEST_F(TrainingJobTest, CancelEndsTheRunAndFailuresAreReported) {
  // Cancelled while it runs (a cancel before the start would end it before any work).
  JobProgress progress;
  progress.cancel();
  EXPECT_THROW(run_training(request("all"), progress), JobCancelled);

  TrainingRequest bad = request("knn");
  bad.protocol = "kfold:1000";  // more folds than segments
  const std::unique_ptr<TrainingJob> started = start_training_job(bad);
  TrainingJob& failing = *started;
  failing.wait();
  EXPECT_EQ(failing.status(), JobStatus::kFailed);
  EXPECT_NE(failing.error().find("--protocol"), std::string::npos) << failing.error();

  TrainingRequest nowhere = request("knn");
  nowhere.layout = "nao";  // no nao recordings in this store
  const std::unique_ptr<TrainingJob> none = start_training_job(nowhere);
  TrainingJob& empty = *none;
  empty.wait();
  EXPECT_EQ(empty.status(), JobStatus::kFailed);
  EXPECT_NE(empty.error().find("on nao recordings"), std::string::npos) << empty.error();
}

}  // namespace
}  // namespace tactile::ml

#pragma once
// A training run in the background, for the workbench's model panel: the feature table
// of a workspace's labelled segments (one skin, one pipeline), then one classifier or
// every preset ("all") under a protocol, as a Job (jobs/job.h) with progress, cancel and
// the result kept for the views (confusion, scatter, SOM map). The caller's thread only
// polls; nothing here blocks it.

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/jobs/job.h"
#include "tactile/labelstore/label.h"
#include "tactile/ml/evaluation.h"

namespace tactile {

struct SavedModel;  // labels/predict.h

// What a training run has finished so far, shared by its worker and the window: the feature
// table once it is made, then each classifier's outcome as it ends. The window shows each
// result as it arrives and keeps what finished when the run is cancelled.
class TrainingSoFar {
 public:
  void set_table(std::shared_ptr<const Dataset> table, std::string pipeline);
  void add(ml::PresetOutcome outcome);
  // How many outcomes have arrived (cheap: the window asks every frame).
  size_t count() const;
  // The table (null before it is made), its pipeline and the outcomes so far.
  std::shared_ptr<const Dataset> table() const;
  std::string pipeline() const;
  std::vector<ml::PresetOutcome> outcomes() const;

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const Dataset> table_;
  std::string pipeline_;
  std::vector<ml::PresetOutcome> outcomes_;
};

struct TrainingRequest {
  std::string database;  // label store
  std::string folder;    // recordings folder ("" = the database's)
  std::string layout;    // only recordings of this skin ("" = all)
  LabelSource segments = LabelSource::kGroundTruth;
  std::string pipeline;         // the feature pipeline (a skin's own: default_pipeline)
  std::string pipeline_params;  // key=value,...
  std::string classifier;       // a specification, or "all"
  std::string protocol = "kfold:5";
  uint64_t seed = 1;
  int threads = 0;
  std::string save_model;                 // when set and one classifier: fit on all rows, save here
  std::shared_ptr<TrainingSoFar> so_far;  // when set: filled as the run goes
};

struct TrainingOutcome {
  std::shared_ptr<const Dataset> dataset;  // the feature table the results are about
  std::vector<ml::PresetOutcome> results;  // one per classifier tried, in the order run
  std::string model_path;                  // written model ("" when none asked for)
  // That model as fitted, so that predicting with it reads no file (a linear SVM of Robovie's
  // 37,401 columns is 112 MB of text, and its parse held 64 MB beside the model's 31).
  std::shared_ptr<const SavedModel> model;
  std::string pipeline;  // as used
};

// The training run: reads the labelled segments, extracts the feature table, evaluates,
// fits and saves the model when asked; reports through `progress` (features are the first
// 30 %, then the folds) and ends with JobCancelled once cancelled.
TrainingOutcome run_training(const TrainingRequest& request, JobProgress& progress);

// A training run on a worker (jobs/job.h), named "training".
using TrainingJob = Job<TrainingOutcome>;
std::unique_ptr<TrainingJob> start_training_job(TrainingRequest request);

}  // namespace tactile

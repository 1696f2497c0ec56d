#pragma once
// A training run in the background, for the workbench's model panel: the feature table
// of a workspace's labelled segments (one skin, one pipeline), then one classifier or
// every preset ("all") under a protocol, on a worker thread, with progress, cancel and
// the result kept for the views (confusion, scatter, SOM map). The caller's thread only
// polls; nothing here blocks it.

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/io/label.h"
#include "tactile/ml/evaluation.h"

namespace tactile::ml {

struct TrainingRequest {
  std::string database;  // label store
  std::string folder;    // recordings folder ("" = the database's)
  std::string layout;    // only recordings of this skin ("" = all)
  LabelSource segments = LabelSource::kGroundTruth;
  std::string pipeline;         // "" = the skin's own (skin_pipeline)
  std::string pipeline_params;  // key=value,...
  std::string classifier;       // a specification, or "all"
  std::string protocol = "kfold:5";
  uint64_t seed = 1;
  int threads = 0;
  std::string save_model;  // when set and one classifier: fit on all rows, save here
};

struct TrainingOutcome {
  Dataset dataset;                     // the feature table the results are about
  std::vector<PresetOutcome> results;  // one per classifier tried, in the order run
  std::string model_path;              // written model ("" when none asked for)
  std::string pipeline;                // as used
};

class TrainingJob {
 public:
  enum class Status { kRunning, kDone, kFailed, kCancelled };

  // Starts the worker at once.
  explicit TrainingJob(TrainingRequest request);
  ~TrainingJob();  // cancels and joins
  TrainingJob(const TrainingJob&) = delete;
  TrainingJob& operator=(const TrainingJob&) = delete;

  const TrainingRequest& request() const { return request_; }
  Status status() const { return status_.load(); }
  // 0..1 over features (first 30 %) and folds.
  double progress() const { return progress_.load(); }
  // What the worker is doing ("features", "linear-svm 3/10 folds"), for the panel.
  std::string stage() const;
  void cancel() { cancel_.store(true); }
  // The error when Failed.
  std::string error() const;
  // The outcome, once Done (moved out on the first call; null before and after).
  std::unique_ptr<TrainingOutcome> take();
  // Blocks until the worker ends (tests and the headless command line).
  void wait();

 private:
  void run();

  TrainingRequest request_;
  std::atomic<Status> status_{Status::kRunning};
  std::atomic<double> progress_{0.0};
  std::atomic<bool> cancel_{false};
  mutable std::mutex mutex_;
  std::string stage_, error_;
  std::unique_ptr<TrainingOutcome> outcome_;
  std::thread worker_;
};

}  // namespace tactile::ml

#pragma once
// Evaluation protocols (spec §6.6-6.7): stratified k-fold (repeated, seeded),
// leave-one-out, leave-one-subject-out, repeated stratified hold-out, train/test split by
// metadata; confusion matrices summed over folds, per-class figures, the misclassified
// segments, timings. Long runs report progress and can be cancelled.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct Protocol {
  enum class Kind { kKFold, kLeaveOneOut, kLeaveOneSubjectOut, kHoldout, kSplit };
  Kind kind = Kind::kKFold;
  int folds = 10;               // k-fold
  int repetitions = 1;          // k-fold and hold-out
  double test_fraction = 0.15;  // hold-out
  std::string train_query;      // split: "side=back,condition=stationary"
  std::string test_query;       // split: "side=front"
  // "kfold:K[xR]" | "loo" | "loso" | "holdout:FxR" | "split:QUERY/QUERY"; throws tactile::Error
  // naming --protocol.
  static Protocol parse(const std::string& text);
  std::string to_string() const;
};

// One train/test split: row indices into the dataset.
struct Fold {
  std::vector<int64_t> train;
  std::vector<int64_t> test;
};
// Folds of a protocol over a dataset; every random step draws from `seed`.
std::vector<Fold> make_folds(const Dataset& dataset, const Protocol& protocol, uint64_t seed);

struct ClassFigures {
  double precision = 0.0;
  double recall = 0.0;
  int64_t support = 0;
};

struct Misclassified {
  int64_t row = 0;         // dataset row
  int64_t segment_id = 0;  // label id in the label store
  std::string recording;
  std::string true_class;
  std::string predicted_class;  // "unknown" for kUnknownClass
};

struct EvaluationResult {
  std::string classifier;  // specification as given
  std::string protocol;
  std::vector<std::string> classes;  // row/column order of the confusion matrix
  // confusion(true, predicted), summed over folds; one extra last column counts
  // "unknown" answers (all zero for classifiers that never answer unknown).
  Eigen::MatrixXi confusion;
  double accuracy = 0.0;
  std::vector<ClassFigures> per_class;
  std::vector<Misclassified> misclassified;
  int64_t predictions = 0;
  double seconds = 0.0;      // wall time of the whole evaluation
  double fit_seconds = 0.0;  // summed over folds
  double predict_seconds = 0.0;
};

struct EvaluationControl {
  std::function<void(int done, int total)> progress;
  const std::atomic<bool>* cancel =
      nullptr;      // set to true to stop; evaluate() throws tactile::Error("cancelled")
  int threads = 0;  // 0 = hardware concurrency
};

EvaluationResult evaluate(const Dataset& dataset, const std::string& classifier_specification,
                          const Protocol& protocol, uint64_t seed,
                          const EvaluationControl& control = {});

nlohmann::json to_json(const EvaluationResult& result);

}  // namespace tactile::ml

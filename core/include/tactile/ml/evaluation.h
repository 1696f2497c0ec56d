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
// Folds of a protocol over a dataset; every random step draws from `seed` (spec §6.6):
//   kfold:K[xR]  stratified: per repetition, per class (ascending class index, classes
//                numbered in first-seen order) shuffle the class's rows and deal them
//                round-robin to folds 0..K-1; repetition r reshuffles from the same stream.
//   loo          one fold per row.
//   loso         one fold per subject (first-seen order), its rows as the test set.
//   holdout:FxR  R stratified hold-outs: per class, min(round(F n_c), n_c - 1) shuffled rows
//                are tested (a class of one sample is only trained on).
//   split:A/B    one fold: rows matching A train, rows matching B test.
// Train and test lists are ascending. Throws tactile::Error naming --protocol on a protocol
// the dataset cannot give (more folds than rows, loso without subjects, a query that
// matches no row, a row in both halves of a split).
std::vector<Fold> make_folds(const Dataset& dataset, const Protocol& protocol, uint64_t seed);
// Rows matching a query `key=value[,key=value]` (AND). Keys: class, subject, recording,
// segment_id or any metadata key. Throws tactile::Error naming `where` and the query when it
// is malformed, names a key no row has, or matches no row.
std::vector<int64_t> rows_matching(const Dataset& dataset, const std::string& query,
                                   const std::string& where);

struct ClassFigures {
  double precision = 0.0;    // M[k][k] / column k (0 when nothing was predicted as k)
  double recall = 0.0;       // M[k][k] / row k (0 for an empty row)
  double false_alarm = 0.0;  // (column k - M[k][k]) / row k (Robovie, spec §4.10; may exceed 1)
  int64_t support = 0;       // row k, "unknown" answers included
};

struct Misclassified {
  int64_t row = 0;         // dataset row
  int64_t segment_id = 0;  // label id in the label store
  std::string recording;
  std::string true_class;
  std::string predicted_class;  // "unknown" for kUnknownClass
  int fold = 0;                 // index into the protocol's folds
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
  uint64_t seed = 0;
  // Per fold, the fitted model as a specification ("knn:k=3,..."); for grid search the
  // parameters it chose on that training fold.
  std::vector<std::string> fold_models;
};

// Spec §6.7 on a confusion matrix with rows = true classes and columns = predicted ones, an
// optional extra last column counting "unknown" (not correct, no false alarm).
double accuracy_of(const Eigen::MatrixXi& confusion);
std::vector<ClassFigures> class_figures(const Eigen::MatrixXi& confusion);

struct EvaluationControl {
  // Called after each fold, from the worker that finished it (calls are serialised).
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

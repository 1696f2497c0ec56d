#pragma once
// Evaluation protocols (spec §6.6-6.7): stratified k-fold (repeated, seeded),
// leave-one-out, leave-one-subject-out, repeated stratified hold-out, train/test split by
// metadata; confusion matrices summed over folds, per-class figures, the misclassified
// segments, timings. Long runs report progress and can be cancelled.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct Protocol {
  enum class Kind {
    kKFold,
    kLeaveOneOut,
    kLeaveOneSubjectOut,
    kLeaveOneGroupOut,
    kHoldout,
    kSplit
  };
  Kind kind = Kind::kKFold;
  int folds = 10;               // k-fold
  int repetitions = 1;          // k-fold and hold-out
  double test_fraction = 0.15;  // hold-out
  std::string train_query;      // split: "side=back,condition=stationary"
  std::string test_query;       // split: "side=front"
  std::string group_column;     // group: "recording", "subject", "session", any metadata key
  // "kfold:K[xR]" | "loo" | "loso" | "group:COLUMN" | "holdout:FxR" | "split:QUERY/QUERY";
  // throws tactile::Error naming --protocol.
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
//   group:COLUMN one fold per value of a column of the table (recording, subject, class or
//                any metadata key; first-seen order): leave one group out, for corpora
//                without subject ids.
//   holdout:FxR  R stratified hold-outs: per class, min(round(F n_c), n_c - 1) shuffled rows
//                are tested (a class of one sample is only trained on).
//   split:A/B    one fold: rows matching A train, rows matching B test.
// Train and test lists are ascending. Throws tactile::Error naming --protocol on a protocol
// the dataset cannot give (more folds than rows, loso without subjects, a query that
// matches no row, a row in both halves of a split).
std::vector<Fold> make_folds(const Dataset& dataset, const Protocol& protocol, uint64_t seed);
// The group each row belongs to under a protocol that holds groups out: its subject for
// loso, its value of the column for group:COLUMN; empty for the other protocols. Throws as
// make_folds on a row without one.
std::vector<std::string> protocol_groups(const Dataset& dataset, const Protocol& protocol);

// The groups of the training rows of the fit running on this thread (one per row of the
// matrix fit() is given), when its evaluation holds groups out; empty otherwise. A search
// inside the fit (auto) then keeps its inner folds to whole groups, as the outer ones are.
const std::vector<std::string>& fit_groups();
// Sets fit_groups() on this thread for its lifetime (and restores the one before).
class FitGroupsScope {
 public:
  explicit FitGroupsScope(const std::vector<std::string>* groups);
  ~FitGroupsScope();
  FitGroupsScope(const FitGroupsScope&) = delete;
  FitGroupsScope& operator=(const FitGroupsScope&) = delete;

 private:
  const std::vector<std::string>* previous_;
};

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

// One test prediction: the row it was made for, where that row's segment lies, what was
// true and what was answered, and how sure the answer was (confidence_of its scores; 0
// when the evaluation did not ask for scores).
struct RowPrediction {
  int64_t row = 0;         // dataset row
  int64_t segment_id = 0;  // label id in the label store (the row number without one)
  std::string recording;
  double t0 = 0.0, t1 = 0.0;  // the segment's bounds (the row's t0/t1 metadata; 0 without)
  std::string region;         // the row's region metadata ("" without)
  int truth = 0;              // index into classes
  int predicted = 0;          // index into classes, or kUnknownClass
  double score = 0.0;
  double margin = 0.0;
  int fold = 0;
};

// A dataset row's place: row, segment id, recording, t0/t1 and region from its metadata
// (truth, predicted and the rest left at their defaults).
RowPrediction row_place(const Dataset& dataset, int64_t row);

// How much one feature column served a classifier (Classifier::feature_importances).
struct FeatureImportance {
  std::string feature;  // the column's name
  double importance = 0.0;
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
  // Every test prediction in fold order, then test-row order within a fold.
  std::vector<RowPrediction> rows;
  int64_t predictions = 0;
  double seconds = 0.0;      // wall time of the whole evaluation
  double fit_seconds = 0.0;  // summed over folds
  double predict_seconds = 0.0;
  uint64_t seed = 0;
  // Per fold, the fitted model as a specification ("knn:k=3,..."); for grid search the
  // parameters it chose on that training fold.
  std::vector<std::string> fold_models;
  // The classifier's feature importances averaged over folds (each fold's sum to 1), the
  // columns with a non-zero one, largest first (ties in column order); empty for a classifier
  // that reports none.
  std::vector<FeatureImportance> importances;
};

// Spec §6.7 on a confusion matrix with rows = true classes and columns = predicted ones, an
// optional extra last column counting "unknown" (not correct, no false alarm).
double accuracy_of(const Eigen::MatrixXi& confusion);
// The mean of the per-class recalls (balanced accuracy).
double mean_recall(const EvaluationResult& result);
std::vector<ClassFigures> class_figures(const Eigen::MatrixXi& confusion);

struct EvaluationControl {
  // Called after each fold, from the worker that finished it (calls are serialised).
  std::function<void(int done, int total)> progress;
  const std::atomic<bool>* cancel =
      nullptr;      // set to true to stop; evaluate() throws tactile::Error("cancelled")
  int threads = 0;  // 0 = every core, or 1 inside a fold of an evaluation that runs in parallel
  // Also compute each prediction's scores (RowPrediction::score and margin); costs one
  // scores() call per fold for classifiers that cannot give both at once.
  bool scores = false;
};

EvaluationResult evaluate(const Dataset& dataset, const std::string& classifier_specification,
                          const Protocol& protocol, uint64_t seed,
                          const EvaluationControl& control = {});

// The result as JSON (with `importances: [{feature, importance}]` when there are any); with
// `with_rows`, also `rows: [{recording, t0, t1, region, true,
// predicted, score, margin, segment_id, fold}]`, one per test prediction.
nlohmann::json to_json(const EvaluationResult& result, bool with_rows = false);

// "Train all" (MATLAB's Classification Learner): every classifier of the catalogue with
// its default parameters (the entries marked preset: not the searches and wrappers).
std::vector<std::string> preset_names();
struct PresetOutcome {
  std::string classifier;
  std::optional<EvaluationResult> result;  // empty when the preset does not fit the data
  std::string skipped;                     // why (the error it raised), when it does not
};
// One line of the train-all table: classifier, accuracy, mean_recall and seconds, or
// skipped with the reason.
nlohmann::json summary_json(const PresetOutcome& outcome);
// Evaluates every preset in turn on the same folds, in train_all_plan's order (train_all.h:
// the quick ones first; past a preset's widest, on the columns chosen in each fold). A preset
// that cannot learn from the data (an error in fit) is kept with the reason and the next one
// runs; cancelling stops all (throws tactile::Error("evaluation", "cancelled")). `each` is
// called after each preset with (outcome, index, total); control.progress with thousandths
// of the estimated work done (done, 1000).
std::vector<PresetOutcome> evaluate_all(
    const Dataset& dataset, const Protocol& protocol, uint64_t seed,
    const EvaluationControl& control = {},
    const std::function<void(const PresetOutcome&, int, int)>& each = {});
// Reads what to_json(result, true) wrote (the workbench opens result files). Throws
// tactile::Error naming `where` and the field that is missing or malformed.
EvaluationResult evaluation_from_json(const nlohmann::json& document, const std::string& where);

// Which rows of a result fall in one cell of its confusion matrix (predicted may be
// kUnknownClass), in result order.
std::vector<const RowPrediction*> rows_in_cell(const EvaluationResult& result, int truth,
                                               int predicted);

}  // namespace tactile::ml

#pragma once
// The train-all result: every classifier preset evaluated on the same folds of one feature
// table, best first. `tactile evaluate --classifier all --out` writes it, the workbench opens it
// (--evaluation, File menu) and makes the same from its own Train all; this is its one type,
// reader and writer. A file of a single evaluation reads as a train-all of one.
//
//   {"protocol": "kfold:5", "seed": 1, "features": "table.csv",
//    "presets": [{"classifier", "accuracy", "mean_recall", "seconds"} | {"classifier", "skipped"}],
//    "evaluations": [to_json(result, true) + "features", ...]}

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "tactile/ml/evaluation.h"

namespace tactile::ml {

// What Train all runs on a table of `rows` x `columns` with `classes` classes, in the order it
// runs them: every preset, the quick ones first by an estimate of each one's training work
// (`cost`, the same unit for all; the order and the progress bar's shares come from it). A
// preset whose training grows out of proportion past its widest (ClassifierEntry::widest:
// boosting and bagging scan every column at every split, a full covariance is P x P) learns,
// on a wider table, from the `widest` columns that best separate each training fold's
// classes (`select:k=WIDEST,base=NAME`, as auto does); its row names that.
struct TrainAllStep {
  std::string classifier;  // a specification for make_classifier
  double cost = 0.0;
};
std::vector<TrainAllStep> train_all_plan(int64_t rows, int64_t columns, int classes);

struct TrainAllResult {
  std::string protocol;
  uint64_t seed = 0;
  std::string features;                 // the table it was run on, as given ("" when not known)
  std::vector<PresetOutcome> outcomes;  // best first; skipped presets last, with the reason
};

// Best accuracy first; presets that did not fit the data after all that did (stable).
void sort_best_first(std::vector<PresetOutcome>& outcomes);
// The index of the outcome with the highest accuracy; -1 when none fitted.
int best_outcome(const std::vector<PresetOutcome>& outcomes);

nlohmann::json to_json(const TrainAllResult& result);
// Throws tactile::Error naming `where` and the field that is missing or malformed.
TrainAllResult train_all_from_json(const nlohmann::json& document, const std::string& where);
// Written to a temporary file and renamed into place.
void write_train_all_file(const std::string& path, const TrainAllResult& result);
// A train-all file, or a file of one evaluation (a train-all of one). Throws tactile::Error
// naming the file: missing, not JSON, holding no evaluation.
TrainAllResult read_train_all_file(const std::string& path);

}  // namespace tactile::ml

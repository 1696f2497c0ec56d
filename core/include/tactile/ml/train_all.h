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

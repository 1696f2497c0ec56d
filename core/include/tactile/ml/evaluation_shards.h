#pragma once
// The work of `tactile evaluate` as items for shards (tactile/shards/shard.h): the folds of one
// classifier, or for `--classifier all` every preset's folds, preset after preset (item
// preset * folds + fold). Each item is one fold's outcome, kept exactly (predictions, scores,
// the model it chose, importances, timings), so the result assembled from every shard's items
// is the one a single process computes.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tactile/ml/evaluation.h"
#include "tactile/shards/shard.h"

namespace tactile::ml {

struct EvaluationJob {
  std::vector<std::string> classifiers;  // one, or preset_names() for train-all
  Protocol protocol;
  uint64_t seed = 1;
  bool scores = false;  // EvaluationControl::scores
  // Train-all: a classifier that fails is skipped with its reason (evaluate_all); otherwise
  // the failure is the job's.
  bool skip_failures = false;
};

// Every item's key, "CLASSIFIER#FOLD:TEST_ROWS", in item order (the shards' plan).
std::vector<std::string> evaluation_plan(const Dataset& dataset, const EvaluationJob& job);

// Runs the shard's items and returns its `done` entries: {index, classifier, fold, predicted,
// scores, model, importances, fit_seconds, predict_seconds, seconds}, or {index, classifier,
// fold, failed} for a fold that failed (or was not taken after one did). Throws a failure
// when job.skip_failures is false; `control.progress` counts this shard's folds.
nlohmann::json run_evaluation_items(const Dataset& dataset, const EvaluationJob& job,
                                    const Shard& shard, const EvaluationControl& control = {});

// Each classifier's outcome from every item of the job in item order (items_in_order): the
// result evaluate() gives, its `seconds` the sum of its folds' wall times, or skipped with
// the first failure in fold order (thrown as tactile::Error when !job.skip_failures).
std::vector<PresetOutcome> outcomes_from_items(const Dataset& dataset, const EvaluationJob& job,
                                               const std::vector<nlohmann::json>& items);

// Sets every time of a result to 0: results of the same inputs then have the same bytes
// (`--no-timings`).
void clear_timings(EvaluationResult& result);

}  // namespace tactile::ml

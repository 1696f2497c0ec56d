#pragma once
// evaluate() in its three steps, for the evaluation's shards (evaluation_shards.cpp), which
// run some folds in one process and assemble the result from every fold's outcome in
// another: prepare (checks, classes, folds), run the folds asked for, assemble in fold order.

#include <exception>
#include <string>
#include <vector>

#include "tactile/ml/evaluation.h"

namespace tactile::ml {

// What one fold hands back; assembled in fold order so threads never change the result.
struct FoldOutcome {
  std::vector<int> predicted;  // per test row
  Matrix scores;               // per test row, when asked for
  std::string model;
  std::vector<double> importances;  // per feature column, when the classifier gives them
  double fit_seconds = 0.0;
  double predict_seconds = 0.0;
  double seconds = 0.0;  // the fold's wall time
  bool ran = false;      // false: not run, as a fold failed before it was taken
  std::exception_ptr failure;
};

struct EvaluationSetup {
  std::string given_specification;  // as asked
  std::string specification;        // as fitted (auto on a stacked table: with its pipelines)
  Protocol protocol;
  uint64_t seed = 0;
  std::vector<std::string> class_names;  // first-seen order
  std::vector<int> classes;              // per row, into class_names
  std::vector<Fold> folds;
  std::vector<std::string> groups;  // protocol_groups
};

// Throws tactile::Error as evaluate() does before any fold runs.
EvaluationSetup prepare_evaluation(const Dataset& dataset, const std::string& given_specification,
                                   const Protocol& protocol, uint64_t seed);
// The outcomes of folds `which` (indices into setup.folds), in that order, on worker threads
// as control says; throws "cancelled". A failing fold keeps its failure and stops the taking
// of further folds: every fold before a failing one was taken, so the first failure in fold
// order is the same whatever the threads (and shards) did.
std::vector<FoldOutcome> run_folds(const Dataset& dataset, const EvaluationSetup& setup,
                                   const std::vector<int>& which, const EvaluationControl& control);
void rethrow_first_failure(const std::vector<FoldOutcome>& outcomes);
// The result from every fold's outcome (index = fold); `seconds` left 0 for the caller.
EvaluationResult assemble_evaluation(const Dataset& dataset, const EvaluationSetup& setup,
                                     const std::vector<FoldOutcome>& outcomes);

}  // namespace tactile::ml

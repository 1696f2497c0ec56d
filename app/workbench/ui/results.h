#pragma once
// The results the classifier views show: trained here (model_panel.h) or opened from files,
// the feature table they are about, and which row is current.

#include <memory>
#include <string>
#include <vector>

#include "workbench_state.h"

namespace tactile {

// The evaluation the views show (the current row of the results), or null.
const ml::EvaluationResult* current_evaluation(const WorkbenchState& state);
// Makes row `index` of the results current: its confusion, scatter rings, SOM.
void choose_result(WorkbenchState& state, int index);
// Makes `table` the one the results are about; the views' maps of another table are dropped.
void set_results_table(WorkbenchState& state, std::shared_ptr<const Dataset> table);

// --evaluation (one result, or a train-all file), --model (a SOM), --features (a table).
// Each reports failure in state.error and returns false.
bool open_evaluation_file(WorkbenchState& state, const std::string& path);
bool open_model_file(WorkbenchState& state, const std::string& path);
bool open_features_file(WorkbenchState& state, const std::string& path);

// The recording file of a recording id: in the workspace, else beside the result files.
std::string recording_file(const WorkbenchState& state, const std::string& recording_id);

// Each row's class index in the current evaluation (-1: not tested there) and whether it
// was misclassified, for the scatter's and the SOM's colours and rings.
struct RowOutcome {
  int truth = -1;
  int predicted = -1;
  bool tested = false;
  const ml::RowPrediction* prediction = nullptr;
};
std::vector<RowOutcome> row_outcomes(const WorkbenchState& state);

}  // namespace tactile

#pragma once
// The workbench's classifier side, shared by the model panel and the confusion, scatter,
// SOM and somatosensory views: training in the background (the job "training"), results
// opened from files, the way from a confusion cell to a segment and back.

#include <string>

#include "workbench_state.h"

namespace tactile {

// Starts training on the open recording's skin over the workspace's label store, with
// the panel's choices; `classifier` is a specification or "all". Reports in state.error. Its
// results are shown as they arrive; when it ends, the best becomes current.
bool start_training(WorkbenchState& state, const std::string& classifier);

// Applies the last model trained here (one classifier: fitted on every row and saved in
// the workspace's models/ folder) to the open recording's segments, as a job; when it ends
// its answers replace the recording's prediction lane as one command.
// The model is that of the results row the views show (after Train all: fitted on every row
// of the table by the job, then saved in models/ too), else of the classifier box.
bool predict_open_recording(WorkbenchState& state);
// Whether Predict has a model to use or to fit (the button's state).
bool can_predict(const WorkbenchState& state);

// The evaluation the views show (the current row of the results), or null.
const ml::EvaluationResult* current_evaluation(const WorkbenchState& state);
// Makes row `index` of the results current: its confusion, scatter rings, SOM.
void choose_result(WorkbenchState& state, int index);

// --evaluation (one result, or a train-all file), --model (a SOM), --features (a table).
// Each reports failure in state.error and returns false.
bool open_evaluation_file(WorkbenchState& state, const std::string& path);
bool open_model_file(WorkbenchState& state, const std::string& path);
bool open_features_file(WorkbenchState& state, const std::string& path);

// Selects a confusion cell: its segments become the list, the first selected.
void select_cell(WorkbenchState& state, int truth, int predicted);
// Goes to one prediction's segment: opens its recording, moves the cursor and the plot
// to it, replays it on the skin with its region outlined, both classes named.
void land_on(WorkbenchState& state, const ml::RowPrediction& row);
// The next (+1) or previous (-1) misclassified prediction after the landed one.
bool walk_misclassified(WorkbenchState& state, int direction);
// Carries out a landing asked for by land_on (after the frame: it may open a file).
void carry_out_landing(WorkbenchState& state);

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

// The SOM map of the current table (fitted once per table, or the opened model).
bool ensure_som(WorkbenchState& state);
// The table's rows on their first two principal components (computed once per table).
bool ensure_scatter(WorkbenchState& state);
// The open recording's (or the workspace's) somatosensory map for the current modality, from
// its cache or computed on a worker; false until it is there (the view shows the job).
bool ensure_somatosensory(WorkbenchState& state);

}  // namespace tactile

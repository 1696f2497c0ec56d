#pragma once
// The model panel's actions: training in the background (the job "training") and Predict
// (the job "predict"). The panel itself is drawn by view_model.cpp.

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

}  // namespace tactile

#pragma once
// Labelling from the keyboard, ELAN's habits: `[` and `]` mark start and end at the
// time cursor (moved back by the reaction time while playing), 1-9 choose the class
// from the skin's vocabulary (0 the tenth, Shift+digits the 11th-20th; C: a type-ahead picker
// for any class), Enter commits;
// G runs the last segmenter again (adaptive at first), A / R accept / reject a
// suggestion, Y confirms a prediction (a digit corrects it), U goes to the least sure one, S
// toggles snapping; Tab / Shift+Tab walk the labels of the operator's lane, arrows step by a sample
// (Shift: a second), Delete removes, Ctrl+Z / Ctrl+Shift+Z undo and redo through the store's
// journal, Escape drops the marks. Each edit is one transaction in the label store the moment it is
// made.

#include <functional>
#include <optional>
#include <vector>

#include "workbench_state.h"

namespace tactile {

// Moves the bounds of an own label dragged in the timeline (released last frame). The keys
// that call the edits below are in keys.h's table.
void apply_dragged_bounds(WorkbenchState& state);
// The type-ahead class picker (key C; for vocabularies beyond the twenty class keys):
// type part of a name, Enter takes the first match as the class. Drawn every frame.
void draw_class_picker(WorkbenchState& state);

// Several writers of one store (two workbenches, a workbench and `tactile segment` or
// `predict`): once a frame, the store's change count (microseconds) says whether another
// writer committed; then the labels are reloaded (the selection kept where its labels still
// exist, the cursor where it is) and the notice names who did what ("bob added 2 labels").
// A store created beside the recording by another writer is opened (checked every 30 frames).
void follow_other_writers(WorkbenchState& state);

// Carries out one command (tactile/labels/commands.h): the edit written in one transaction
// and one journal batch under the operator, so Ctrl+Z takes it back whole. Returns the new
// labels' ids; nothing when the store refused (the reason in state.error). An edit of a label
// another writer changed or removed meanwhile is refused whole (EditConflict): the error names
// the label and the other annotator, and the view reloads to show the other's state.
std::optional<std::vector<int64_t>> apply_command(WorkbenchState& state, const LabelEdit& edit);

// The edits the keys make; also for mouse actions. Each reports failure in
// state.error and returns false.
bool mark_start(WorkbenchState& state);
bool mark_end(WorkbenchState& state);
bool choose_class(WorkbenchState& state, int key);  // 1-based position in the vocabulary
bool commit_label(WorkbenchState& state);
bool remove_selected_label(WorkbenchState& state);
bool undo_edit(WorkbenchState& state, bool redo);
// Selects the next (+1) or previous (-1) label of the operator's lane from the cursor
// and moves the cursor to its start.
bool walk_labels(WorkbenchState& state, int direction);

// Runs a segmenter on the open recording (parameters from the Labels menu) as the job
// "segmenter"; when it ends its segments replace its earlier ones for this recording, less the
// rejected ones, as one command, and the first is selected.
bool run_segmenter(WorkbenchState& state, const std::string& method);
// Labels > Fit segmenter to my labels: a job that chooses adaptive's parameters on the
// operator's labels in the open recording (at least three) and saves them as the preset
// "fitted" beside the label store (the job "fit segmenter"); once it has ended G runs adaptive
// with them. Never changes a label.
bool fit_segmenter_to_labels(WorkbenchState& state);
// A: the selected suggestion (a segmenter's label) becomes a label of the operator's
// lane with its bounds and region, and the class chosen with 1-9 (else its own when
// it has one); R: rejects it (remembered in the store). Both move to the next one.
bool accept_suggestion(WorkbenchState& state);
bool reject_suggestion(WorkbenchState& state);

// The prediction lane (labels of source model): Y confirms the selected prediction,
// its class's digit corrects it; either writes a manual label of the operator with its
// bounds and region, then moves to the next most uncertain. U goes to the prediction
// with the smallest margin that no label of the operator covers yet.
bool confirm_prediction(WorkbenchState& state, const std::string& corrected_class);
bool next_uncertain_prediction(WorkbenchState& state);

// Moves the bounds of an own label (a dragged edge); one transaction.
bool move_label_bounds(WorkbenchState& state, int64_t label, double t0, double t1);
// `t` moved, when snapping is on, to the nearest boundary of the other lanes' labels
// (segmenters, ground truth) within `tolerance` seconds, else to the nearest of the
// signal's onsets and releases (where some taxel leaves or returns to its noise band).
double snapped(WorkbenchState& state, double t, double tolerance);

// The labels of the operator's lane (manual, this annotator), or null when empty.
const LaneIndex* active_lane(const WorkbenchState& state);

}  // namespace tactile

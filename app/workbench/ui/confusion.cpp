#include "confusion.h"

#include <algorithm>

#include "results.h"
#include "views.h"

namespace tactile {

void select_cell(WorkbenchState& state, int truth, int predicted) {
  AnalysisState& analysis = state.analysis;
  analysis.confusion.cell_true = truth;
  analysis.confusion.cell_predicted = predicted;
  analysis.confusion.cell_rows.clear();
  analysis.confusion.cell_selected = 0;
  const ml::EvaluationResult* result = current_evaluation(state);
  if (!result) return;
  for (size_t k = 0; k < result->rows.size(); ++k)
    if (result->rows[k].truth == truth && result->rows[k].predicted == predicted)
      analysis.confusion.cell_rows.push_back(k);
  // The least sure first: the segments most worth a look, in a right cell as in a wrong one.
  std::stable_sort(
      analysis.confusion.cell_rows.begin(), analysis.confusion.cell_rows.end(),
      [&](size_t a, size_t b) { return result->rows[a].margin < result->rows[b].margin; });
  analysis.confusion.list_active = !analysis.confusion.cell_rows.empty();
  if (analysis.confusion.cell_rows.empty() && result->rows.empty())
    state.notice = "this result lists no rows (written without --out?)";
}

void land_on(WorkbenchState& state, const ml::RowPrediction& row) {
  state.analysis.confusion.landed = row;
  state.analysis.confusion.landing_pending = true;
  if (!state.document || state.document->recording_id() != row.recording) {
    const std::string file = recording_file(state, row.recording);
    if (file.empty()) {
      state.error = "no file for recording " + row.recording + " in the workspace";
      state.analysis.confusion.landed.reset();
      return;
    }
    state.open_request = file;
  }
}

void carry_out_landing(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.confusion.landing_pending || !analysis.confusion.landed || !state.document) return;
  const ml::RowPrediction& row = *analysis.confusion.landed;
  if (state.document->recording_id() != row.recording) return;  // still opening
  analysis.confusion.landing_pending = false;
  const double span = std::max(0.2, row.t1 - row.t0);
  state.plot.view_t0 = row.t0 - span;
  state.plot.view_t1 = row.t1 + span;
  state.selection.taxels.clear();
  state.selection.segments = {row.segment_id};
  state.selection.labels.clear();
  for (const Label& label : state.document->labels)
    if (label.id == row.segment_id) state.selection.labels = {label.id};
  state.clock.seek(row.t0);
  state.clock.play();
  analysis.confusion.replay_until = row.t1;
  const ml::EvaluationResult* result = current_evaluation(state);
  const auto name = [&](int k) {
    return result && k >= 0 && k < static_cast<int>(result->classes.size())
               ? result->classes[static_cast<size_t>(k)]
               : std::string("unknown");
  };
  state.error.clear();
  state.notice = row.recording + " " + format_seconds(row.t0) + ": true " + name(row.truth) +
                 ", predicted " + name(row.predicted);
}

bool walk_misclassified(WorkbenchState& state, int direction) {
  const ml::EvaluationResult* result = current_evaluation(state);
  if (!result || result->rows.empty()) return fail(state, "no evaluation with rows open");
  const auto count = static_cast<int64_t>(result->rows.size());
  int64_t start = -1;
  if (state.analysis.confusion.landed)
    for (int64_t k = 0; k < count; ++k)
      if (result->rows[static_cast<size_t>(k)].row == state.analysis.confusion.landed->row &&
          result->rows[static_cast<size_t>(k)].fold == state.analysis.confusion.landed->fold)
        start = k;
  if (start < 0 && direction < 0) start = count;
  for (int64_t step = 1; step <= count; ++step) {
    const int64_t k = ((start + direction * step) % count + count) % count;
    const ml::RowPrediction& row = result->rows[static_cast<size_t>(k)];
    if (row.truth == row.predicted) continue;
    land_on(state, row);
    return true;
  }
  state.notice = "no misclassified segment";
  return false;
}

}  // namespace tactile

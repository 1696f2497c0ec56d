#include "results.h"

#include <filesystem>

#include "jobs.h"
#include "tactile/error.h"
#include "tactile/ml/train_all.h"
#include "tactile/skins/skin.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

void reset_views(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  analysis.confusion.cell_true = analysis.confusion.cell_predicted = -1;
  analysis.confusion.cell_rows.clear();
  analysis.confusion.cell_selected = 0;
  analysis.confusion.list_active = false;
  analysis.som.table = nullptr;
  analysis.som.neuron = -1;
  analysis.scatter.table = nullptr;
  drop_job(state, "scatter");  // it was for the table before
  analysis.som.held = analysis.scatter.held = false;
}

}  // namespace

void set_results_table(WorkbenchState& state, std::shared_ptr<const Dataset> dataset) {
  AnalysisState& analysis = state.analysis;
  analysis.results.dataset_layout = dataset->shared_metadata("layout");
  // A table's classes take its skin's colours when no recording of that skin is open.
  if (!state.document || state.document->layout.id != analysis.results.dataset_layout)
    state.class_colours.set_vocabulary(skin_classes(analysis.results.dataset_layout));
  analysis.results.dataset = std::move(dataset);
  analysis.som.model.reset();
  analysis.som.quality.reset();
  analysis.som.spread_for = nullptr;
  drop_job(state, "som");
  reset_views(state);
}

const ml::EvaluationResult* current_evaluation(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  if (analysis.results.current < 0 ||
      analysis.results.current >= static_cast<int>(analysis.results.rows.size()))
    return nullptr;
  const auto& result = analysis.results.rows[static_cast<size_t>(analysis.results.current)].result;
  return result ? &*result : nullptr;
}

void choose_result(WorkbenchState& state, int index) {
  AnalysisState& analysis = state.analysis;
  analysis.results.current = index;
  // The scatter and the SOM belong to the table, not to the result: only the clicked
  // cell and the rings (drawn from the current result) change.
  analysis.confusion.cell_true = analysis.confusion.cell_predicted = -1;
  analysis.confusion.cell_rows.clear();
  analysis.confusion.cell_selected = 0;
  analysis.confusion.list_active = false;
  if (current_evaluation(state)) analysis.tab_request = "confusion";
  // The classifier box names the row shown, so Run and Predict act on what the views show.
  if (index >= 0 && index < static_cast<int>(analysis.results.rows.size())) {
    const std::string& name = analysis.results.rows[static_cast<size_t>(index)].classifier;
    analysis.panel.classifier.fill('\0');
    name.copy(analysis.panel.classifier.data(), analysis.panel.classifier.size() - 1);
  }
}

bool open_evaluation_file(WorkbenchState& state, const std::string& path) {
  AnalysisState& analysis = state.analysis;
  try {
    ml::TrainAllResult opened = ml::read_train_all_file(path);
    analysis.results.rows = std::move(opened.outcomes);
    analysis.results.from = fs::path(path).filename().string();
    analysis.results.dataset.reset();
    analysis.som.model.reset();
    analysis.som.quality.reset();
    analysis.som.spread_for = nullptr;
    analysis.som.classes.clear();
    // The table it was made from, for the scatter and the SOM (relative to the result).
    if (!opened.features.empty()) {
      fs::path table(opened.features);
      if (table.is_relative() && !fs::exists(table)) table = fs::path(path).parent_path() / table;
      if (fs::exists(table))
        set_results_table(state, std::make_shared<const Dataset>(read_dataset_csv(table.string())));
    }
  } catch (const std::exception& error) {
    return fail(state, std::string("cannot open the evaluation: ") + error.what());
  }
  choose_result(state, 0);
  return true;
}

bool open_model_file(WorkbenchState& state, const std::string& path) {
  try {
    SavedModel model = read_model_file(path);
    auto* som = dynamic_cast<ml::SomClassifier*>(model.classifier.get());
    if (!som)
      throw Error(path, "a " + model.classifier->name() + " model: only a SOM has a map to show");
    model.classifier.release();
    state.analysis.som.model.reset(som);
    state.analysis.som.quality.reset();
    state.analysis.som.spread_for = nullptr;
    state.analysis.som.classes = model.classes;
    state.analysis.som.table = nullptr;
    state.analysis.som.winners.clear();
    state.analysis.tab_request = "som";
  } catch (const std::exception& error) {
    return fail(state, std::string("cannot open the model: ") + error.what());
  }
  return true;
}

bool open_features_file(WorkbenchState& state, const std::string& path) {
  try {
    set_results_table(state, std::make_shared<const Dataset>(read_dataset_csv(path)));
    if (state.analysis.results.rows.empty()) state.analysis.tab_request = "scatter";
  } catch (const std::exception& error) {
    return fail(state, std::string("cannot open the features: ") + error.what());
  }
  return true;
}

//---- From a cell to a segment ---------------------------------------------------------------

std::string recording_file(const WorkbenchState& state, const std::string& recording_id) {
  for (const std::string& file : state.workspace_files)
    if (fs::path(file).stem() == recording_id) return file;
  for (const std::string& beside :
       {state.options.evaluation_path, state.options.features_path, state.options.model_path}) {
    if (beside.empty()) continue;
    const fs::path candidate = fs::path(beside).parent_path() / (recording_id + ".h5");
    if (fs::exists(candidate)) return candidate.string();
  }
  return "";
}

std::vector<RowOutcome> row_outcomes(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  std::vector<RowOutcome> outcomes(
      analysis.results.dataset ? static_cast<size_t>(analysis.results.dataset->rows()) : 0);
  const ml::EvaluationResult* result = current_evaluation(state);
  if (!result) return outcomes;
  for (const ml::RowPrediction& row : result->rows)
    if (row.row >= 0 && row.row < static_cast<int64_t>(outcomes.size())) {
      RowOutcome& outcome = outcomes[static_cast<size_t>(row.row)];
      // With repetitions a row is tested more than once: a wrong answer wins.
      if (outcome.tested && outcome.truth != outcome.predicted) continue;
      outcome = {row.truth, row.predicted, true, &row};
    }
  return outcomes;
}

//---- Derived views --------------------------------------------------------------------------

}  // namespace tactile

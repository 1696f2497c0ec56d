#include "analysis.h"

#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>

#include "jobs.h"
#include "labelling.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/predict.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/ml/table_maps.h"
#include "tactile/ml/train_all.h"
#include "tactile/skins/skin.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

std::string label_database(const WorkbenchState& state) {
  if (state.document && !state.document->labels_path.empty()) return state.document->labels_path;
  if (!state.options.labels_path.empty()) return state.options.labels_path;
  return (fs::path(state.workspace) / "labels.db").string();
}

void reset_views(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  analysis.cell_true = analysis.cell_predicted = -1;
  analysis.cell_rows.clear();
  analysis.cell_selected = 0;
  analysis.list_active = false;
  analysis.som_for = nullptr;
  analysis.som_neuron = -1;
  analysis.scatter_for = nullptr;
  drop_job(state, "scatter");  // it was for the table before
  analysis.som_held = analysis.scatter_held = false;
}

void set_dataset(WorkbenchState& state, std::shared_ptr<const Dataset> dataset) {
  AnalysisState& analysis = state.analysis;
  analysis.dataset_layout = dataset->shared_metadata("layout");
  // A table's classes take its skin's colours when no recording of that skin is open.
  if (!state.document || state.document->layout.id != analysis.dataset_layout)
    state.class_colours.set_vocabulary(skin_classes(analysis.dataset_layout));
  analysis.dataset = std::move(dataset);
  analysis.som.reset();
  analysis.som_quality.reset();
  analysis.som_spread_for = nullptr;
  drop_job(state, "som");
  reset_views(state);
}

}  // namespace

//---- Training -------------------------------------------------------------------------------

namespace {

// The table the results are about, once: the same table again keeps the views' maps.
void show_table(WorkbenchState& state, std::shared_ptr<const Dataset> table,
                const std::string& pipeline) {
  AnalysisState& analysis = state.analysis;
  if (!table || analysis.dataset == table) return;
  analysis.results_from = analysis.last_request.layout + ", " + pipeline + " features, " +
                          std::to_string(table->rows()) + " segments";
  set_dataset(state, std::move(table));
}

// The running job's results that arrived since the last frame; the first becomes current,
// without leaving the model tab, which shows the run's progress and Cancel.
void show_results_so_far(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.so_far || analysis.so_far->count() == analysis.so_far_shown) return;
  show_table(state, analysis.so_far->table(), analysis.so_far->pipeline());
  const bool first = analysis.so_far_shown == 0;
  analysis.results = analysis.so_far->outcomes();
  analysis.so_far_shown = analysis.results.size();
  if (!first) return;
  const std::string tab = analysis.tab_request;
  choose_result(state, ml::best_outcome(analysis.results));
  analysis.tab_request = tab;
}

// The training run's end (jobs.h): its results, the table, the model and its evaluation file;
// after a cancel, the results that finished before it.
void apply_training(WorkbenchState& state, Job<TrainingOutcome>& job) {
  AnalysisState& analysis = state.analysis;
  show_results_so_far(state);
  const JobStatus status = job.status();
  if (status == JobStatus::kFailed) {
    state.error = "training failed: " + job.error();
    analysis.so_far.reset();
    return;
  }
  std::optional<TrainingOutcome> outcome = job_result(state, job);
  const std::shared_ptr<TrainingSoFar> so_far = std::move(analysis.so_far);
  if (status == JobStatus::kCancelled) {
    // What finished before Cancel stays: each result is whole.
    const size_t kept = so_far ? so_far->count() : 0;
    state.notice = kept == 0 ? "training cancelled"
                             : "training cancelled: kept the " + std::to_string(kept) +
                                   " finished result" + (kept == 1 ? "" : "s");
    if (kept > 0) choose_result(state, ml::best_outcome(analysis.results));
  }
  if (!outcome) return;
  const TrainingRequest& request = analysis.last_request;
  analysis.results = std::move(outcome->results);
  if (!outcome->model_path.empty()) {
    analysis.model_path = outcome->model_path;
    analysis.model_classifier = request.classifier;
    analysis.model = outcome->model;
  }
  // Every result is a file: the evaluation beside the model.
  if (!outcome->model_path.empty() && !analysis.results.empty() && analysis.results[0].result) {
    try {
      fs::path path(outcome->model_path);
      path.replace_extension(".evaluation.json");
      write_json_file(path.string(), ml::to_json(*analysis.results[0].result, true), "evaluation");
    } catch (const Error& error) {
      state.error = error.what();
    }
  }
  show_table(state, outcome->dataset, outcome->pipeline);
  const int best = ml::best_outcome(analysis.results);
  choose_result(state, best);
  state.notice = best < 0
                     ? "no classifier fitted the data"
                     : "trained: best " + analysis.results[static_cast<size_t>(best)].classifier;
}

}  // namespace

bool start_training(WorkbenchState& state, const std::string& classifier) {
  AnalysisState& analysis = state.analysis;
  if (find_job(state, "training"))
    return fail(state, "a training run is going on: wait or cancel it");
  if (!state.document) return fail(state, "open a recording of the skin to train for");
  if (classifier != "all") {
    try {
      ml::make_classifier(classifier);
    } catch (const Error& error) {
      return fail(state, error.what());
    }
  }
  TrainingRequest request;
  request.database = label_database(state);
  request.folder = fs::path(request.database).parent_path().string();
  request.layout = state.document->layout.id;
  request.segments = analysis.segments;
  request.pipeline =
      analysis.pipeline.empty() ? default_pipeline(request.layout) : analysis.pipeline;
  request.pipeline_params = analysis.pipeline_params.data();
  // Typed parameters are checked here, so a wrong key is named at once, not after the features.
  if (!request.pipeline_params.empty()) {
    try {
      effective_pipeline_parameters(request.pipeline, request.pipeline_params,
                                    "features parameters");
    } catch (const Error& error) {
      return fail(state, error.what());
    }
  }
  request.classifier = classifier;
  request.protocol = analysis.protocol.data();
  // One classifier: also fitted on every row and saved, so it can predict (Predict).
  if (classifier != "all") {
    const fs::path models = fs::path(request.folder) / "models";
    std::error_code error;
    fs::create_directories(models, error);
    std::string name = classifier.substr(0, classifier.find(':'));
    if (!error) request.save_model = (models / (request.layout + "-" + name + ".json")).string();
  }
  // Leave a core to the window, so frames keep their time while training.
  request.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1);
  try {
    ml::Protocol::parse(request.protocol);
  } catch (const Error& error) {
    return fail(state, error.what());
  }
  request.so_far = std::make_shared<TrainingSoFar>();
  analysis.so_far = request.so_far;
  analysis.so_far_shown = 0;
  analysis.last_request = request;
  adopt_job<TrainingOutcome>(state, "training", start_training_job(request), apply_training,
                             JobExtras{show_results_so_far, true});
  state.error.clear();
  state.notice = "training " + classifier + " on " + request.layout + " recordings";
  return true;
}

const ml::EvaluationResult* current_evaluation(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  if (analysis.current < 0 || analysis.current >= static_cast<int>(analysis.results.size()))
    return nullptr;
  const auto& result = analysis.results[static_cast<size_t>(analysis.current)].result;
  return result ? &*result : nullptr;
}

void choose_result(WorkbenchState& state, int index) {
  AnalysisState& analysis = state.analysis;
  analysis.current = index;
  // The scatter and the SOM belong to the table, not to the result: only the clicked
  // cell and the rings (drawn from the current result) change.
  analysis.cell_true = analysis.cell_predicted = -1;
  analysis.cell_rows.clear();
  analysis.cell_selected = 0;
  analysis.list_active = false;
  if (current_evaluation(state)) analysis.tab_request = "confusion";
  // The classifier box names the row shown, so Run and Predict act on what the views show.
  if (index >= 0 && index < static_cast<int>(analysis.results.size())) {
    const std::string& name = analysis.results[static_cast<size_t>(index)].classifier;
    analysis.classifier.fill('\0');
    name.copy(analysis.classifier.data(), analysis.classifier.size() - 1);
  }
}

namespace {

// The classifier Predict uses: the results row the views show, else the classifier box.
std::string classifier_to_predict(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  if (analysis.current >= 0 && analysis.current < static_cast<int>(analysis.results.size()) &&
      analysis.results[static_cast<size_t>(analysis.current)].result)
    return analysis.results[static_cast<size_t>(analysis.current)].classifier;
  return analysis.classifier.data();
}

// Where a model of `classifier` for the training run's skin is saved: the models/ folder of the
// label store's workspace, as a single run saves it.
std::string model_file_for(const TrainingRequest& request, const std::string& classifier) {
  const fs::path models = fs::path(request.folder) / "models";
  std::error_code error;
  fs::create_directories(models, error);
  if (error) throw Error(models.string(), "cannot make the models folder: " + error.message());
  return (models / (request.layout + "-" + classifier.substr(0, classifier.find(':')) + ".json"))
      .string();
}

}  // namespace

bool can_predict(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  if (!state.document) return false;
  const std::string classifier = classifier_to_predict(state);
  return (!analysis.model_path.empty() && analysis.model_classifier == classifier) ||
         (analysis.dataset && !classifier.empty() && classifier != "all" &&
          analysis.last_request.layout == state.document->layout.id);
}

namespace {

// The prediction's end: the model it fitted kept, the recording's lanes read again.
void apply_finished_prediction(WorkbenchState& state, Job<AnalysisState::PredictionsMade>& job) {
  std::optional<AnalysisState::PredictionsMade> made = job_result(state, job);
  if (!made) return;
  state.analysis.model_path = made->model_path;
  state.analysis.model_classifier = made->classifier;
  state.analysis.model = made->fitted;
  if (!state.document || state.document->path != made->document) return;
  state.document->reload_labels();
  state.error.clear();
  state.notice =
      std::to_string(made->predicted) + " predictions by " + made->model + " (U: the least sure)";
}

}  // namespace

bool predict_open_recording(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!state.document) return fail(state, "open a recording to predict");
  if (!can_predict(state))
    return fail(state, "Run one classifier or Train all first: a model predicts");
  Document& document = *state.document;
  // The recording's segmenter suggestions, else its ground truth, as `tactile predict`.
  std::vector<Label> segments = segments_to_predict(document.labels);
  if (segments.empty()) return fail(state, "no segments to predict: run a segmenter (Labels menu)");
  const size_t count = segments.size();
  const std::string classifier = classifier_to_predict(state);
  try {
    // The row shown has no saved model yet (a Train all row): the job fits it on every row of
    // the table first, as a single run would have, and saves it beside the others.
    const bool fit = analysis.model_path.empty() || analysis.model_classifier != classifier;
    const std::string model_path =
        fit ? model_file_for(analysis.last_request, classifier) : analysis.model_path;
    std::shared_ptr<const Dataset> table = fit ? analysis.dataset : nullptr;
    std::shared_ptr<const SavedModel> fitted = fit ? nullptr : analysis.model;
    const std::string database = document.label_store().path();
    // On a worker, from reading the model to storing the answers (2.6-3.3 s for 40 minutes of
    // a 64-taxel strip when it ran in one frame). A second Predict replaces a run still going.
    start_job<AnalysisState::PredictionsMade>(
        state, "predict", "predict",
        [open = source_for_job(document), layout = document.layout, path = document.path,
         model_path, table, fitted, classifier, request = analysis.last_request,
         segments = std::move(segments), database, recording = document.recording_id(),
         annotator = state.labelling.annotator](JobProgress& progress) {
          // The model fitted in this session, else fitted now (and saved), else its file.
          std::shared_ptr<const SavedModel> model = fitted;
          if (table) {
            progress.report(0.0, "fitting " + classifier + " on every row");
            auto made = std::make_shared<SavedModel>(fit_model(
                *table, classifier, request.seed, request.pipeline, request.pipeline_params));
            write_json_file(model_path, model_document(*made), "model");
            model = std::move(made);
          }
          if (!model)
            model = std::make_shared<SavedModel>(
                read_model_file(model_path, progress.steps("reading the model", 0.0, 0.2)));
          // A pipeline that reads only the segments' samples (Robovie's correlations) reads
          // their windows from the file; the recording is never held whole.
          const Predictions predictions = predict_segments(
              *model, *open(), layout, segments,
              progress.steps("features of " + std::to_string(segments.size()) + " segments", 0.2,
                             1.0));
          LabelStore store(database, LabelStore::OpenMode::kExisting);
          const LabelEdit edit = prediction_edit(store, recording, predictions.labels);
          progress.check();  // the last place to stop: what follows is one transaction
          // The model's lane replaced as one command of the operator's: Ctrl+Z takes it back.
          store.apply(edit, annotator);
          return AnalysisState::PredictionsMade{path,
                                                fs::path(model_path).stem().string(),
                                                predictions.labels.size(),
                                                model_path,
                                                classifier,
                                                model};
        },
        apply_finished_prediction);
  } catch (const std::exception& error) {
    return fail(state, std::string("predict: ") + error.what());
  }
  state.error.clear();
  state.notice = "predicting " + std::to_string(count) + " segments...";
  return true;
}

//---- Files ----------------------------------------------------------------------------------

bool open_evaluation_file(WorkbenchState& state, const std::string& path) {
  AnalysisState& analysis = state.analysis;
  try {
    ml::TrainAllResult opened = ml::read_train_all_file(path);
    analysis.results = std::move(opened.outcomes);
    analysis.results_from = fs::path(path).filename().string();
    analysis.dataset.reset();
    analysis.som.reset();
    analysis.som_quality.reset();
    analysis.som_spread_for = nullptr;
    analysis.som_classes.clear();
    // The table it was made from, for the scatter and the SOM (relative to the result).
    if (!opened.features.empty()) {
      fs::path table(opened.features);
      if (table.is_relative() && !fs::exists(table)) table = fs::path(path).parent_path() / table;
      if (fs::exists(table))
        set_dataset(state, std::make_shared<const Dataset>(read_dataset_csv(table.string())));
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
    state.analysis.som.reset(som);
    state.analysis.som_quality.reset();
    state.analysis.som_spread_for = nullptr;
    state.analysis.som_classes = model.classes;
    state.analysis.som_for = nullptr;
    state.analysis.som_winners.clear();
    state.analysis.tab_request = "som";
  } catch (const std::exception& error) {
    return fail(state, std::string("cannot open the model: ") + error.what());
  }
  return true;
}

bool open_features_file(WorkbenchState& state, const std::string& path) {
  try {
    set_dataset(state, std::make_shared<const Dataset>(read_dataset_csv(path)));
    if (state.analysis.results.empty()) state.analysis.tab_request = "scatter";
  } catch (const std::exception& error) {
    return fail(state, std::string("cannot open the features: ") + error.what());
  }
  return true;
}

//---- From a cell to a segment ---------------------------------------------------------------

void select_cell(WorkbenchState& state, int truth, int predicted) {
  AnalysisState& analysis = state.analysis;
  analysis.cell_true = truth;
  analysis.cell_predicted = predicted;
  analysis.cell_rows.clear();
  analysis.cell_selected = 0;
  const ml::EvaluationResult* result = current_evaluation(state);
  if (!result) return;
  for (size_t k = 0; k < result->rows.size(); ++k)
    if (result->rows[k].truth == truth && result->rows[k].predicted == predicted)
      analysis.cell_rows.push_back(k);
  // The least sure first: the segments most worth a look, in a right cell as in a wrong one.
  std::stable_sort(analysis.cell_rows.begin(), analysis.cell_rows.end(), [&](size_t a, size_t b) {
    return result->rows[a].margin < result->rows[b].margin;
  });
  analysis.list_active = !analysis.cell_rows.empty();
  if (analysis.cell_rows.empty() && result->rows.empty())
    state.notice = "this result lists no rows (written without --out?)";
}

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

void land_on(WorkbenchState& state, const ml::RowPrediction& row) {
  state.analysis.landed = row;
  state.analysis.landing_pending = true;
  if (!state.document || state.document->recording_id() != row.recording) {
    const std::string file = recording_file(state, row.recording);
    if (file.empty()) {
      state.error = "no file for recording " + row.recording + " in the workspace";
      state.analysis.landed.reset();
      return;
    }
    state.open_request = file;
  }
}

void carry_out_landing(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.landing_pending || !analysis.landed || !state.document) return;
  const ml::RowPrediction& row = *analysis.landed;
  if (state.document->recording_id() != row.recording) return;  // still opening
  analysis.landing_pending = false;
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
  analysis.replay_until = row.t1;
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
  if (state.analysis.landed)
    for (int64_t k = 0; k < count; ++k)
      if (result->rows[static_cast<size_t>(k)].row == state.analysis.landed->row &&
          result->rows[static_cast<size_t>(k)].fold == state.analysis.landed->fold)
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

std::vector<RowOutcome> row_outcomes(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  std::vector<RowOutcome> outcomes(analysis.dataset ? static_cast<size_t>(analysis.dataset->rows())
                                                    : 0);
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

namespace {

// The ends of the derived views' jobs, applied on the window's thread (jobs.h).
void apply_som_fit(WorkbenchState& state, Job<AnalysisState::SomFit>& job) {
  AnalysisState& analysis = state.analysis;
  if (job.status() == JobStatus::kCancelled) analysis.som_held = true;
  std::optional<AnalysisState::SomFit> fit = job_result(state, job);
  if (!fit) return;
  analysis.som = std::move(fit->som);
  analysis.som_spread_for = nullptr;
  analysis.som_classes = std::move(fit->classes);
  analysis.som_winners = std::move(fit->winners);
  analysis.som_quality = fit->quality;
  analysis.som_for = analysis.dataset ? &*analysis.dataset : nullptr;
}

void apply_scatter_fit(WorkbenchState& state, Job<AnalysisState::ScatterFit>& job) {
  AnalysisState& analysis = state.analysis;
  if (job.status() == JobStatus::kCancelled) analysis.scatter_held = true;
  std::optional<AnalysisState::ScatterFit> fit = job_result(state, job);
  if (!fit) return;
  analysis.scatter = std::move(fit->scatter);
  analysis.scatter_explained = fit->explained;
}

void apply_map_made(WorkbenchState& state, Job<AnalysisState::MapMade>& job) {
  AnalysisState& analysis = state.analysis;
  std::optional<AnalysisState::MapMade> made = job_result(state, job);
  if (made && made->key == analysis.map_for) {
    analysis.map = std::move(made->map);
    analysis.map_layout.reset();
  }
}

}  // namespace

bool ensure_som(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  // The rows' winners are for this table (none without a table).
  const void* table = analysis.dataset ? &*analysis.dataset : nullptr;
  poll_jobs(state);
  if (analysis.som && analysis.som_for == table) return true;
  if (find_job(state, "som")) return false;              // fitting: the view shows its progress
  if (!analysis.som && analysis.som_held) return false;  // cancelled: the view offers it again
  try {
    if (!analysis.som) {
      if (!analysis.dataset) return false;
      // The map of the table: the flux paper's 7 x 7 SOM fitted on every row, on a worker
      // (18-20 s on a 454 x 1692 table), with its rows' winners.
      start_job<AnalysisState::SomFit>(
          state, "som", "SOM map",
          [table = analysis.dataset](JobProgress& progress) {
            ml::TableSom fit = ml::som_of(*table, [&progress](double fraction) {
              progress.report(fraction, "fitting the map");
              progress.check();
            });
            return AnalysisState::SomFit{std::move(fit.som), std::move(fit.classes),
                                         std::move(fit.winners), fit.quality};
          },
          apply_som_fit);
      return false;
    }
    // A loaded map: the winners of this table's rows (a pass over the rows, no fit).
    analysis.som_winners = analysis.dataset
                               ? ml::som_winners(*analysis.som, analysis.dataset->features)
                               : std::vector<int>{};
    analysis.som_for = table;
  } catch (const std::exception& error) {
    analysis.som.reset();
    analysis.som_quality.reset();
    analysis.som_spread_for = nullptr;
    return fail(state, std::string("SOM map: ") + error.what());
  }
  return true;
}

bool ensure_scatter(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.dataset) return false;
  poll_jobs(state);
  if (find_job(state, "scatter")) return false;  // computing: the view shows its progress
  if (analysis.scatter_held) return false;       // cancelled: the view offers it again
  if (analysis.scatter_for == &*analysis.dataset) return analysis.scatter.rows() > 0;
  analysis.scatter_for = &*analysis.dataset;
  analysis.scatter.resize(0, 2);
  // The table on its first two principal components, on a worker (7.8 s at 454 x 1692).
  start_job<AnalysisState::ScatterFit>(
      state, "scatter", "scatter",
      [table = analysis.dataset](JobProgress& progress) {
        ml::TableScatter scatter =
            ml::scatter_of(table->features, progress.steps("principal components of " +
                                                           std::to_string(table->rows()) + " x " +
                                                           std::to_string(table->features.cols())));
        return AnalysisState::ScatterFit{std::move(scatter.points), scatter.explained};
      },
      apply_scatter_fit);
  return false;
}

bool ensure_somatosensory(WorkbenchState& state) {
  if (!state.document) return false;
  AnalysisState& analysis = state.analysis;
  const SkinLayout& layout = state.document->layout;
  const std::string modality =
      layout.modalities.empty() ? "" : layout.modalities[static_cast<size_t>(state.modality)];
  const std::string key =
      (analysis.somatosensory_corpus ? "corpus:" + state.workspace + ":" + layout.id
                                     : state.document->path) +
      "#" + modality;
  if (analysis.map_for == key) return analysis.map.has_value();
  analysis.map_for = key;
  analysis.map.reset();
  analysis.map_layout.reset();
  // On a worker, cache and all (8.3 s for 30 min of Robovie's 274 channels the first time); a
  // map asked for meanwhile (another modality, the corpus) replaces it.
  if (analysis.somatosensory_corpus) {
    std::vector<std::string> files;
    for (const std::string& file : state.workspace_files)
      if (!state.damaged.count(file)) files.push_back(file);
    start_job<AnalysisState::MapMade>(
        state, "somatosensory", "somatosensory map (all recordings)",
        [key, files, layout, modality, index = state.modality,
         cache = somatosensory_corpus_cache_path(state.workspace, layout.id, modality)](
            JobProgress& progress) {
          // Every recording of this skin in the workspace (the others are left out).
          std::vector<std::string> same_skin;
          for (const std::string& file : files) {
            progress.check();
            try {
              if (RecordingFile(file).layout_id() == layout.id) same_skin.push_back(file);
            } catch (const Error&) {
            }
          }
          AnalysisState::MapMade made{key, {}};
          if (std::optional<SomatosensoryMap> cached =
                  read_somatosensory_corpus_cache(cache, same_skin)) {
            made.map = std::move(*cached);
            return made;
          }
          made.map = somatosensory_corpus_map(
              same_skin, layout, index,
              progress.steps("correlations over " + std::to_string(same_skin.size()) +
                             " recordings"));
          write_somatosensory_corpus_cache(cache, same_skin, made.map);
          return made;
        },
        apply_map_made);
  } else if (!dynamic_cast<const FileSampleSource*>(&state.document->samples())) {
    // A live stream: over what has arrived so far, copied now; no cache (nothing on disk yet).
    start_job<AnalysisState::MapMade>(
        state, "somatosensory", "somatosensory map",
        [key, read = recording_for_job(*state.document, 0.0, 0.0), layout,
         index = state.modality](JobProgress& progress) {
          const Recording recording = read(progress);
          return AnalysisState::MapMade{
              key, somatosensory_map(MemorySampleSource(recording, recording.streams.front()),
                                     layout, index, progress.steps("correlations of the taxels"))};
        },
        apply_map_made);
  } else {
    start_job<AnalysisState::MapMade>(
        state, "somatosensory", "somatosensory map",
        [key, path = state.document->path, stream = state.document->samples().info().stream, layout,
         modality, index = state.modality](JobProgress& progress) {
          AnalysisState::MapMade made{key, {}};
          if (std::optional<SomatosensoryMap> cached = read_somatosensory_cache(path, modality)) {
            made.map = std::move(*cached);
            return made;
          }
          FileSourceOptions options;
          options.stream = stream;
          options.cache_bytes = int64_t{8} << 20;
          options.damaged_chunks_as_gaps = true;
          progress.report(0.0, "opening the recording");
          const FileSampleSource source(path, options);
          made.map = somatosensory_map(source, layout, index,
                                       progress.steps("correlations of the taxels"));
          write_somatosensory_cache(path, made.map);
          return made;
        },
        apply_map_made);
  }
  return false;
}

}  // namespace tactile

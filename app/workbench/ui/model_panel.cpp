#include "model_panel.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "jobs.h"
#include "labelling.h"
#include "results.h"
#include "tactile/error.h"
#include "tactile/labels/predict.h"
#include "tactile/labelstore/label_store.h"
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

}  // namespace

//---- Training -------------------------------------------------------------------------------

namespace {

// The table the results are about, once: the same table again keeps the views' maps.
void show_table(WorkbenchState& state, std::shared_ptr<const Dataset> table,
                const std::string& pipeline) {
  AnalysisState& analysis = state.analysis;
  if (!table || analysis.results.dataset == table) return;
  analysis.results.from = analysis.panel.last_request.layout + ", " + pipeline + " features, " +
                          std::to_string(table->rows()) + " segments";
  set_results_table(state, std::move(table));
}

// The running job's results that arrived since the last frame; the first becomes current,
// without leaving the model tab, which shows the run's progress and Cancel.
void show_results_so_far(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  if (!analysis.results.so_far || analysis.results.so_far->count() == analysis.results.so_far_shown)
    return;
  show_table(state, analysis.results.so_far->table(), analysis.results.so_far->pipeline());
  const bool first = analysis.results.so_far_shown == 0;
  analysis.results.rows = analysis.results.so_far->outcomes();
  analysis.results.so_far_shown = analysis.results.rows.size();
  if (!first) return;
  const std::string tab = analysis.tab_request;
  choose_result(state, ml::best_outcome(analysis.results.rows));
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
    analysis.results.so_far.reset();
    return;
  }
  std::optional<TrainingOutcome> outcome = job_result(state, job);
  const std::shared_ptr<TrainingSoFar> so_far = std::move(analysis.results.so_far);
  if (status == JobStatus::kCancelled) {
    // What finished before Cancel stays: each result is whole.
    const size_t kept = so_far ? so_far->count() : 0;
    state.notice = kept == 0 ? "training cancelled"
                             : "training cancelled: kept the " + std::to_string(kept) +
                                   " finished result" + (kept == 1 ? "" : "s");
    if (kept > 0) choose_result(state, ml::best_outcome(analysis.results.rows));
  }
  if (!outcome) return;
  const TrainingRequest& request = analysis.panel.last_request;
  analysis.results.rows = std::move(outcome->results);
  if (!outcome->model_path.empty()) {
    analysis.panel.model_path = outcome->model_path;
    analysis.panel.model_classifier = request.classifier;
    analysis.panel.model = outcome->model;
  }
  // Every result is a file: the evaluation beside the model.
  if (!outcome->model_path.empty() && !analysis.results.rows.empty() &&
      analysis.results.rows[0].result) {
    try {
      fs::path path(outcome->model_path);
      path.replace_extension(".evaluation.json");
      write_json_file(path.string(), ml::to_json(*analysis.results.rows[0].result, true),
                      "evaluation");
    } catch (const Error& error) {
      state.error = error.what();
    }
  }
  show_table(state, outcome->dataset, outcome->pipeline);
  const int best = ml::best_outcome(analysis.results.rows);
  choose_result(state, best);
  state.notice =
      best < 0 ? "no classifier fitted the data"
               : "trained: best " + analysis.results.rows[static_cast<size_t>(best)].classifier;
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
  request.segments = analysis.panel.segments;
  request.pipeline =
      analysis.panel.pipeline.empty() ? default_pipeline(request.layout) : analysis.panel.pipeline;
  request.pipeline_params = analysis.panel.pipeline_params.data();
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
  request.protocol = analysis.panel.protocol.data();
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
  analysis.results.so_far = request.so_far;
  analysis.results.so_far_shown = 0;
  analysis.panel.last_request = request;
  adopt_job<TrainingOutcome>(state, "training", start_training_job(request), apply_training,
                             JobExtras{show_results_so_far, true});
  state.error.clear();
  state.notice = "training " + classifier + " on " + request.layout + " recordings";
  return true;
}

namespace {

// The classifier Predict uses: the results row the views show, else the classifier box.
std::string classifier_to_predict(const WorkbenchState& state) {
  const AnalysisState& analysis = state.analysis;
  if (analysis.results.current >= 0 &&
      analysis.results.current < static_cast<int>(analysis.results.rows.size()) &&
      analysis.results.rows[static_cast<size_t>(analysis.results.current)].result)
    return analysis.results.rows[static_cast<size_t>(analysis.results.current)].classifier;
  return analysis.panel.classifier.data();
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
  return (!analysis.panel.model_path.empty() && analysis.panel.model_classifier == classifier) ||
         (analysis.results.dataset && !classifier.empty() && classifier != "all" &&
          analysis.panel.last_request.layout == state.document->layout.id);
}

namespace {

// The prediction's end: the model it fitted kept, the recording's lanes read again.
void apply_finished_prediction(WorkbenchState& state, Job<ModelPanelState::PredictionsMade>& job) {
  std::optional<ModelPanelState::PredictionsMade> made = job_result(state, job);
  if (!made) return;
  state.analysis.panel.model_path = made->model_path;
  state.analysis.panel.model_classifier = made->classifier;
  state.analysis.panel.model = made->fitted;
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
    const bool fit =
        analysis.panel.model_path.empty() || analysis.panel.model_classifier != classifier;
    const std::string model_path =
        fit ? model_file_for(analysis.panel.last_request, classifier) : analysis.panel.model_path;
    std::shared_ptr<const Dataset> table = fit ? analysis.results.dataset : nullptr;
    std::shared_ptr<const SavedModel> fitted = fit ? nullptr : analysis.panel.model;
    const std::string database = document.label_store().path();
    // On a worker, from reading the model to storing the answers (2.6-3.3 s for 40 minutes of
    // a 64-taxel strip when it ran in one frame). A second Predict replaces a run still going.
    start_job<ModelPanelState::PredictionsMade>(
        state, "predict", "predict",
        [open = source_for_job(document), layout = document.layout, path = document.path,
         model_path, table, fitted, classifier, request = analysis.panel.last_request,
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
          return ModelPanelState::PredictionsMade{path,
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

}  // namespace tactile

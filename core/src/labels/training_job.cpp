// The training run: features, then evaluation, as a job on a worker thread.
#include "tactile/labels/training_job.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/labels/predict.h"
#include "tactile/parameters.h"

namespace tactile {

namespace {
constexpr double kFeatureShare = 0.3;  // of the progress bar
}

void TrainingSoFar::set_table(std::shared_ptr<const Dataset> table, std::string pipeline) {
  const std::lock_guard<std::mutex> lock(mutex_);
  table_ = std::move(table);
  pipeline_ = std::move(pipeline);
}

void TrainingSoFar::add(ml::PresetOutcome outcome) {
  const std::lock_guard<std::mutex> lock(mutex_);
  outcomes_.push_back(std::move(outcome));
}

size_t TrainingSoFar::count() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return outcomes_.size();
}

std::shared_ptr<const Dataset> TrainingSoFar::table() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return table_;
}

std::string TrainingSoFar::pipeline() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return pipeline_;
}

std::vector<ml::PresetOutcome> TrainingSoFar::outcomes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return outcomes_;
}

std::unique_ptr<TrainingJob> start_training_job(TrainingRequest request) {
  return std::make_unique<TrainingJob>("training",
                                       [request = std::move(request)](JobProgress& progress) {
                                         return run_training(request, progress);
                                       });
}

TrainingOutcome run_training(const TrainingRequest& request, JobProgress& progress) {
  // The corpus and the evaluation stop at the cancel flag by throwing an error of their own.
  try {
    TrainingOutcome outcome;
    progress.report(0.0, "reading labels");
    const std::vector<CorpusRecording> corpus =
        corpus_from_store({request.database, request.segments, request.folder, request.layout});
    if (request.pipeline.empty()) throw Error("training", "names no feature pipeline");
    outcome.pipeline = request.pipeline;
    const auto extractor = make_feature_extractor(
        outcome.pipeline, Parameters::parse(request.pipeline_params, "pipeline parameters"));
    progress.report(0.0, "features (" + outcome.pipeline + ")");
    CorpusOptions corpus_options;
    corpus_options.threads = request.threads;
    corpus_options.cancel = progress.flag();
    corpus_options.progress = [&progress](int64_t done, int64_t total) {
      progress.report(kFeatureShare * static_cast<double>(done) / static_cast<double>(total));
    };
    CorpusDataset table = extract_corpus(*extractor, corpus, corpus_options);
    if (table.dataset.rows() == 0)
      throw Error("features",
                  "no rows: all " + std::to_string(table.segments) + " segments were skipped");
    outcome.dataset = std::make_shared<const Dataset>(std::move(table.dataset));
    if (request.so_far) request.so_far->set_table(outcome.dataset, outcome.pipeline);

    const ml::Protocol protocol = ml::Protocol::parse(request.protocol);
    ml::EvaluationControl control;
    control.threads = request.threads;
    control.cancel = progress.flag();
    control.scores = true;
    control.progress = [&progress](int done, int total) {
      progress.report(kFeatureShare + (1.0 - kFeatureShare) * done / std::max(1, total));
    };
    if (request.classifier == "all") {
      outcome.results = ml::evaluate_all(
          *outcome.dataset, protocol, request.seed, control,
          [&](const ml::PresetOutcome& preset, int index, int total) {
            if (request.so_far) request.so_far->add(preset);
            progress.report(progress.fraction(), "trained " + preset.classifier + " (" +
                                                     std::to_string(index + 1) + "/" +
                                                     std::to_string(total) + ")");
          });
    } else {
      progress.report(kFeatureShare, "evaluating " + request.classifier);
      ml::PresetOutcome one;
      one.classifier = request.classifier;
      one.result =
          ml::evaluate(*outcome.dataset, request.classifier, protocol, request.seed, control);
      if (request.so_far) request.so_far->add(one);
      outcome.results.push_back(std::move(one));
      if (!request.save_model.empty()) {
        progress.report(progress.fraction(), "fitting the model on every row");
        auto model = std::make_shared<SavedModel>(fit_model(*outcome.dataset, request.classifier,
                                                            request.seed, outcome.pipeline,
                                                            request.pipeline_params));
        write_json_file(request.save_model, model_document(*model), "model");
        outcome.model_path = request.save_model;
        outcome.model = std::move(model);
      }
    }
    progress.report(1.0, "done");
    return outcome;
  } catch (const Error&) {
    if (progress.cancelled()) throw JobCancelled{};
    throw;
  }
}

}  // namespace tactile

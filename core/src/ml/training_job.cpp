// TrainingJob: features, then evaluation, on one worker thread.
#include "tactile/ml/training_job.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/labels/predict.h"
#include "tactile/parameters.h"

namespace tactile::ml {

namespace {
constexpr double kFeatureShare = 0.3;  // of the progress bar
[[maybe_unused]] constexpr int kWorkerNice = 19;
}

TrainingJob::TrainingJob(TrainingRequest request) : request_(std::move(request)) {
  worker_ = std::thread([this] { run(); });
}

TrainingJob::~TrainingJob() {
  cancel();
  if (worker_.joinable()) worker_.join();
}

std::string TrainingJob::stage() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return stage_;
}

std::string TrainingJob::error() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

std::unique_ptr<TrainingOutcome> TrainingJob::take() {
  if (status_.load() != Status::kDone) return nullptr;
  const std::lock_guard<std::mutex> lock(mutex_);
  return std::move(outcome_);
}

void TrainingJob::wait() {
  if (worker_.joinable()) worker_.join();
}

void TrainingJob::run() {
#if defined(__linux__)
  // Below the window's thread: the frames keep their time while training takes the rest
  // of the machine (threads this one starts inherit the priority).
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kWorkerNice);
#endif
  const auto set_stage = [this](std::string text) {
    const std::lock_guard<std::mutex> lock(mutex_);
    stage_ = std::move(text);
  };
  try {
    auto outcome = std::make_unique<TrainingOutcome>();
    set_stage("reading labels");
    const std::vector<CorpusRecording> corpus = corpus_from_store(
        {request_.database, request_.segments, request_.folder, request_.layout});
    outcome->pipeline = request_.pipeline.empty()
                            ? skin_pipeline(request_.layout.empty() ? "" : request_.layout)
                            : request_.pipeline;
    const auto extractor = make_feature_extractor(
        outcome->pipeline, Parameters::parse(request_.pipeline_params, "pipeline parameters"));
    set_stage("features (" + outcome->pipeline + ")");
    CorpusOptions corpus_options;
    corpus_options.threads = request_.threads;
    corpus_options.cancel = &cancel_;
    corpus_options.progress = [this](int64_t done, int64_t total) {
      progress_.store(kFeatureShare * static_cast<double>(done) / static_cast<double>(total));
    };
    CorpusDataset table = extract_corpus(*extractor, corpus, corpus_options);
    if (table.dataset.rows() == 0)
      throw Error("features", "no rows: all " + std::to_string(table.segments) +
                                  " segments were skipped");
    outcome->dataset = std::move(table.dataset);

    const Protocol protocol = Protocol::parse(request_.protocol);
    EvaluationControl control;
    control.threads = request_.threads;
    control.cancel = &cancel_;
    control.scores = true;
    control.progress = [this](int done, int total) {
      progress_.store(kFeatureShare + (1.0 - kFeatureShare) * done / std::max(1, total));
    };
    if (request_.classifier == "all") {
      outcome->results = evaluate_all(
          outcome->dataset, protocol, request_.seed, control,
          [&](const PresetOutcome& preset, int index, int total) {
            set_stage("trained " + preset.classifier + " (" + std::to_string(index + 1) + "/" +
                      std::to_string(total) + ")");
          });
    } else {
      set_stage("evaluating " + request_.classifier);
      PresetOutcome one;
      one.classifier = request_.classifier;
      one.result = evaluate(outcome->dataset, request_.classifier, protocol, request_.seed, control);
      outcome->results.push_back(std::move(one));
      if (!request_.save_model.empty()) {
        set_stage("fitting the model on every row");
        write_json_file(request_.save_model,
                        fit_model_document(outcome->dataset, request_.classifier, request_.seed,
                                           outcome->pipeline, request_.pipeline_params),
                        "model");
        outcome->model_path = request_.save_model;
      }
    }
    progress_.store(1.0);
    set_stage("done");
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      outcome_ = std::move(outcome);
    }
    status_.store(Status::kDone);
  } catch (const std::exception& failure) {
    if (cancel_.load()) {
      set_stage("cancelled");
      status_.store(Status::kCancelled);
      return;
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      error_ = failure.what();
    }
    status_.store(Status::kFailed);
  }
}

}  // namespace tactile::ml

// `tactile predict --model MODEL.json RECORDING.h5|FOLDER... --labels DB [--segments S]`
// Applies a saved model (`evaluate --save-model`) to the segments of new recordings and
// stores its answers as labels of source `model` (the workbench's prediction lane), each
// with its class, score (confidence) and margin. A recording's earlier predictions are
// replaced. Segments: `--segments METHOD` runs that segmenter; `--segments source:NAME`
// takes the recording's labels of that source; by default the recording's segmenter
// labels, else its ground truth.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/labels/predict.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/segment/segmenter.h"

namespace tactile::cli {

namespace {

struct PredictOptions {
  std::vector<std::string> inputs;
  std::string model, database, segments, params;
};

std::vector<Label> labels_of(const LabelStore& store, const std::string& recording,
                             LabelSource source) {
  LabelFilter filter;
  filter.recording = recording;
  filter.source = source;
  return store.list(filter);
}

// The segments to classify, as the options ask.
std::vector<Label> segments_of(const PredictOptions& options, const LabelStore& store,
                               const Recording& recording, const SkinLayout& layout) {
  if (options.segments.rfind("source:", 0) == 0) {
    LabelSource source;
    try {
      source = parse_label_source(options.segments.substr(7));
    } catch (const Error& error) {
      throw Error("--segments", error.message());
    }
    return labels_of(store, recording.id, source);
  }
  if (!options.segments.empty())
    return segment_recording(options.segments, recording, layout,
                             Parameters::parse(options.params, "--params"));
  LabelFilter of_recording;
  of_recording.recording = recording.id;
  return segments_to_predict(store.list(of_recording));
}

void run_predict(const PredictOptions& options) {
  if (!options.params.empty() &&
      (options.segments.empty() || options.segments.rfind("source:", 0) == 0))
    throw Error("--params", "belongs to a segmenter: give --segments METHOD too");
  const SavedModel model = read_model_file(options.model);
  if (model.pipeline.empty())
    throw Error(options.model,
                "the model does not name its feature pipeline (save it again with "
                "`evaluate --save-model` and --pipeline)");
  const std::vector<std::string> files = recording_files(options.inputs);
  LabelStore store(options.database);
  int64_t total = 0;
  for (const std::string& file : files) {
    const Recording recording = read_recording(file);
    const SkinLayout layout = load_layout(recording.layout_id);
    const std::vector<Label> segments = segments_of(options, store, recording, layout);
    const Predictions predictions = predict_segments(model, recording, layout, segments);
    for (const SkippedSegment& skipped : predictions.skipped)
      std::cerr << "skipped: " << skipped.recording << " " << skipped.t0 << "-" << skipped.t1
                << " s: " << skipped.reason << "\n";
    // The model's lane replaced, in one transaction (labels/predict.h, as the workbench's).
    size_t removed = 0;
    store.apply(prediction_edit(store, recording.id, predictions.labels, &removed),
                kModelAnnotator);
    total += static_cast<int64_t>(predictions.labels.size());
    std::cout << recording.id << ": " << predictions.labels.size() << " predictions of "
              << segments.size() << " segments";
    if (removed > 0) std::cout << " (replaced " << removed << ")";
    std::cout << "\n";
  }
  std::cout << total << " predictions from " << files.size()
            << (files.size() == 1 ? " recording" : " recordings") << " stored in "
            << options.database << " (source model)\n";
}

}  // namespace

void register_predict(CLI::App& app) {
  auto options = std::make_shared<PredictOptions>();
  CLI::App* command = app.add_subcommand(
      "predict", "Apply a saved model to recordings; store its answers as labels (source model)");
  command->add_option("RECORDINGS", options->inputs, "Recording files (.h5) or folders of them")
      ->required();
  command->add_option("--model", options->model, "Model JSON (from `evaluate --save-model`)")
      ->required();
  command->add_option("--labels", options->database, "Label database (SQLite; created if missing)")
      ->required();
  command->add_option("--segments", options->segments,
                      "METHOD: run this segmenter; source:NAME: the recording's labels of that "
                      "source (default: its segmenter labels, else its ground truth)");
  command->add_option("--params", options->params, "Segmenter parameters as key=value,...");
  command->callback([options] { run_predict(*options); });
}

}  // namespace tactile::cli

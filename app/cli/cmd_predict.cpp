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
#include "tactile/labels/predict.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/segment/segmenter.h"

namespace tactile::cli {

namespace {

struct PredictOptions {
  std::vector<std::string> inputs;
  std::string model, database, segments, params;
  ShardArgs shard;
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

// One recording predicted: what a shard keeps in its part and the store is given.
struct PredictedRecording {
  std::string recording;  // its id
  size_t segments = 0;    // segments classified
  Predictions predictions;
};

void print_skipped(const Predictions& predictions) {
  for (const SkippedSegment& skipped : predictions.skipped)
    std::cerr << "skipped: " << skipped.recording << " " << skipped.t0 << "-" << skipped.t1
              << " s: " << skipped.reason << "\n";
}

PredictedRecording predict_file(const PredictOptions& options, const SavedModel& model,
                                const LabelStore& store, const std::string& file) {
  const Recording recording = read_recording(file);
  const SkinLayout layout = load_layout(recording.layout_id);
  const std::vector<Label> segments = segments_of(options, store, recording, layout);
  PredictedRecording predicted{recording.id, segments.size(),
                               predict_segments(model, recording, layout, segments)};
  print_skipped(predicted.predictions);
  return predicted;
}

// The model's lane of one recording replaced, in one transaction (labels/predict.h, as the
// workbench's), and said so; returns how many predictions it stored.
size_t store_predictions(LabelStore& store, const PredictedRecording& predicted) {
  size_t removed = 0;
  store.apply(prediction_edit(store, predicted.recording, predicted.predictions.labels, &removed),
              kModelAnnotator);
  std::cout << predicted.recording << ": " << predicted.predictions.labels.size()
            << " predictions of " << predicted.segments << " segments";
  if (removed > 0) std::cout << " (replaced " << removed << ")";
  std::cout << "\n";
  return predicted.predictions.labels.size();
}

void print_predict_total(int64_t total, size_t files, const std::string& database) {
  std::cout << total << " predictions from " << files << (files == 1 ? " recording" : " recordings")
            << " stored in " << database << " (source model)\n";
}

nlohmann::json predicted_item(size_t index, const PredictedRecording& predicted) {
  nlohmann::json labels = nlohmann::json::array(), skipped = nlohmann::json::array();
  for (const Label& label : predicted.predictions.labels) labels.push_back(label_json(label));
  for (const SkippedSegment& skip : predicted.predictions.skipped)
    skipped.push_back({{"recording", skip.recording},
                       {"segment_id", skip.segment_id},
                       {"t0", skip.t0},
                       {"t1", skip.t1},
                       {"reason", skip.reason}});
  return {{"index", index},
          {"recording", predicted.recording},
          {"segments", predicted.segments},
          {"labels", labels},
          {"skipped", skipped}};
}

PredictedRecording predicted_of(const nlohmann::json& item) {
  PredictedRecording predicted;
  predicted.recording = item.at("recording").get<std::string>();
  predicted.segments = item.at("segments").get<size_t>();
  for (const nlohmann::json& label : item.at("labels"))
    predicted.predictions.labels.push_back(label_from_json(label, "merge: " + predicted.recording));
  for (const nlohmann::json& skip : item.at("skipped"))
    predicted.predictions.skipped.push_back(
        {skip.at("recording").get<std::string>(), skip.at("segment_id").get<int64_t>(),
         skip.at("t0").get<double>(), skip.at("t1").get<double>(),
         skip.at("reason").get<std::string>()});
  return predicted;
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
  const ShardPlan plan = shard_plan(options.shard, options.database + ".predict");
  if (plan.shard.active()) {  // its recordings' predictions only: the store is merge's to write
    // A shard only reads the store (its segments), and so needs it to be there.
    if (!std::filesystem::exists(options.database))
      throw Error(options.database,
                  "no such label store: a shard reads it and leaves the writing "
                  "to merge; create it first (`tactile labels import`)");
    const LabelStore store(options.database, LabelStore::OpenMode::kReadOnly);
    Part part;
    part.command = "predict";
    part.shard = plan.shard;
    part.inputs = {{"--model", file_digest(options.model)},
                   {"--segments", options.segments},
                   {"--params", options.params}};
    part.result = options.database;
    part.items = static_cast<int64_t>(files.size());
    part.plan = plan_digest(files);
    part.shared = nlohmann::json::object();
    part.done = nlohmann::json::array();
    for (size_t index : plan.shard.items_of(files.size())) {
      const PredictedRecording predicted = predict_file(options, model, store, files[index]);
      part.done.push_back(predicted_item(index, predicted));
      std::cout << predicted.recording << ": " << predicted.predictions.labels.size()
                << " predictions of " << predicted.segments << " segments\n";
    }
    write_shard_part(plan, part);
    return;
  }
  LabelStore store(options.database);
  int64_t total = 0;
  for (const std::string& file : files)
    total +=
        static_cast<int64_t>(store_predictions(store, predict_file(options, model, store, file)));
  print_predict_total(total, files.size(), options.database);
}

}  // namespace

void merge_predict(const std::vector<Part>& parts, const std::string& out) {
  LabelStore store(out);
  int64_t total = 0;
  const std::vector<nlohmann::json> items = items_in_order(parts);
  for (const nlohmann::json& item : items) {
    const PredictedRecording predicted = predicted_of(item);
    print_skipped(predicted.predictions);
    total += static_cast<int64_t>(store_predictions(store, predicted));
  }
  print_predict_total(total, items.size(), out);
}

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
  add_shard_options(command, options->shard);
  command->callback([options] { run_predict(*options); });
}

}  // namespace tactile::cli

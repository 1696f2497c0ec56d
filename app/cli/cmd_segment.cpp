// `tactile segment RECORDING.h5|FOLDER... --labels DB [--method M] [--params k=v,...] [--replace]`
// Runs a segmenter on each recording and stores its labels (source segmenter) in the
// label database, one transaction per recording. A folder stands for every .h5 file under
// it. Segments whose class the method does not know are stored with class "unknown"
// (the store needs a class); `tactile features` gives them the overlapping ground truth.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/labels/suggestions.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct SegmentOptions {
  std::vector<std::string> inputs;
  std::string database, method, params;
  bool replace = false;
  ShardArgs shard;
};

void check_segment_method(const std::string& method) {
  const std::vector<std::string> methods = segmenter_methods();
  if (!method.empty() && std::find(methods.begin(), methods.end(), method) == methods.end())
    throw Error("--method", "unknown segmenter '" + method + "' (known: " + joined(methods) + ")");
}

// One recording segmented: what a shard keeps in its part and the store is given.
struct SegmentedRecording {
  std::string recording;  // its id
  std::string method;
  std::vector<Label> segments;
};

SegmentedRecording segment_file(const SegmentOptions& options, const std::string& file) {
  const Recording recording = read_recording(file);
  const SkinLayout layout = load_layout(recording.layout_id);
  // Without --method, each recording's skin's own segmenter with its parameters.
  const auto [own_method, own_params] = default_segmenter(recording.layout_id);
  const std::string method = options.method.empty() ? own_method : options.method;
  const Parameters parameters = Parameters::parse(
      options.method.empty() && options.params.empty() ? own_params : options.params, "--params");
  return {recording.id, method, segment_recording(method, recording, layout, parameters)};
}

// Stores one recording's segments as one transaction and says so; returns how many.
size_t store_segments(LabelStore& store, const SegmentedRecording& segmented, bool replace) {
  const std::string annotator = "segmenter:" + segmented.method;
  // Suggestions an annotator rejected stay rejected; --replace removes the method's
  // earlier ones, in the same transaction (labels/suggestions.h, as the workbench's G).
  const SegmenterRun run =
      segmenter_run(store, segmented.recording, segmented.method, segmented.segments, replace);
  store.apply(run.edit, annotator);
  std::cout << segmented.recording << ": " << run.edit.add.size() << " segments ("
            << segmented.method << ")";
  if (replace) std::cout << " (replaced " << run.replaced << ")";
  if (run.rejected > 0) std::cout << " (" << run.rejected << " left out: rejected before)";
  std::cout << "\n";
  return run.edit.add.size();
}

void print_segment_total(int64_t total, size_t files, const std::string& database,
                         const std::set<std::string>& annotators) {
  std::cout << total << " segments from " << files << (files == 1 ? " recording" : " recordings")
            << " stored in " << database << " (" << joined({annotators.begin(), annotators.end()})
            << ")\n";
}

Part segment_part(const SegmentOptions& options, const Shard& shard,
                  const std::vector<std::string>& files) {
  Part part;
  part.command = "segment";
  part.shard = shard;
  part.inputs = {
      {"--method", options.method}, {"--params", options.params}, {"--replace", options.replace}};
  part.result = options.database;
  part.items = static_cast<int64_t>(files.size());
  part.plan = plan_digest(files);
  part.shared = nlohmann::json::object();
  part.done = nlohmann::json::array();
  return part;
}

void run_segment(const SegmentOptions& options) {
  check_segment_method(options.method);
  const std::vector<std::string> files = recording_files(options.inputs);
  const ShardPlan plan = shard_plan(options.shard, options.database + ".segment");
  if (plan.shard.active()) {  // its recordings' segments only: the store is merge's to write
    Part part = segment_part(options, plan.shard, files);
    for (size_t index : plan.shard.items_of(files.size())) {
      const SegmentedRecording segmented = segment_file(options, files[index]);
      nlohmann::json segments = nlohmann::json::array();
      for (const Label& label : segmented.segments) segments.push_back(label_json(label));
      part.done.push_back({{"index", index},
                           {"recording", segmented.recording},
                           {"method", segmented.method},
                           {"segments", segments}});
      std::cout << segmented.recording << ": " << segmented.segments.size() << " segments ("
                << segmented.method << ")\n";
    }
    write_shard_part(plan, part);
    return;
  }
  LabelStore store(options.database);
  std::set<std::string> annotators;
  int64_t total = 0;
  for (const std::string& file : files) {
    const SegmentedRecording segmented = segment_file(options, file);
    annotators.insert("segmenter:" + segmented.method);
    total += static_cast<int64_t>(store_segments(store, segmented, options.replace));
  }
  print_segment_total(total, files.size(), options.database, annotators);
}

}  // namespace

void merge_segment(const std::vector<Part>& parts, const std::string& out) {
  const bool replace = parts.front().inputs.at("--replace").get<bool>();
  LabelStore store(out);
  std::set<std::string> annotators;
  int64_t total = 0;
  const std::vector<nlohmann::json> items = items_in_order(parts);
  for (const nlohmann::json& item : items) {
    SegmentedRecording segmented;
    segmented.recording = item.at("recording").get<std::string>();
    segmented.method = item.at("method").get<std::string>();
    for (const nlohmann::json& label : item.at("segments"))
      segmented.segments.push_back(label_from_json(label, "merge: " + segmented.recording));
    annotators.insert("segmenter:" + segmented.method);
    total += static_cast<int64_t>(store_segments(store, segmented, replace));
  }
  print_segment_total(total, items.size(), out, annotators);
}

void register_segment(CLI::App& app) {
  auto options = std::make_shared<SegmentOptions>();
  CLI::App* command = app.add_subcommand(
      "segment", "Find touch segments in recordings and store them as labels (source segmenter)");
  command->add_option("RECORDINGS", options->inputs, "Recording files (.h5) or folders of them")
      ->required();
  command->add_option("--labels", options->database, "Label database (SQLite; created if missing)")
      ->required();
  command->add_option(
      "--method", options->method,
      "Segmenter: " + joined(segmenter_methods()) + " (default: each recording's skin's own)");
  command->add_option("--params", options->params, "Method parameters as key=value,...");
  command->add_flag("--replace", options->replace,
                    "First remove each recording's earlier labels from this method");
  add_shard_options(command, options->shard);
  command->callback([options] { run_segment(*options); });
}

}  // namespace tactile::cli

// `tactile segment RECORDING.h5|FOLDER... --labels DB [--method M] [--params k=v,...]
//  [--preset NAME] [--fit-to LANE] [--score LANE] [--replace]`
// Runs a segmenter on each recording and stores its labels (source segmenter) in the
// label database, one transaction per recording. --fit-to first chooses adaptive's parameters
// from a lane's labelled touches (segment/fit.h), prints them with their held-out scores and
// saves them as a preset; --score prints each recording's segments scored against a lane. A folder
// stands for every .h5 file under it. Segments whose class the method does not know are stored with
// class "unknown" (the store needs a class); `tactile features` gives them the overlapping ground
// truth.
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
#include "tactile/labels/lanes.h"
#include "tactile/labels/suggestions.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/segment/fit.h"
#include "tactile/segment/presets.h"
#include "tactile/segment/scoring.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct SegmentOptions {
  std::vector<std::string> inputs;
  std::string database, method, params, preset, fit_to, score;
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
  double start_time = 0.0, rate_hz = 0.0;  // its frames, for --score
  int64_t frames = 0;
};

SegmentedRecording segment_file(const SegmentOptions& options, const std::string& file) {
  const Recording recording = read_recording(file);
  const SkinLayout layout = load_layout(recording.layout_id);
  // Without --method, each recording's skin's own segmenter with its parameters.
  const auto [own_method, own_params] = default_segmenter(recording.layout_id);
  const std::string method = options.method.empty() ? own_method : options.method;
  const Parameters parameters = Parameters::parse(
      options.method.empty() && options.params.empty() ? own_params : options.params, "--params");
  SegmentedRecording segmented{recording.id, method,
                               segment_recording(method, recording, layout, parameters)};
  const Stream& stream = recording.streams.front();  // segment_recording needs one
  segmented.start_time = stream.sample_count() > 0 ? stream.time_of(0) : 0.0;
  segmented.rate_hz = stream.rate_hz;
  segmented.frames = stream.sample_count();
  return segmented;
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

// The labels of one lane ("ground-truth" or "truth", "manual:NAME" or NAME, "segmenter:M",
// "model:NAME") on one recording.
LabelFilter lane_filter(const std::string& lane) {
  const LaneKey key = lane_from_id(lane == "truth" ? "ground-truth" : lane);
  LabelFilter filter;
  filter.source = key.source;
  if (key.source != LabelSource::kGroundTruth) filter.annotator = key.annotator;
  return filter;
}

std::vector<Label> lane_labels(const LabelStore& store, const std::string& lane,
                               const std::string& recording) {
  LabelFilter filter = lane_filter(lane);
  filter.recording = recording;
  return store.list(filter);
}

// --score LANE names a lane with labels in the store, or nothing is segmented: a score against
// an empty lane (a misspelt name) would read as a segmenter that found nothing right.
void check_score_lane(const LabelStore& store, const std::string& lane) {
  if (!store.list(lane_filter(lane)).empty()) return;
  std::set<std::string> lanes;
  for (const Label& label : store.list())
    if (label.source != LabelSource::kSegmenter) lanes.insert(lane_of(label).id());
  throw Error("--score " + lane,
              "no labels in this lane in " + store.path() + " (lanes with labels: " +
                  (lanes.empty() ? "none" : joined({lanes.begin(), lanes.end()})) + ")");
}

// --preset NAME: the preset's method and parameters, unless the line gives its own.
void apply_preset(SegmentOptions& options) {
  if (options.preset.empty() || !options.fit_to.empty()) return;
  const std::string path = segmenter_presets_path(options.database);
  const std::optional<SegmenterPreset> preset = find_segmenter_preset(path, options.preset);
  if (!preset) throw Error("--preset " + options.preset, "no such preset in " + path);
  if (!options.method.empty() && options.method != preset->method)
    throw Error("--preset " + options.preset,
                "is a preset of " + preset->method + ", not of --method " + options.method);
  if (!options.params.empty())
    throw Error("--params", "give either --params or --preset, not both");
  options.method = preset->method;
  options.params = preset->params;
}

// --fit-to LANE: adaptive's parameters chosen on the lane's touches, printed and saved as a
// preset; the recordings are then segmented with them.
void fit_to_lane(SegmentOptions& options, const std::vector<std::string>& files) {
  if (!options.method.empty() && options.method != "adaptive")
    throw Error("--fit-to", "fits the adaptive segmenter's parameters, not " + options.method);
  if (!options.params.empty()) throw Error("--params", "--fit-to chooses the parameters itself");
  std::vector<Recording> recordings;
  std::vector<SkinLayout> layouts;
  recordings.reserve(files.size());
  layouts.reserve(files.size());
  const LabelStore store(options.database, LabelStore::OpenMode::kExisting);
  std::vector<FitRecording> items;
  for (const std::string& file : files) {
    recordings.push_back(read_recording(file));
    layouts.push_back(load_layout(recordings.back().layout_id));
  }
  for (size_t r = 0; r < files.size(); ++r)
    items.push_back(
        {&recordings[r], &layouts[r], lane_labels(store, options.fit_to, recordings[r].id)});
  const SegmenterFit fit = fit_segmenter(items);
  std::cout << fit_report(fit);
  const SegmenterPreset preset =
      fit_preset(fit, options.preset.empty() ? "fitted" : options.preset, options.fit_to);
  const std::string path = segmenter_presets_path(options.database);
  save_segmenter_preset(path, preset);
  std::cout << "saved as preset '" << preset.name << "' in " << path
            << " (tactile segment --preset " << preset.name << ")\n";
  options.method = fit.method;
  options.params = fit.params;
}

void run_segment(SegmentOptions options) {
  check_segment_method(options.method);
  const std::vector<std::string> files = recording_files(options.inputs);
  const ShardPlan plan = shard_plan(options.shard, options.database + ".segment");
  if (plan.shard.active() && (!options.fit_to.empty() || !options.score.empty()))
    throw Error("--shard", "runs without --fit-to and --score (they read every recording)");
  if (!options.fit_to.empty()) fit_to_lane(options, files);
  apply_preset(options);
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
  if (!options.score.empty()) check_score_lane(store, options.score);
  std::set<std::string> annotators;
  int64_t total = 0;
  TouchScore scored;
  for (const std::string& file : files) {
    const SegmentedRecording segmented = segment_file(options, file);
    annotators.insert("segmenter:" + segmented.method);
    total += static_cast<int64_t>(store_segments(store, segmented, options.replace));
    if (options.score.empty()) continue;
    const TouchScore score =
        score_touches(segmented.segments, lane_labels(store, options.score, segmented.recording),
                      segmented.start_time, segmented.rate_hz, segmented.frames);
    std::cout << "  against " << options.score << ": " << touch_score_text(score) << "\n";
    scored += score;
  }
  print_segment_total(total, files.size(), options.database, annotators);
  if (!options.score.empty())
    std::cout << "all recordings against " << options.score << ": " << touch_score_text(scored)
              << "\n";
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
  command->add_option("--preset", options->preset,
                      "A saved segmenter preset (with --fit-to: the name to save it as; "
                      "default 'fitted')");
  command->add_option("--fit-to", options->fit_to,
                      "Choose adaptive's parameters from this lane's labelled touches "
                      "(ground-truth, manual:NAME or NAME; at least three touches), print "
                      "them with their held-out scores, save them as a preset, then segment");
  command->add_option("--score", options->score,
                      "Score each recording's segments against this lane (frame F1, event F1, "
                      "touches split and merged)");
  command->add_flag("--replace", options->replace,
                    "First remove each recording's earlier labels from this method");
  add_shard_options(command, options->shard);
  command->callback([options] { run_segment(*options); });
}

}  // namespace tactile::cli

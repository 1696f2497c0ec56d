// `tactile segment RECORDING.h5|FOLDER... --labels DB [--method M] [--params k=v,...] [--replace]`
// Runs a segmenter on each recording and stores its labels (source segmenter) in the
// label database, one transaction per recording. A folder stands for every .h5 file under
// it. Segments whose class the method does not know are stored with class "unknown"
// (the store needs a class); `tactile features` gives them the overlapping ground truth.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
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
};

void run_segment(const SegmentOptions& options) {
  const std::vector<std::string> methods = segmenter_methods();
  if (!options.method.empty() &&
      std::find(methods.begin(), methods.end(), options.method) == methods.end())
    throw Error("--method",
                "unknown segmenter '" + options.method + "' (known: " + joined(methods) + ")");
  const std::vector<std::string> files = recording_files(options.inputs);
  LabelStore store(options.database);
  std::set<std::string> annotators;
  int64_t total = 0;
  for (const std::string& file : files) {
    const Recording recording = read_recording(file);
    const SkinLayout layout = load_layout(recording.layout_id);
    // Without --method, each recording's skin's own segmenter with its parameters.
    const auto [own_method, own_params] = default_segmenter(recording.layout_id);
    const std::string method = options.method.empty() ? own_method : options.method;
    const Parameters parameters = Parameters::parse(
        options.method.empty() && options.params.empty() ? own_params : options.params, "--params");
    const std::string annotator = "segmenter:" + method;
    annotators.insert(annotator);
    // Suggestions an annotator rejected stay rejected; --replace removes the method's
    // earlier ones, in the same transaction (labels/suggestions.h, as the workbench's G).
    const SegmenterRun run =
        segmenter_run(store, recording.id, method,
                      segment_recording(method, recording, layout, parameters), options.replace);
    store.apply(run.edit, annotator);
    total += static_cast<int64_t>(run.edit.add.size());
    std::cout << recording.id << ": " << run.edit.add.size() << " segments (" << method << ")";
    if (options.replace) std::cout << " (replaced " << run.replaced << ")";
    if (run.rejected > 0) std::cout << " (" << run.rejected << " left out: rejected before)";
    std::cout << "\n";
  }
  std::cout << total << " segments from " << files.size()
            << (files.size() == 1 ? " recording" : " recordings") << " stored in "
            << options.database << " (" << joined({annotators.begin(), annotators.end()}) << ")\n";
}

}  // namespace

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
  command->callback([options] { run_segment(*options); });
}

}  // namespace tactile::cli

// `tactile segment RECORDING.h5|FOLDER... --labels DB --method M [--params k=v,...] [--replace]`
// Runs a segmenter on each recording and stores its labels (source segmenter) in the
// label database, one transaction per recording. A folder stands for every .h5 file under
// it. Segments whose class the method does not know are stored with class "unknown"
// (the store needs a class); `tactile features` gives them the overlapping ground truth.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
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

namespace tactile::cli {

namespace {

struct SegmentOptions {
  std::vector<std::string> inputs;
  std::string database, method, params;
  bool replace = false;
};

void run_segment(const SegmentOptions& options) {
  const std::vector<std::string> methods = segmenter_methods();
  if (std::find(methods.begin(), methods.end(), options.method) == methods.end()) {
    std::string known;
    for (const std::string& name : methods) known += (known.empty() ? "" : ", ") + name;
    throw Error("--method", "unknown segmenter '" + options.method +
                                "' (known: " + (known.empty() ? "none" : known) + ")");
  }
  const Parameters parameters = Parameters::parse(options.params, "--params");
  const std::vector<std::string> files = recording_files(options.inputs);
  LabelStore store(options.database);
  const std::string annotator = "segmenter:" + options.method;
  int64_t total = 0;
  for (const std::string& file : files) {
    const Recording recording = read_recording(file);
    const SkinLayout layout = load_layout(recording.layout_id);
    // Suggestions an annotator rejected stay rejected; --replace removes the method's
    // earlier ones, in the same transaction (labels/suggestions.h, as the workbench's G).
    const SegmenterRun run = segmenter_run(
        store, recording.id, options.method,
        segment_recording(options.method, recording, layout, parameters), options.replace);
    store.apply(run.edit, annotator);
    total += static_cast<int64_t>(run.edit.add.size());
    std::cout << recording.id << ": " << run.edit.add.size() << " segments";
    if (options.replace) std::cout << " (replaced " << run.replaced << ")";
    if (run.rejected > 0) std::cout << " (" << run.rejected << " left out: rejected before)";
    std::cout << "\n";
  }
  std::cout << total << " segments from " << files.size()
            << (files.size() == 1 ? " recording" : " recordings") << " stored in "
            << options.database << " (" << annotator << ")\n";
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
  command
      ->add_option("--method", options->method,
                   "Segmenter: proximity, threshold, frame-edge, scenario, excitation or adaptive")
      ->required();
  command->add_option("--params", options->params, "Method parameters as key=value,...");
  command->add_flag("--replace", options->replace,
                    "First remove each recording's earlier labels from this method");
  command->callback([options] { run_segment(*options); });
}

}  // namespace tactile::cli

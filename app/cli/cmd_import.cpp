// `tactile import FILE.csv --layout ID [--rate HZ] [--wide --samples-per-capture N
//  --labels-file Y.csv --class-names a,b,..] --out FILE.h5 [--labels DB] [--recording-id NAME]`
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/csv.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/layout/skin_layout.h"

namespace tactile::cli {

namespace {

struct ImportOptions {
  std::string file;
  std::string layout;
  std::optional<double> rate_hz;
  bool wide = false;
  int64_t samples_per_capture = 0;
  std::string labels_file;
  std::vector<std::string> class_names;
  std::string out;
  std::string labels;
  std::string recording_id;
  // Which wide-only options were given, to refuse them without --wide.
  const CLI::Option* samples_per_capture_option = nullptr;
  const CLI::Option* labels_file_option = nullptr;
  const CLI::Option* class_names_option = nullptr;
};

void check_options(const ImportOptions& options) {
  if (options.wide) {
    if (options.samples_per_capture_option->count() == 0)
      throw Error("--samples-per-capture", "required with --wide");
    if (options.labels_file_option->count() == 0)
      throw Error("--labels-file", "required with --wide");
    if (!options.rate_hz) throw Error("--rate", "required with --wide");
    return;
  }
  for (const CLI::Option* option :
       {options.samples_per_capture_option, options.labels_file_option, options.class_names_option})
    if (option->count() > 0) throw Error(option->get_name(), "only with --wide");
}

void run_import(const ImportOptions& options) {
  check_options(options);
  const SkinLayout layout = load_layout(options.layout);
  ImportedRecording imported;
  if (options.wide) {
    CsvWideOptions wide;
    wide.samples_per_capture = options.samples_per_capture;
    wide.labels_path = options.labels_file;
    wide.class_names = options.class_names;
    wide.rate_hz = *options.rate_hz;
    imported = import_csv_wide(options.file, layout, wide);
  } else {
    CsvLongOptions long_options;
    long_options.rate_hz = options.rate_hz;
    imported.recording = import_csv_long(options.file, layout, long_options);
  }
  Recording& recording = imported.recording;
  recording.id = options.recording_id.empty() ? std::filesystem::path(options.out).stem().string()
                                              : options.recording_id;
  for (Label& label : imported.labels) label.recording = recording.id;
  write_recording(options.out, recording);

  const Stream& stream = recording.streams.front();
  std::cout << "wrote " << options.out << ": recording " << recording.id << ", layout " << layout.id
            << ", " << stream.sample_count() << " samples x " << stream.channel_count()
            << " channels at " << stream.rate_hz << " Hz";
  if (!imported.labels.empty()) std::cout << ", " << imported.labels.size() << " labels";
  std::cout << "\n";
  if (imported.labels.empty()) return;
  if (options.labels.empty()) {
    std::cerr << "tactile import: " << imported.labels.size()
              << " ground-truth labels not stored: no --labels database given\n";
    return;
  }
  // Importing the same file again replaces its ground truth instead of doubling it.
  LabelStore store(options.labels);
  LabelFilter previous;
  previous.recording = recording.id;
  previous.source = LabelSource::kGroundTruth;
  store.remove_where(previous, "import");
  store.add_many(imported.labels);
  if (!layout.classes.empty() && store.classes(layout.id).empty())
    store.set_classes(layout.id, layout.classes);
  std::cout << "stored " << imported.labels.size() << " ground-truth labels in " << options.labels
            << "\n";
}

}  // namespace

void register_import(CLI::App& app) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand("import", "Convert a CSV recording to the native file");
  command->add_option("FILE", options->file, "CSV file (long: header + one row per sample)")
      ->required();
  command
      ->add_option("--layout", options->layout,
                   "Layout id: nao, tsa, fur, robovie, flux, "
                   "grid:RxC, strip:N")
      ->required();
  command
      ->add_option("--rate", options->rate_hz,
                   "Sampling rate in Hz (default for long CSV: from the time column)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--wide", options->wide,
                    "One capture per row, channel-major, with a labels file");
  options->samples_per_capture_option =
      command
          ->add_option("--samples-per-capture", options->samples_per_capture,
                       "Samples of each channel in one capture (--wide)")
          ->check(CLI::PositiveNumber);
  options->labels_file_option =
      command->add_option("--labels-file", options->labels_file,
                          "One class per capture, by name or 0-based index (--wide)");
  options->class_names_option =
      command
          ->add_option("--class-names", options->class_names,
                       "Class names, comma-separated (--wide; default: the layout's)")
          ->delimiter(',');
  command->add_option("--out", options->out, "Output recording file (.h5)")->required();
  command->add_option("--labels", options->labels,
                      "Label database (SQLite) for the ground-truth labels of --wide");
  command->add_option("--recording-id", options->recording_id,
                      "Recording id (default: the output file's stem)");
  command->callback([options] { run_import(*options); });
}

}  // namespace tactile::cli

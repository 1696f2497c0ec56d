// `tactile import FILE --layout ID --out FILE.h5|FOLDER [--labels DB]`: a recording from
// what other programs publish (docs/IMPORT.md): long or wide CSV (a class column, grouping
// columns), NumPy .npy / .npz, JSON arrays of frames, a dataset of any HDF5 file, a MATLAB .mat
// variable, EDF+/BDF+, an XDF stream.
// The import itself is core's (tactile/labels/import_files.h), shared with the workbench.
#include <iostream>
#include <memory>
#include <vector>

#include "commands.h"
#include "tactile/labels/import_files.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

// The parsed flags; which of the wide-only ones were given is read off their options.
struct ImportArguments {
  FileImportOptions options;
  int64_t samples_per_capture = 0;
  std::string labels_file;
  std::vector<std::string> class_names;
  const CLI::Option* samples_per_capture_option = nullptr;
  const CLI::Option* labels_file_option = nullptr;
  const CLI::Option* class_names_option = nullptr;
};

void run_import(ImportArguments& arguments) {
  FileImportOptions& options = arguments.options;
  if (arguments.samples_per_capture_option->count() > 0)
    options.samples_per_capture = arguments.samples_per_capture;
  if (arguments.labels_file_option->count() > 0) options.labels_file = arguments.labels_file;
  if (arguments.class_names_option->count() > 0) options.class_names = arguments.class_names;
  const FileImportReport report = import_file(
      options, {}, [](const ImportedFile& file) { std::cout << imported_file_line(file) << "\n"; });
  if (report.labels == 0) return;
  const std::string kind =
      options.annotator.empty() ? "ground-truth labels" : "labels of " + options.annotator;
  if (options.labels.empty()) {
    std::cerr << "tactile import: " << report.labels << " " << kind
              << " not stored: no --labels database given\n";
    return;
  }
  std::cout << "stored " << report.stored << " " << kind << " in " << options.labels << "\n";
}

}  // namespace

void register_import(CLI::App& app) {
  auto arguments = std::make_shared<ImportArguments>();
  FileImportOptions* options = &arguments->options;
  CLI::App* command = app.add_subcommand("import",
                                         "Convert other programs' data (CSV, NumPy .npy/.npz, JSON "
                                         "frames, HDF5 datasets, MATLAB .mat, EDF+/BDF+, XDF) "
                                         "to recordings");
  command
      ->add_option("FILE", options->file,
                   "CSV (long: header + one row per sample; or --wide), .npy, .npz, .json, .h5, "
                   ".mat (v5, v7.3), .edf, .bdf or .xdf")
      ->required();
  command
      ->add_option("--layout", options->layout,
                   "Layout id: " + joined(known_layout_ids()) + ", grid:RxC, strip:N")
      ->required();
  command
      ->add_option("--rate", options->rate_hz,
                   "Sampling rate in Hz (default for long CSV: from the time column)")
      ->check(CLI::PositiveNumber);
  command->add_option(
      "--rate-variable", options->rate_variable,
      ".mat: the scalar variable holding the rate in Hz (e.g. fs or s.rate; not with --rate)");
  command->add_flag("--wide", options->wide,
                    "One capture per row, channel-major, with a labels file");
  arguments->samples_per_capture_option =
      command
          ->add_option("--samples-per-capture", arguments->samples_per_capture,
                       "Samples of each channel in one capture (--wide)")
          ->check(CLI::PositiveNumber);
  arguments->labels_file_option =
      command->add_option("--labels-file", arguments->labels_file,
                          "One class per capture, by name or 0-based index (--wide)");
  arguments->class_names_option =
      command
          ->add_option("--class-names", arguments->class_names,
                       "Class names, comma-separated (--wide; default: the layout's)")
          ->delimiter(',');
  command->add_option("--dataset", options->dataset,
                      "The array to read: a .npz array's name, an HDF5 file's dataset path, a .mat "
                      "variable (s.field for a "
                      "struct's field; default: the file's one array)");
  command->add_option("--key", options->key,
                      "The JSON key holding the frames (a.b for nested; default: the top level)");
  command->add_option(
      "--value-key", options->value_key,
      "JSON frames given as objects ({\"label\": ..., \"data\": [...]}): the member holding each "
      "frame (e.g. data)");
  command->add_option(
      "--class-key", options->class_key,
      "JSON frames given as objects: the member holding each frame's class (e.g. label)");
  command->add_flag("--captures", options->captures,
                    "The array is [captures][channels][samples]: captures laid end to end");
  command->add_option(
      "--class-array", options->class_array,
      "Classes per frame (or per capture) in the same file: a .npz array, an HDF5 dataset, a JSON "
      "key, a .mat variable (cell array of names, char matrix, numeric vector); names, or indices "
      "into the layout's classes; none/empty: no touch");
  command->add_option("--class-column", options->class_column,
                      "Long CSV: the column of class names per row (none/empty: no touch)");
  command
      ->add_option(
          "--group-columns", options->group_columns,
          "Long CSV: columns whose values split the table into recordings (e.g. subject,capture); "
          "--out is then a folder")
      ->delimiter(',');
  command
      ->add_option("--out", options->out,
                   "Output recording file (.h5), or a folder with --group-columns")
      ->required();
  command->add_option("--labels", options->labels,
                      "Label database (SQLite) for the ground-truth labels (--wide, "
                      "--class-column, --class-array)");
  command->add_option("--recording-id", options->recording_id,
                      "Recording id (default: the output file's stem)");
  command
      ->add_option(
          "--signals", options->signals,
          "EDF/BDF: the signals by label, comma-separated, in channel order (default: every "
          "signal but the annotations)")
      ->delimiter(',');
  command
      ->add_option(
          "--annotation-seconds", options->annotation_seconds,
          "EDF/BDF: the length of annotations of zero or unknown duration (default: refused)")
      ->check(CLI::PositiveNumber);
  command->add_option(
      "--annotator", options->annotator,
      "Store the file's labels as this annotator's (replacing theirs of the recording) "
      "instead of the ground truth");
  command->add_option(
      "--stream", options->stream,
      "XDF: the data stream, NAME or type:TYPE (default: the only numeric stream with a "
      "nominal rate)");
  command->add_option(
      "--markers", options->markers,
      "XDF: the markers stream whose markers become ground-truth labels, NAME or type:TYPE "
      "(default: the only markers stream)");
  command->callback([arguments] { run_import(*arguments); });
}

}  // namespace tactile::cli

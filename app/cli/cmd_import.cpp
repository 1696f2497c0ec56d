// `tactile import FILE --layout ID --out FILE.h5|FOLDER [--labels DB]`: a recording from
// what other programs publish (docs/IMPORT.md): long or wide CSV (a class column, grouping
// columns), NumPy .npy / .npz, JSON arrays of frames, a dataset of any HDF5 file.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/array_import.h"
#include "tactile/io/csv.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/labels/commands.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

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
  std::string dataset;       // .npz array, HDF5 dataset
  std::string key;           // JSON key
  std::string value_key;     // JSON frames as objects: the member holding each frame
  std::string class_key;     // ... and the member holding its class
  std::string class_array;   // classes per frame or capture: .npz array, HDF5 dataset, JSON key
  std::string class_column;  // long CSV
  std::vector<std::string> group_columns;
  bool captures = false;
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

std::string extension_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// The array a file holds: `name` picks a .npz array or an HDF5 dataset, `key` a JSON key.
ImportedArray array_in(const std::string& path, const std::string& name, const std::string& key,
                       const char* name_option, const std::string& member = "") {
  const std::string extension = extension_of(path);
  if (extension == ".npy") return read_npy(path);
  if (extension == ".json") return read_json_array(path, key, member);
  if (extension == ".npz") {
    if (!name.empty()) return read_npz(path, name);
    const std::vector<std::string> names = npz_names(path);
    if (names.size() != 1) {
      std::string list;
      for (const std::string& entry : names) list += (list.empty() ? "" : ", ") + entry;
      throw Error(name_option, path + " holds " + std::to_string(names.size()) + " arrays (" + list + "): name one");
    }
    return read_npz(path, names.front());
  }
  if (extension == ".h5" || extension == ".hdf5" || extension == ".hdf") {
    if (name.empty()) throw Error(name_option, "names the dataset of " + path + " to read (e.g. /data/pressure)");
    return read_hdf5_dataset(path, name);
  }
  throw Error(path, "not a format import reads (.csv, .npy, .npz, .json, .h5)");
}

std::vector<ImportedRecording> read_input(const ImportOptions& options, const SkinLayout& layout) {
  const std::string extension = extension_of(options.file);
  if (extension == ".csv" || extension == ".txt") {
    if (!options.dataset.empty() || !options.key.empty() || !options.class_array.empty() || options.captures)
      throw Error("--dataset/--key/--class-array/--captures", "are for array files, not CSV");
    if (options.wide) {
      CsvWideOptions wide;
      wide.samples_per_capture = options.samples_per_capture;
      wide.labels_path = options.labels_file;
      wide.class_names = options.class_names;
      wide.rate_hz = *options.rate_hz;
      return {import_csv_wide(options.file, layout, wide)};
    }
    if (!options.class_column.empty() || !options.group_columns.empty()) {
      CsvTableOptions table;
      table.rate_hz = options.rate_hz;
      table.class_column = options.class_column;
      table.group_columns = options.group_columns;
      return import_csv_table(options.file, layout, table);
    }
    CsvLongOptions long_options;
    long_options.rate_hz = options.rate_hz;
    ImportedRecording imported;
    imported.recording = import_csv_long(options.file, layout, long_options);
    return {std::move(imported)};
  }
  const bool json = extension == ".json";
  if (!options.class_column.empty())
    throw Error("--class-column",
                std::string("is for CSV tables; the classes of an array file are named by ") +
                    (json ? "--class-key (a member of each frame object) or --class-array (a key)"
                          : "--class-array (an array or dataset of the same file)"));
  if (options.wide || !options.group_columns.empty())
    throw Error("--wide/--group-columns", "are for CSV files");
  if (!json && (!options.value_key.empty() || !options.class_key.empty()))
    throw Error("--value-key/--class-key", "are for JSON frames given as objects");
  if (!options.class_key.empty() && !options.class_array.empty())
    throw Error("--class-key", "or --class-array, not both");
  if (!options.rate_hz) throw Error("--rate", "is needed for an array (it carries no time)");
  const ImportedArray array =
      array_in(options.file, options.dataset, options.key, "--dataset", options.value_key);
  ArrayRecordingOptions array_options;
  array_options.rate_hz = *options.rate_hz;
  array_options.captures = options.captures;
  if (!options.class_array.empty() || !options.class_key.empty()) {
    // The classes live in the same file: another array, dataset or key, or a member of each
    // frame object.
    const ImportedArray classes =
        !options.class_key.empty()
            ? array_in(options.file, "", options.key, "--class-key", options.class_key)
            : array_in(options.file, json ? "" : options.class_array,
                       json ? options.class_array : "", "--class-array");
    if (classes.text) {
      array_options.classes = classes.strings;
    } else {
      for (double value : classes.values) {
        // Class indices into the layout's vocabulary (or the number as the name).
        const auto index = static_cast<int64_t>(value);
        array_options.classes.push_back(index >= 0 && index < static_cast<int64_t>(layout.classes.size()) && value == static_cast<double>(index)
                                            ? layout.classes[static_cast<size_t>(index)]
                                            : std::to_string(index));
      }
    }
  }
  std::string where = options.file;
  if (!options.dataset.empty()) where += ":" + options.dataset;
  if (!options.key.empty()) where += " key " + options.key;
  if (!options.value_key.empty()) where += " member " + options.value_key;
  ImportedRecording imported = recording_from_array(array, layout, array_options, where);
  imported.recording.id = std::filesystem::path(options.file).stem().string();
  imported.recording.metadata["imported_from"] = std::filesystem::path(options.file).filename().string();
  return {std::move(imported)};
}

void run_import(const ImportOptions& options) {
  check_options(options);
  const SkinLayout layout = load_layout(options.layout);
  std::vector<ImportedRecording> recordings = read_input(options, layout);
  const bool grouped = !options.group_columns.empty();
  if (grouped && !options.recording_id.empty())
    throw Error("--recording-id", "names one recording; --group-columns makes one per group");
  if (grouped) {
    // One file per group in the --out folder, never over an existing one.
    std::error_code error;
    std::filesystem::create_directories(options.out, error);
    if (!std::filesystem::is_directory(options.out))
      throw Error("--out", options.out + " is not a folder (with --group-columns it holds one file per group)");
    for (const ImportedRecording& imported : recordings) {
      const std::string path = (std::filesystem::path(options.out) / (imported.recording.id + ".h5")).string();
      if (std::filesystem::exists(path)) throw Error(path, "exists already; import writes no file over another");
    }
  }
  size_t stored = 0, labels = 0;
  std::unique_ptr<LabelStore> store;
  for (ImportedRecording& imported : recordings) {
    Recording& recording = imported.recording;
    std::string out = options.out;
    if (grouped) {
      out = (std::filesystem::path(options.out) / (recording.id + ".h5")).string();
    } else {
      recording.id = options.recording_id.empty() ? std::filesystem::path(options.out).stem().string()
                                                  : options.recording_id;
    }
    for (Label& label : imported.labels) label.recording = recording.id;
    write_recording(out, recording);
    const Stream& stream = recording.streams.front();
    std::cout << "wrote " << out << ": recording " << recording.id << ", layout " << layout.id << ", "
              << stream.sample_count() << " samples x " << stream.channel_count() << " channels at "
              << stream.rate_hz << " Hz";
    if (!imported.labels.empty()) std::cout << ", " << imported.labels.size() << " labels";
    std::cout << "\n";
    labels += imported.labels.size();
    if (imported.labels.empty() || options.labels.empty()) continue;
    if (!store) store = std::make_unique<LabelStore>(options.labels);
    // Importing the same file again replaces its ground truth instead of doubling it; one
    // command, so `undo` by "import" takes back the whole import.
    store->apply(ground_truth_import(*store, recording.id, imported.labels), "import");
    stored += imported.labels.size();
  }
  if (labels == 0) return;
  if (options.labels.empty()) {
    std::cerr << "tactile import: " << labels << " ground-truth labels not stored: no --labels database given\n";
    return;
  }
  if (!layout.classes.empty() && store->classes(layout.id).empty()) store->set_classes(layout.id, layout.classes);
  std::cout << "stored " << stored << " ground-truth labels in " << options.labels << "\n";
}

}  // namespace

void register_import(CLI::App& app) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand(
      "import", "Convert other programs' data (CSV, NumPy .npy/.npz, JSON frames, HDF5 datasets) to recordings");
  command->add_option("FILE", options->file,
                      "CSV (long: header + one row per sample; or --wide), .npy, .npz, .json or .h5")
      ->required();
  command
      ->add_option("--layout", options->layout,
                   "Layout id: " + joined(known_layout_ids()) + ", grid:RxC, strip:N")
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
  command->add_option("--dataset", options->dataset,
                      "The array to read: a .npz array's name, an HDF5 file's dataset path");
  command->add_option("--key", options->key, "The JSON key holding the frames (a.b for nested; default: the top level)");
  command->add_option(
      "--value-key", options->value_key,
      "JSON frames given as objects ({\"label\": ..., \"data\": [...]}): the member holding each "
      "frame (e.g. data)");
  command->add_option(
      "--class-key", options->class_key,
      "JSON frames given as objects: the member holding each frame's class (e.g. label)");
  command->add_flag("--captures", options->captures,
                    "The array is [captures][channels][samples]: captures laid end to end");
  command->add_option("--class-array", options->class_array,
                      "Classes per frame (or per capture) in the same file: a .npz array, an HDF5 dataset, a JSON "
                      "key; names, or indices into the layout's classes; none/empty: no touch");
  command->add_option("--class-column", options->class_column,
                      "Long CSV: the column of class names per row (none/empty: no touch)");
  command->add_option("--group-columns", options->group_columns,
                      "Long CSV: columns whose values split the table into recordings (e.g. subject,capture); "
                      "--out is then a folder")
      ->delimiter(',');
  command->add_option("--out", options->out, "Output recording file (.h5), or a folder with --group-columns")
      ->required();
  command->add_option("--labels", options->labels,
                      "Label database (SQLite) for the ground-truth labels (--wide, --class-column, --class-array)");
  command->add_option("--recording-id", options->recording_id,
                      "Recording id (default: the output file's stem)");
  command->callback([options] { run_import(*options); });
}

}  // namespace tactile::cli

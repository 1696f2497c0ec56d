#include "tactile/labels/import_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "tactile/error.h"
#include "tactile/io/array_import.h"
#include "tactile/io/csv.h"
#include "tactile/io/edf_import.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/io/mat_import.h"
#include "tactile/io/xdf_import.h"
#include "tactile/labels/commands.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile {

namespace {

void check_import_options(const FileImportOptions& options) {
  if (options.layout.empty())
    throw Error("--layout",
                "required: a layout id (" + joined(known_layout_ids()) + "), grid:RxC or strip:N");
  if (options.wide) {
    if (!options.samples_per_capture) throw Error("--samples-per-capture", "required with --wide");
    if (!options.labels_file) throw Error("--labels-file", "required with --wide");
    if (!options.rate_hz) throw Error("--rate", "required with --wide");
    return;
  }
  if (options.samples_per_capture) throw Error("--samples-per-capture", "only with --wide");
  if (options.labels_file) throw Error("--labels-file", "only with --wide");
  if (options.class_names) throw Error("--class-names", "only with --wide");
  if ((!options.stream.empty() || !options.markers.empty()) &&
      import_format_of(options.file) != ".xdf")
    throw Error("--stream/--markers", "are for XDF files");
}

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// The array a file holds: `name` picks a .npz array or an HDF5 dataset, `key` a JSON key.
ImportedArray array_in(const std::string& path, const std::string& name, const std::string& key,
                       const char* name_option, const std::string& member = "") {
  const std::string extension = lower_extension(path);
  if (extension == ".npy") return read_npy(path);
  if (extension == ".json") return read_json_array(path, key, member);
  if (extension == ".npz") {
    if (!name.empty()) return read_npz(path, name);
    const std::vector<std::string> names = npz_names(path);
    if (names.size() != 1) {
      std::string list;
      for (const std::string& entry : names) list += (list.empty() ? "" : ", ") + entry;
      throw Error(name_option, path + " holds " + std::to_string(names.size()) + " arrays (" +
                                   list + "): name one");
    }
    return read_npz(path, names.front());
  }
  if (extension == ".h5" || extension == ".hdf5" || extension == ".hdf") {
    if (name.empty())
      throw Error(name_option, "names the dataset of " + path + " to read (e.g. /data/pressure)");
    return read_hdf5_dataset(path, name);
  }

  if (extension == ".mat") {
    if (!name.empty()) return read_mat_variable(path, name);
    // Without a name: the one numeric variable (or struct field) of two or more dimensions
    // longer than 1, as a .npz of one array needs none.
    const std::vector<MatVariable> variables = mat_variables(path);
    std::vector<std::string> candidates;
    std::string list;
    for (const MatVariable& variable : variables) {
      if (!list.empty()) list += ", ";
      list += mat_variable_line(variable);
      if (variable.numeric() && std::count_if(variable.dims.begin(), variable.dims.end(),
                                              [](int64_t extent) { return extent > 1; }) >= 2)
        candidates.push_back(variable.name);
    }
    if (candidates.size() != 1)
      throw Error(name_option, path + " holds " + std::to_string(candidates.size()) +
                                   " numeric arrays of 2 or more dimensions: name one (" +
                                   (list.empty() ? "no variables" : list) + ")");
    return read_mat_variable(path, candidates.front());
  }
  throw Error(path,
              "not a format import reads (.csv, .npy, .npz, .json, .h5, .mat, .edf, .bdf, .xdf)");
}

// A recording file (EDF, XDF) carries its own rate, channel names and labels: the options of
// arrays and CSV files are refused as not for `what`.
void refuse_array_options(const FileImportOptions& options, const std::string& what) {
  if (!options.dataset.empty() || !options.key.empty() || !options.value_key.empty() ||
      !options.class_key.empty() || !options.class_array.empty() || options.captures ||
      !options.class_column.empty() || options.wide || !options.group_columns.empty())
    throw Error(
        "--dataset/--key/--value-key/--class-key/--class-array/--captures/--class-column/"
        "--wide/--group-columns",
        "are not for " + what);
}

// What the file holds, read into recordings of the layout; `shape` gets an array's shape.
std::vector<ImportedRecording> read_import_input(const FileImportOptions& options,
                                                 const SkinLayout& layout,
                                                 std::vector<int64_t>* shape) {
  const std::string extension = lower_extension(options.file);
  if (extension == ".edf" || extension == ".bdf") {
    if (options.rate_hz)
      throw Error("--rate", "an EDF or BDF file states its own rate; leave --rate out");
    refuse_array_options(options, "EDF or BDF files (--signals chooses their signals)");
    EdfImportOptions edf;
    edf.signals = options.signals;
    edf.annotation_seconds = options.annotation_seconds;
    return {import_edf(options.file, layout, edf)};
  }
  if (!options.signals.empty() || options.annotation_seconds)
    throw Error("--signals/--annotation-seconds", "are for EDF and BDF files");
  if (extension == ".xdf") {
    if (options.rate_hz)
      throw Error("--rate", "an XDF stream is resampled to its own nominal rate");
    refuse_array_options(options, "XDF files (--stream and --markers choose its streams)");
    return {import_xdf(options.file, layout, XdfImportOptions{options.stream, options.markers})};
  }
  if (!options.rate_variable.empty() && extension != ".mat")
    throw Error("--rate-variable", "is for .mat files (a scalar variable holding the rate in Hz)");
  if (extension == ".csv" || extension == ".txt") {
    if (!options.dataset.empty() || !options.key.empty() || !options.class_array.empty() ||
        options.captures)
      throw Error("--dataset/--key/--class-array/--captures", "are for array files, not CSV");
    if (options.wide) {
      CsvWideOptions wide;
      wide.samples_per_capture = *options.samples_per_capture;
      wide.labels_path = *options.labels_file;
      if (options.class_names) wide.class_names = *options.class_names;
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
  std::optional<double> rate_hz = options.rate_hz;
  if (!options.rate_variable.empty()) {
    // The rate as a scalar variable of the .mat file.
    if (rate_hz) throw Error("--rate-variable", "or --rate, not both");
    const ImportedArray rate = read_mat_variable(options.file, options.rate_variable);
    if (rate.text || rate.values.size() != 1 || !std::isfinite(rate.values.front()) ||
        rate.values.front() <= 0.0)
      throw Error("--rate-variable", options.file + ":" + options.rate_variable +
                                         " is not one positive number (the rate in Hz)");
    rate_hz = rate.values.front();
  }
  if (!rate_hz) throw Error("--rate", "is needed for an array (it carries no time)");
  const ImportedArray array =
      array_in(options.file, options.dataset, options.key, "--dataset", options.value_key);
  if (shape) *shape = array.shape;
  ArrayRecordingOptions array_options;
  array_options.rate_hz = *rate_hz;
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
        array_options.classes.push_back(
            index >= 0 && index < static_cast<int64_t>(layout.classes.size()) &&
                    value == static_cast<double>(index)
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
  imported.recording.metadata["imported_from"] =
      std::filesystem::path(options.file).filename().string();
  return {std::move(imported)};
}

void report(const std::function<void(double)>& step, double fraction) {
  if (step) step(fraction);
}

}  // namespace

std::string import_format_of(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".csv" || extension == ".txt") return "CSV";
  if (extension == ".hdf5" || extension == ".hdf") return ".h5";
  for (const char* known : {".npy", ".npz", ".json", ".h5", ".mat", ".edf", ".bdf", ".xdf"})
    if (extension == known) return known;
  return "";
}

std::string imported_file_line(const ImportedFile& file) {
  std::ostringstream line;
  line << "wrote " << file.path << ": recording " << file.recording << ", layout " << file.layout
       << ", " << file.samples << " samples x " << file.channels << " channels at " << file.rate_hz
       << " Hz";
  if (file.labels > 0) line << ", " << file.labels << " labels";
  return line.str();
}

FileImportReport import_file(const FileImportOptions& options,
                             const std::function<void(double)>& step,
                             const std::function<void(const ImportedFile&)>& written) {
  check_import_options(options);
  if (options.out.empty()) throw Error("--out", "required: the recording file (.h5) to write");
  report(step, 0.0);
  const SkinLayout layout = load_layout(options.layout);
  std::vector<ImportedRecording> recordings = read_import_input(options, layout, nullptr);
  const bool grouped = !options.group_columns.empty();
  if (grouped && !options.recording_id.empty())
    throw Error("--recording-id", "names one recording; --group-columns makes one per group");
  namespace fs = std::filesystem;
  if (grouped) {
    // One file per group in the --out folder, never over an existing one.
    std::error_code error;
    fs::create_directories(options.out, error);
    if (!fs::is_directory(options.out))
      throw Error(
          "--out",
          options.out + " is not a folder (with --group-columns it holds one file per group)");
    for (const ImportedRecording& imported : recordings) {
      const std::string path = (fs::path(options.out) / (imported.recording.id + ".h5")).string();
      if (fs::exists(path)) throw Error(path, "exists already; import writes no file over another");
    }
  }
  // Reading is the first half; the files the second, one step each.
  report(step, 0.5);
  FileImportReport result;
  std::unique_ptr<LabelStore> store;
  for (size_t index = 0; index < recordings.size(); ++index) {
    // A stop asked for (a cancelled job) ends the import between two files.
    if (index > 0)
      report(step, 0.5 + 0.5 * static_cast<double>(index) / static_cast<double>(recordings.size()));
    ImportedRecording& imported = recordings[index];
    Recording& recording = imported.recording;
    std::string out = options.out;
    if (grouped) {
      out = (fs::path(options.out) / (recording.id + ".h5")).string();
    } else {
      recording.id = options.recording_id.empty() ? fs::path(options.out).stem().string()
                                                  : options.recording_id;
    }
    for (Label& label : imported.labels) {
      label.recording = recording.id;
      if (!options.annotator.empty()) {
        // --annotator: the file's labels are this person's, not the ground truth.
        label.annotator = options.annotator;
        label.source = LabelSource::kManual;
      }
    }
    write_recording(out, recording);
    const Stream& stream = recording.streams.front();
    ImportedFile file{out,
                      recording.id,
                      layout.id,
                      stream.sample_count(),
                      stream.channel_count(),
                      stream.rate_hz,
                      imported.labels.size()};
    if (written) written(file);
    result.files.push_back(std::move(file));
    result.labels += imported.labels.size();
    if (!imported.labels.empty() && !options.labels.empty()) {
      if (!store) store = std::make_unique<LabelStore>(options.labels);
      // Importing the same file again replaces its ground truth (or the --annotator's labels)
      // instead of doubling them; one command, so `undo` by "import" takes back the whole import.
      store->apply(options.annotator.empty()
                       ? ground_truth_import(*store, recording.id, imported.labels)
                       : annotator_import(*store, recording.id, options.annotator, imported.labels),
                   "import");
      result.stored += imported.labels.size();
    }
  }
  if (store && !layout.classes.empty() && store->classes(layout.id).empty())
    store->set_classes(layout.id, layout.classes);
  return result;
}

ImportPreview preview_import(const FileImportOptions& options, int frames,
                             const std::function<void(double)>& step) {
  ImportPreview preview;
  try {
    check_import_options(options);
    report(step, 0.0);
    const SkinLayout layout = load_layout(options.layout);
    std::vector<int64_t> shape;
    const std::vector<ImportedRecording> recordings = read_import_input(options, layout, &shape);
    report(step, 1.0);
    const std::string format = import_format_of(options.file);
    if (format == ".edf" || format == ".bdf")
      preview.format = format + " recording";
    else if (format == ".xdf")
      preview.format =
          "XDF stream " + in_quotes(recordings.front().recording.metadata.at("xdf_stream"));
    else if (format != "CSV")
      preview.format = format + " array";
    else if (options.wide)
      preview.format = "wide CSV";
    else if (!options.class_column.empty() || !options.group_columns.empty())
      preview.format = "long CSV table";
    else
      preview.format = "long CSV";
    preview.shape = std::move(shape);
    preview.layout = layout.id;
    for (const ImportedRecording& imported : recordings) {
      preview.recordings.push_back(imported.recording.id);
      preview.samples += imported.recording.streams.front().sample_count();
      preview.labels += imported.labels.size();
      for (const Label& label : imported.labels)
        if (std::find(preview.classes.begin(), preview.classes.end(), label.class_name) ==
            preview.classes.end())
          preview.classes.push_back(label.class_name);
    }
    if (recordings.empty()) return preview;
    const ImportedRecording& first = recordings.front();
    const Stream& stream = first.recording.streams.front();
    preview.channels = stream.channels;
    preview.rate_hz = stream.rate_hz;
    const int64_t shown = std::min<int64_t>(std::max(frames, 0), stream.sample_count());
    for (int64_t row = 0; row < shown; ++row) {
      const double time = stream.time_of(row);
      preview.times.push_back(time);
      std::vector<double> values(static_cast<size_t>(stream.channel_count()));
      for (int64_t column = 0; column < stream.channel_count(); ++column)
        values[static_cast<size_t>(column)] = static_cast<double>(stream.samples(row, column));
      preview.frames.push_back(std::move(values));
      std::string class_name;
      for (const Label& label : first.labels)
        if (label.t0 <= time && time < label.t1) class_name = label.class_name;
      preview.frame_classes.push_back(std::move(class_name));
    }
  } catch (const Error& refusal) {
    ImportPreview refused;
    refused.refusal = refusal.what();
    return refused;
  }
  return preview;
}

}  // namespace tactile

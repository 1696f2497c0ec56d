#include "tactile/formats/import.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <sstream>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/commands.h"
#include "tactile/labels/label_format.h"
#include "tactile/labels/quality.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// A label file of another tool (ELAN, Label Studio) given to `import` is no recording: say where
// it goes, instead of asking for the options of a recording format that claims its extension.
void refuse_label_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return;
  const LabelFormat* format = nullptr;
  try {
    format = &label_format_of(path);
  } catch (const Error&) {
    return;  // no label format reads it
  }
  if (format->reads_any_of_its_extension()) return;
  throw Error(path, "a label file (" + format->name() +
                        "), not a recording: labels go into a label store with `tactile labels "
                        "import DB " +
                        path + "`");
}

// The importer of the file, its options checked against what it takes.
const RecordingImporter& checked_importer(const FileImportOptions& options) {
  if (options.layout.empty())
    throw Error("--layout",
                "required: a layout id (" + joined(known_layout_ids()) + "), grid:RxC or strip:N");
  const RecordingImporter* importer = importer_for(options.file);
  refuse_label_file(options.file);
  if (!importer)
    throw Error(options.file, "not a format import reads (" + import_formats_text() + ")");
  check_import_values(*importer, options.values);
  return *importer;
}

void report(const std::function<void(double)>& step, double fraction) {
  if (step) step(fraction);
}

}  // namespace

bool import_writes_folder(const FileImportOptions& options) {
  const RecordingImporter* importer = importer_for(options.file);
  return importer && importer->writes_several(options.values);
}

std::string imported_file_line(const ImportedFile& file) {
  std::ostringstream line;
  line << "wrote " << file.path << ": recording " << file.recording << ", layout " << file.layout
       << ", " << file.samples << " samples x " << file.channels << " channels at " << file.rate_hz
       << " Hz";
  if (file.labels > 0) line << ", " << file.labels << " labels";
  if (!file.dropped_labels.empty()) line << "; no label made of: " << file.dropped_labels;
  return line.str();
}

FileImportReport import_file(const FileImportOptions& options,
                             const std::function<void(double)>& step,
                             const std::function<void(const ImportedFile&)>& written) {
  const RecordingImporter& importer = checked_importer(options);
  if (options.out.empty()) throw Error("--out", "required: the recording file (.h5) to write");
  report(step, 0.0);
  const SkinLayout layout = load_layout(options.layout);
  std::vector<ImportedRecording> recordings =
      importer.read(options.file, layout, options.values).recordings;
  const bool grouped = importer.writes_several(options.values);
  if (grouped && !options.recording_id.empty())
    throw Error("--recording-id", "names one recording; the import makes one per group");
  namespace fs = std::filesystem;
  if (grouped) {
    // One file per group in the --out folder, never over an existing one.
    std::error_code error;
    fs::create_directories(options.out, error);
    if (!fs::is_directory(options.out))
      throw Error("--out",
                  options.out + " is not a folder (this import writes one file per group into it)");
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
    // A label outside the recording or shorter than one of its samples is refused before
    // anything is written.
    const RecordingSpan span = recording_span(recording);
    for (const Label& label : imported.labels)
      if (const SpanProblem problem = span_problem(label, span); !problem.kind.empty())
        throw Error(options.file, problem.what);
    write_recording(out, recording);
    const Stream& stream = recording.streams.front();
    ImportedFile file{out,
                      recording.id,
                      layout.id,
                      stream.sample_count(),
                      stream.channel_count(),
                      stream.rate_hz,
                      imported.labels.size(),
                      recording.metadata.count("dropped_labels")
                          ? recording.metadata.at("dropped_labels")
                          : std::string()};
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
    const RecordingImporter& importer = checked_importer(options);
    report(step, 0.0);
    const SkinLayout layout = load_layout(options.layout);
    ImportRead read = importer.read(options.file, layout, options.values);
    report(step, 1.0);
    const std::vector<ImportedRecording>& recordings = read.recordings;
    preview.format = read.described.empty() ? importer.name() : read.described;
    preview.shape = std::move(read.shape);
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

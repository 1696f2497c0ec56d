#pragma once
// Other programs' files into recordings (docs/IMPORT.md): `tactile import` and the workbench's
// File > Import call this one function, so the checks, the refusals (naming the option or the
// place in the file, as the command line's options are named), what is written and where
// are the same wherever an import starts. The ground truth goes into a label store as one
// command (ground_truth_import: importing again replaces it). A preview reads the same way
// and writes nothing.
//
// Each format is an importer (formats/importer.h, one file each in core/src/formats/): this
// driver checks the options against the one that reads the file, lets it read, and writes.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/importer.h"

namespace tactile {

// What `tactile import` is given: the file, the layout and where to write, and the options of
// the file's format by their flags (formats/importer.h).
struct FileImportOptions {
  std::string file;          // FILE: any format an importer reads (importer_for)
  std::string layout;        // --layout: a layout id, grid:RxC or strip:N
  ImportValues values;       // the format's options: --rate, --dataset, --signals, ...
  std::string out;           // --out: the .h5 file, or the folder when the format writes several
  std::string labels;        // --labels: the label store; "" = the ground truth is not stored
  std::string recording_id;  // --recording-id: "" = the output file's stem
  // Any format: the file's labels stored as this annotator's (replacing their labels of the
  // recording on a second import) instead of the ground truth; "" = the ground truth.
  std::string annotator;  // --annotator
};

// True when the import writes a folder of recordings (a CSV split by --group-columns).
bool import_writes_folder(const FileImportOptions& options);

// One recording written.
struct ImportedFile {
  std::string path;       // the .h5
  std::string recording;  // its id
  std::string layout;
  int64_t samples = 0, channels = 0;
  double rate_hz = 0.0;
  size_t labels = 0;  // ground-truth labels read for it
  // Annotations or markers of the file that made no label (at or after the data's end, under
  // one sample), as the reader named them; "" when none (the recording's "dropped_labels").
  std::string dropped_labels;
};

// "wrote OUT: recording ID, layout L, N samples x C channels at R Hz[, K labels][; no label
// made of: ...]", the line `tactile import` prints per file.
std::string imported_file_line(const ImportedFile& file);

struct FileImportReport {
  std::vector<ImportedFile> files;  // in the order written
  size_t labels = 0;                // ground-truth labels read, in all files
  size_t stored = 0;                // of them stored in options.labels (0 when it is "")
};

// Reads the file, checks it against the layout and the options, writes each recording
// (never over an existing file with group_columns) and stores its ground truth. `step`
// gets the fraction done (reading, then each file) and may throw to stop before the next
// file; `written` is told of each file once it is on disk. Throws tactile::Error naming the
// option ("--rate: ...") or the place in the file; nothing is written when the input is
// refused.
FileImportReport import_file(const FileImportOptions& options,
                             const std::function<void(double)>& step = {},
                             const std::function<void(const ImportedFile&)>& written = {});

// What an import would read: the first frames and what the whole file holds.
struct ImportPreview {
  std::string format;          // "long CSV", "wide CSV", ".npz array", ...
  std::vector<int64_t> shape;  // the array's shape as stored (array files)
  std::string layout;
  std::vector<std::string> channels;  // the layout's channel names, in column order
  double rate_hz = 0.0;
  std::vector<std::string> recordings;      // ids (one per group with group_columns)
  int64_t samples = 0;                      // in all recordings
  std::vector<double> times;                // of the first frames (first recording)
  std::vector<std::vector<double>> frames;  // [frame][channel], the first frames
  std::vector<std::string> frame_classes;   // the ground-truth class at each first frame, "" none
  std::vector<std::string> classes;         // every class of the ground truth, first seen first
  size_t labels = 0;
  // What the import would stop with ("--rate: is needed for an array ..."); "" when it
  // would go on to write. The fields above are empty when it is set.
  std::string refusal;
};

// Reads as import_file does and writes nothing; `frames` first frames are kept. The output
// options (out, labels, recording_id) are not looked at. A refusal is returned, not thrown.
ImportPreview preview_import(const FileImportOptions& options, int frames = 10,
                             const std::function<void(double)>& step = {});

}  // namespace tactile

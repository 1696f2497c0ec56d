#pragma once
// Other programs' files into recordings (docs/IMPORT.md): `tactile import` and the workbench's
// File > Import call this one function, so the checks, the refusals (naming the option or the
// place in the file, as the command line's options are named), what is written and where
// are the same wherever an import starts. The ground truth goes into a label store as one
// command (ground_truth_import: importing again replaces it). A preview reads the same way
// and writes nothing.
//
//   long CSV   header, time column, one column per channel; class_column, group_columns
//   wide CSV   wide: one capture per row, with a labels file
//   .npy .npz .json .h5 .mat   an array (dataset / key), classes from class_array, captures; JSON
//              frames given as objects through value_key (and class_key for their classes)
//   .edf .bdf  EDF+/BDF+ signals chosen by label, annotations as labels (io/edf_import.h)
//   .xdf       a numeric stream (stream) resampled to its nominal rate, a markers stream's labels

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tactile {

// The options of `tactile import`, by the names of its flags.
struct FileImportOptions {
  std::string file;               // FILE: .csv/.txt, .npy, .npz, .json, .h5/.hdf5/.hdf, .mat
  std::string layout;             // --layout: a layout id, grid:RxC or strip:N
  std::optional<double> rate_hz;  // --rate (long CSV: from its time column when unset)
  std::string rate_variable;      // --rate-variable: .mat: the scalar variable holding the rate
  bool wide = false;              // --wide
  // Wide CSV only; set when given, and refused without `wide`.
  std::optional<int64_t> samples_per_capture;           // --samples-per-capture
  std::optional<std::string> labels_file;               // --labels-file
  std::optional<std::vector<std::string>> class_names;  // --class-names
  std::string dataset;      // --dataset: a .npz array, an HDF5 dataset, a .mat variable ("s.field")
  std::string key;          // --key: the JSON key of the frames
  std::string value_key;    // --value-key: JSON frames given as objects, the member of each frame
  std::string class_key;    // --class-key: ... and the member of its class
  std::string class_array;  // --class-array: classes per frame or capture in the same file
  bool captures = false;    // --captures: [N][C][S]
  std::string class_column;                // --class-column (long CSV)
  std::vector<std::string> group_columns;  // --group-columns (long CSV): out is a folder
  std::string out;                         // --out: the .h5 file, or the folder with group_columns
  std::string labels;        // --labels: the label store; "" = the ground truth is not stored
  std::string recording_id;  // --recording-id: "" = the output file's stem
  // EDF+ / BDF+ only: the signals by label, in channel order (empty: every ordinary signal), and
  // the length of annotations of zero or unknown duration (unset: they are refused).
  std::vector<std::string> signals;          // --signals
  std::optional<double> annotation_seconds;  // --annotation-seconds
  // Any format: the file's labels stored as this annotator's (replacing their labels of the
  // recording on a second import) instead of the ground truth; "" = the ground truth.
  std::string annotator;  // --annotator
  // XDF only (refused for other files): NAME or type:TYPE; "" = the only candidate.
  std::string stream;   // --stream: the data stream
  std::string markers;  // --markers: the markers stream whose markers become labels
};

// One recording written.
struct ImportedFile {
  std::string path;       // the .h5
  std::string recording;  // its id
  std::string layout;
  int64_t samples = 0, channels = 0;
  double rate_hz = 0.0;
  size_t labels = 0;  // ground-truth labels read for it
};

// "wrote OUT: recording ID, layout L, N samples x C channels at R Hz[, K labels]", the line
// `tactile import` prints per file.
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

// The format an import reads a file as, by its extension: "CSV", ".npy", ".npz", ".json",
// ".h5", ".mat", ".edf", ".bdf", ".xdf"; "" for one it does not read.
std::string import_format_of(const std::string& path);

}  // namespace tactile

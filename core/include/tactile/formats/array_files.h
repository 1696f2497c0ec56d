#pragma once
// Arrays as other programs publish them, read into recordings: NumPy .npy and .npz files,
// JSON arrays of frames, and any numeric dataset of another program's HDF5 file. Every
// reader checks the sizes a file declares against the bytes it holds before it allocates
// anything, and refuses bad input with tactile::Error naming the file and the place (byte,
// entry, index) and what is wrong.
//
// Shapes (docs/IMPORT.md): [T][C] samples of C channels; [T][R][C] frames of an R x C grid
// (channel r * C + c); with `captures`, [N][C][S] captures of C channels and S samples,
// laid end to end (as the wide CSV).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tactile/formats/csv_files.h"
#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

// Numbers (C order) or strings, with their shape.
struct ImportedArray {
  std::vector<int64_t> shape;
  std::vector<double> values;        // numeric arrays
  std::vector<std::string> strings;  // string arrays (class names per frame or capture)
  bool text = false;
  int64_t size() const;  // product of the shape
};

// The most elements one array may declare (2^31: 8 GiB of doubles); more is refused.
inline constexpr int64_t kMaxImportedElements = int64_t{1} << 31;

// A .npy file's bytes (format versions 1-3; little- or big-endian bool, integer and float
// types, fixed-length unicode or byte strings; C or Fortran order). `where` names it.
ImportedArray parse_npy(std::span<const uint8_t> bytes, const std::string& where);
ImportedArray read_npy(const std::string& path);
// The arrays of a .npz file (a zip of .npy files, stored or deflated), by name without
// ".npy", in the archive's order.
std::vector<std::string> npz_names(const std::string& path);
ImportedArray read_npz(const std::string& path, const std::string& name);
// JSON: the top-level array, or the array under `key` ("a.b" for nested objects), of
// numbers nested to any regular depth, or of strings. An array of objects (frames given as
// {"label": "Punch", "data": [[...]]}) is read through `member`: each object's member of that
// name (the frame, or its class); an array of objects without `member` is refused naming the
// members of the first.
ImportedArray read_json_array(const std::string& path, const std::string& key,
                              const std::string& member = "");
// One dataset of an HDF5 file written by any program (numbers, or fixed or variable-length
// strings). The file's structure is walked first, as a MATLAB v7.3 file's is (groups and object
// headers within the file; formats/hdf5_structure.h), and the dataset named is checked against
// what the walk found before libhdf5 reads it.
ImportedArray read_hdf5_dataset(const std::string& path, const std::string& dataset);
// A dataset of an HDF5 file: its path and how refusals describe it.
struct Hdf5Dataset {
  std::string path;       // "/sensors/pressure"
  std::string described;  // "/sensors/pressure 6x4 float64" (printable)
};
// The file's readable datasets (numbers or strings), walked as read_hdf5_dataset walks them;
// empty when the file's groups are of the new style (HDF5 1.8+ superblocks of version 2 or 3),
// which the walk checks but does not list.
std::vector<Hdf5Dataset> hdf5_datasets(const std::string& path);

struct ArrayRecordingOptions {
  double rate_hz = 0.0;  // required
  std::string stream_name = "skin";
  bool captures = false;  // [N][C][S]
  // One class per frame (T) or per capture (N); "" or "none" is no touch. Consecutive
  // frames of one class become one ground-truth label.
  std::vector<std::string> classes;
};

// The array as one stream of the layout. Throws tactile::Error naming `where` when the
// shape does not fit the layout's channels, a value is not finite, or the classes do not
// match the frames.
ImportedRecording recording_from_array(const ImportedArray& array, const SkinLayout& layout,
                                       const ArrayRecordingOptions& options,
                                       const std::string& where);

// Consecutive equal classes (one per sample from `start`, at `rate_hz`) as ground-truth
// labels of region "all", annotator "import"; "" and "none" make none.
std::vector<Label> labels_from_frame_classes(const std::vector<std::string>& classes, double start,
                                             double rate_hz);

}  // namespace tactile

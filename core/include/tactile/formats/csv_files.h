#pragma once
// CSV import and export in the two shapes found in published tactile data sets.
//
// long: a header row, then one row per sample: an optional time column first (named
//       t, time, time_s or timestamp, or simply the first column) and one column per
//       channel of the layout, in the layout's order.
// wide: no header, one capture per row, channel-major (ch0 s0..s{N-1}, ch1 s0.. ...),
//       with a separate labels file holding one class per capture.
//
// Files are read line by line (a 1 GB file is never held in memory as text), numbers
// parsed with std::from_chars, and every bad cell reported as tactile::Error with
// "file.csv:LINE column COLUMN" (both 1-based). NaN and infinite cells are refused.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tactile/io/hdf5_file.h"
#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

struct CsvLongOptions {
  // Sampling rate; without it the rate comes from the time column (1 / median step).
  std::optional<double> rate_hz;
  std::string stream_name = "skin";
  // Whether the first column holds time. Unset: decided from the header, a time
  // column being present when there is one more column than the layout has channels.
  // A file without time column needs rate_hz.
  std::optional<bool> has_time_column;
};

// Time steps further than this fraction from the median step make a stream irregular:
// its time stamps are kept.
inline constexpr double kIrregularStepTolerance = 0.01;

// A long CSV that holds more than samples: a class per row (`class_column`; "" or
// "none" is no touch, consecutive rows of one class become one ground-truth label) and
// grouping columns (`group_columns`, e.g. subject and capture) that split one table into
// recordings, each with its group's values as metadata and id "STEM-VALUE-VALUE". The
// columns other than these are the long shape's (time, then the layout's channels).
struct CsvTableOptions : CsvLongOptions {
  std::string class_column;
  std::vector<std::string> group_columns;
};
struct ImportedRecording;
// Groups in the order they first appear; rows of a group need not be adjacent. Throws
// tactile::Error naming file, line and column (or the option naming a missing column).
std::vector<ImportedRecording> import_csv_table(const std::string& path, const SkinLayout& layout,
                                                const CsvTableOptions& options);

// The table without class and grouping columns: its one recording. Recording id = the
// file's stem, layout id = layout.id, one stream with the layout's channel names and units.
// Throws tactile::Error naming file, line and column.
Recording import_csv_long(const std::string& path, const SkinLayout& layout,
                          const CsvLongOptions& options);

struct CsvWideOptions {
  int64_t samples_per_capture = 0;
  std::string labels_path;
  // Vocabulary for the labels file: a line is a class name or a 0-based index into it.
  // Empty: the layout's classes; when those are empty too, every line is a class name.
  std::vector<std::string> class_names;
  double rate_hz = 0.0;
  std::string stream_name = "skin";
};

struct ImportedRecording {
  Recording recording;
  std::vector<Label> labels;  // ground truth, one per capture, recording = recording.id
};

// Captures laid end to end in one stream; capture k gets the ground-truth label
// [k*N/rate, (k+1)*N/rate) on region "all", annotator "import".
ImportedRecording import_csv_wide(const std::string& path, const SkinLayout& layout,
                                  const CsvWideOptions& options);

// Long CSV of one stream (empty name: the first stream): header "time_s,<channels>",
// then the time of each sample and its values in shortest round-trip form, so export
// then import gives back the same bits. Written to a temporary file, then renamed.
void export_csv_long(const std::string& path, const Recording& recording,
                     const std::string& stream = {});
// The same from an open file, reading one block of samples at a time, so an hour of
// a large skin is exported without loading it.
void export_csv_long(const std::string& path, const RecordingFile& file,
                     const std::string& stream = {});

}  // namespace tactile

#pragma once
// EDF+ and BDF+ recordings (and plain EDF/BDF) read with EDFlib (Debian libedf-dev) into one
// stream of a layout, their annotations into labels (docs/IMPORT.md).
//
// Signals are chosen by label (EDF pads labels with spaces; they are matched trimmed); the
// chosen signals must share one sample rate (samples per data record / record duration) and be
// as many as the layout has channels. Values are the physical ones (digital scaled by the
// signal's physical and digital range), units the signals' physical dimensions.
//
// Before the file reaches EDFlib, the header is read here and every size it declares (header
// bytes, samples per record, data records) is checked against the bytes the file holds, and
// EDF+D is refused (EDFlib does not give the onsets of its data records, so the gaps between
// them cannot be placed). EDFlib 1.23 refuses these files too, but as "format errors" without
// saying where; the checks here name the field and its byte offset, and do not depend on the
// library's version to keep a lying header from sizing an allocation.

#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/csv_files.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

struct EdfImportOptions {
  // Signal labels in the stream's channel order; empty: every ordinary signal (the annotation
  // signals "EDF Annotations" / "BDF Annotations" are never samples).
  std::vector<std::string> signals;
  // The length given to annotations of zero or unknown duration; unset, such an annotation is
  // refused with its onset and text.
  std::optional<double> annotation_seconds;
  std::string stream_name = "skin";
};

// The file as one stream of the layout (channel names the layout's, units the file's) and its
// annotations as ground-truth labels (class = the text trimmed, region "all", annotator
// "import", [onset, onset + duration) clipped to the data's end). An annotation at or after the
// data's end ("Recording ends" at the last instant), or one clipped to less than a sample, is
// no label: it is dropped and named in the metadata "dropped_labels". Metadata: imported_from,
// edf_format, edf_signals (the labels read, in order), start_time (ISO 8601, as the file states
// it, no time zone) and the patient and recording fields the file fills. Throws tactile::Error
// naming the file and the place (byte offset, signal, annotation) and what is wrong, with the
// header's bytes quoted printable (\xFE for a byte that is no text).
ImportedRecording import_edf(const std::string& path, const SkinLayout& layout,
                             const EdfImportOptions& options = {});

// What import_edf checks before EDFlib opens the file, on its first bytes and its size: the
// version field, EDF+D, the signal count, the header size, every signal's samples per record
// and the data records against `file_size`. `header` holds at least the main header and the
// signal headers when the file has them (fewer bytes are refused). Throws tactile::Error
// naming `where` and the byte offset.
void check_edf_header(const std::vector<unsigned char>& header, long long file_size,
                      const std::string& where);

}  // namespace tactile

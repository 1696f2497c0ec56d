#pragma once
// Internal to the dataset writers (dataset.cpp, dataset_arff.cpp): the checks a dataset
// passes before any byte is written, the number format, and the temp-file-then-rename
// write that leaves no partial file behind.

#include <string>

#include "tactile/features/dataset.h"

namespace tactile::dataset_files {

// The fixed columns after the features, in the CSV's order.
inline constexpr const char* kClassColumn = "class";
inline constexpr const char* kSubjectColumn = "subject";
inline constexpr const char* kRecordingColumn = "recording";
inline constexpr const char* kSegmentIdColumn = "segment_id";

// Throws tactile::Error(path, ...) when the per-row vectors disagree with the row count,
// the dataset has no rows, a column name is empty or repeated, a class is empty, or a
// feature value is NaN or infinite (naming its row and column).
void check_dataset(const std::string& path, const Dataset& dataset);

// Writes `text` to a temporary file beside `path`, then renames it over `path`; on any

}  // namespace tactile::dataset_files

#pragma once
// What the array formats (NumPy, JSON, HDF5, MATLAB) share: the options of an array's time and
// classes, and an array made into a recording of the layout.

#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/array_files.h"
#include "tactile/formats/importer.h"

namespace tactile::formats {

// --rate (required unless `rate_optional`, when another option gives it), --class-array
// (`class_array_help`: what names the classes in this format) and --captures.
std::vector<ImportOption> array_options(const std::string& class_array_help,
                                        const std::string& class_array_hint);

// The file's extension in lower case, with the dot.
std::string lower_extension(const std::string& path);

// --rate, refused as missing: an array carries no time.
double required_rate(const ImportValues& values);

// The array (and its classes, when given: names, or indices into the layout's classes) as one
// recording named after the file. `where` names the array in errors ("file.npz:pressure").
ImportRead array_recording(const std::string& path, const SkinLayout& layout, double rate_hz,
                           bool captures, const ImportedArray& array,
                           const std::optional<ImportedArray>& classes, const std::string& where,
                           const std::string& described);

// The refusal of CSV's --class-column by an array format: where its classes are named instead.
std::string class_column_refusal(const std::string& instead);

}  // namespace tactile::formats

#pragma once
// The built-in importers, one file each in this folder; builtin_importers.cpp lists them.

#include <memory>

#include "tactile/formats/importer.h"

namespace tactile::formats {

std::unique_ptr<RecordingImporter> csv_importer();
std::unique_ptr<RecordingImporter> numpy_importer();
std::unique_ptr<RecordingImporter> json_importer();
std::unique_ptr<RecordingImporter> hdf5_importer();
std::unique_ptr<RecordingImporter> mat_importer();
std::unique_ptr<RecordingImporter> edf_importer();
std::unique_ptr<RecordingImporter> xdf_importer();

}  // namespace tactile::formats

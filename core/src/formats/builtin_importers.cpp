// The formats `tactile import` reads (docs/IMPORT.md). A new format is one more file in this
// folder and one more row here, or register_importer from the program or test that brings it.
#include "builtin.h"

namespace tactile {

std::vector<std::unique_ptr<RecordingImporter>> builtin_importers() {
  std::vector<std::unique_ptr<RecordingImporter>> list;
  list.push_back(formats::csv_importer());
  list.push_back(formats::numpy_importer());
  list.push_back(formats::json_importer());
  list.push_back(formats::hdf5_importer());
  list.push_back(formats::mat_importer());
  list.push_back(formats::edf_importer());
  list.push_back(formats::xdf_importer());
  return list;
}

}  // namespace tactile

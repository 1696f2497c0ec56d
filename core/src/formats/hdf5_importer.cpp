// HDF5: one dataset of a file any program wrote (formats/array_files.h), its structure walked
// first as a MATLAB v7.3 file's is.
#include <optional>

#include "array_importers.h"
#include "builtin.h"
#include "tactile/error.h"

namespace tactile::formats {

namespace {

class Hdf5Importer : public ArrayImporter {
 public:
  Hdf5Importer()
      : ArrayImporter({"an HDF5 dataset", "the dataset of the classes",
                       "--class-array (an array or dataset of the same file)"}) {}
  std::string name() const override { return "HDF5"; }
  std::vector<std::string> extensions() const override { return {".h5", ".hdf5", ".hdf"}; }
  bool recognises(const std::string& bytes) const override {
    return bytes.rfind(std::string("\x89HDF\r\n\x1a\n", 8), 0) == 0;
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    const double rate_hz = required_rate(values);
    const std::string dataset = values.text("--dataset");
    if (dataset.empty()) {
      // The walk that checks the file lists its datasets (a damaged file is refused here).
      std::string known;
      for (const Hdf5Dataset& readable : hdf5_datasets(path))
        known += (known.empty() ? "" : ", ") + readable.described;
      throw Error("--dataset", "names the dataset of " + path + " to read (" +
                                   (known.empty() ? "e.g. /data/pressure" : "it holds " + known) +
                                   ")");
    }
    const ImportedArray array = read_hdf5_dataset(path, dataset);
    std::optional<ImportedArray> classes;
    if (!values.text("--class-array").empty())
      classes = read_hdf5_dataset(path, values.text("--class-array"));
    return array_recording(path, layout, rate_hz, values.on("--captures"), array, classes,
                           path + ":" + dataset, ".h5 array");
  }

 protected:
  std::vector<ImportOption> own_options() const override {
    return {{"--dataset", ImportOption::Kind::kText,
             "The dataset to read (required, e.g. /data/pressure)",
             "the dataset, e.g. /data/pressure", "", ""}};
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> hdf5_importer() { return std::make_unique<Hdf5Importer>(); }

}  // namespace tactile::formats

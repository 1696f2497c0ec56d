// NumPy: a .npy array, or one array of a .npz archive (formats/array_files.h).
#include <optional>

#include "array_importers.h"
#include "builtin.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::formats {

namespace {

class NumpyImporter : public ArrayImporter {
 public:
  NumpyImporter()
      : ArrayImporter({"a .npz array", "the array of the classes",
                       "--class-array (an array of the same file)"}) {}
  std::string name() const override { return "NumPy"; }
  std::vector<std::string> extensions() const override { return {".npy", ".npz"}; }
  bool recognises(const std::string& bytes) const override {
    return bytes.rfind("\x93NUMPY", 0) == 0;
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    const double rate_hz = required_rate(values);
    // A file without the extension was recognised by the .npy magic.
    const bool archive = lower_extension(path) == ".npz";
    const std::string dataset = values.text("--dataset");
    const std::string class_array = values.text("--class-array");
    if (!archive && (!dataset.empty() || !class_array.empty()))
      throw Error(dataset.empty() ? "--class-array" : "--dataset",
                  "a .npy file holds one array; name arrays of a .npz");
    std::string where = path;
    ImportedArray array;
    if (!archive) {
      array = read_npy(path);
    } else {
      const std::string chosen = dataset.empty() ? only_array(path) : dataset;
      array = read_npz(path, chosen);
      if (!dataset.empty()) where += ":" + dataset;
    }
    std::optional<ImportedArray> classes;
    if (!class_array.empty()) classes = read_npz(path, class_array);
    return array_recording(path, layout, rate_hz, values.on("--captures"), array, classes, where,
                           archive ? ".npz array" : ".npy array");
  }

 private:
  static std::string only_array(const std::string& path) {
    const std::vector<std::string> names = npz_names(path);
    if (names.size() != 1)
      throw Error("--dataset", path + " holds " + std::to_string(names.size()) + " arrays (" +
                                   joined(names) + "): name one");
    return names.front();
  }

 protected:
  std::vector<ImportOption> own_options() const override {
    return {{"--dataset", ImportOption::Kind::kText,
             "The .npz array to read (default: the archive's one array)",
             "the array (default: the only one)", "", ""}};
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> numpy_importer() { return std::make_unique<NumpyImporter>(); }

}  // namespace tactile::formats

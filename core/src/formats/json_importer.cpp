// JSON: an array of frames, at the top level or under a key, of numbers or of objects whose
// members hold the frame and its class (formats/array_files.h).
#include <optional>

#include "array_importers.h"
#include "builtin.h"
#include "tactile/error.h"

namespace tactile::formats {

namespace {

class JsonImporter : public ArrayImporter {
 public:
  JsonImporter()
      : ArrayImporter({"a JSON key", "the key of the classes",
                       "--class-key (a member of each frame object) or --class-array (a key)"}) {}
  std::string name() const override { return "JSON"; }
  std::vector<std::string> extensions() const override { return {".json"}; }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    const std::string key = values.text("--key"), value_key = values.text("--value-key");
    const std::string class_key = values.text("--class-key");
    const std::string class_array = values.text("--class-array");
    if (!class_key.empty() && !class_array.empty())
      throw Error("--class-key", "or --class-array, not both");
    const double rate_hz = required_rate(values);
    const ImportedArray array = read_json_array(path, key, value_key);
    std::optional<ImportedArray> classes;
    if (!class_key.empty())
      classes = read_json_array(path, key, class_key);
    else if (!class_array.empty())
      classes = read_json_array(path, class_array, "");
    std::string where = path;
    if (!key.empty()) where += " key " + key;
    if (!value_key.empty()) where += " member " + value_key;
    return array_recording(path, layout, rate_hz, values.on("--captures"), array, classes, where,
                           ".json array");
  }

 protected:
  std::vector<ImportOption> own_options() const override {
    return {{"--key", ImportOption::Kind::kText,
             "The JSON key holding the frames (a.b for nested; default: the top level)",
             "a.b (default: the top level)", "", ""},
            {"--value-key", ImportOption::Kind::kText,
             "Frames given as objects ({\"label\": ..., \"data\": [...]}): the member holding each "
             "frame (e.g. data)",
             "frames as objects: the member of each frame, e.g. data", "", ""},
            {"--class-key", ImportOption::Kind::kText,
             "Frames given as objects: the member holding each frame's class (e.g. label)",
             "frames as objects: the member of each class, e.g. label", "", ""}};
  }
};

}  // namespace

std::unique_ptr<RecordingImporter> json_importer() { return std::make_unique<JsonImporter>(); }

}  // namespace tactile::formats

#include "array_importers.h"

#include <cctype>
#include <filesystem>

#include "tactile/error.h"

namespace tactile::formats {

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

std::vector<ImportOption> ArrayImporter::options() const {
  std::vector<ImportOption> list = own_options();
  list.push_back({"--rate", ImportOption::Kind::kNumber,
                  "Sampling rate in Hz (an array carries no time)", "Hz", "", ""});
  list.push_back({"--class-array", ImportOption::Kind::kText,
                  "Classes per frame (or per capture) in the same file: " + classes_.help +
                      "; names, or indices into the layout's classes; none/empty: no touch",
                  classes_.hint, "", ""});
  list.push_back({"--captures", ImportOption::Kind::kSwitch,
                  "The array is [captures][channels][samples]: captures laid end to end",
                  "[captures][channels][samples]", "", ""});
  return list;
}

std::string ArrayImporter::refusal_of(const std::string& flag) const {
  if (flag != "--class-column") return {};
  return "is for CSV tables; the classes of an array file are named by " + classes_.instead;
}

double required_rate(const ImportValues& values) {
  const std::optional<double> rate = values.number("--rate");
  if (!rate) throw Error("--rate", "is needed for an array (it carries no time)");
  return *rate;
}

ImportRead array_recording(const std::string& path, const SkinLayout& layout, double rate_hz,
                           bool captures, const ImportedArray& array,
                           const std::optional<ImportedArray>& classes, const std::string& where,
                           const std::string& described) {
  ArrayRecordingOptions options;
  options.rate_hz = rate_hz;
  options.captures = captures;
  if (classes) {
    if (classes->text) {
      options.classes = classes->strings;
    } else {
      for (double value : classes->values) {
        // Class indices into the layout's vocabulary (or the number as the name).
        const auto index = static_cast<int64_t>(value);
        options.classes.push_back(index >= 0 &&
                                          index < static_cast<int64_t>(layout.classes.size()) &&
                                          value == static_cast<double>(index)
                                      ? layout.classes[static_cast<size_t>(index)]
                                      : std::to_string(index));
      }
    }
  }
  ImportedRecording imported = recording_from_array(array, layout, options, where);
  imported.recording.id = std::filesystem::path(path).stem().string();
  imported.recording.metadata["imported_from"] = std::filesystem::path(path).filename().string();
  ImportRead read;
  read.recordings.push_back(std::move(imported));
  read.described = described;
  read.shape = array.shape;
  return read;
}

}  // namespace tactile::formats

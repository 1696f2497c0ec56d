#include "toy_format.h"

#include <fstream>
#include <memory>
#include <sstream>

#include "tactile/error.h"
#include "tactile/formats/array_files.h"
#include "tactile/formats/importer.h"

namespace tactile::test {

namespace {

class ToyImporter : public RecordingImporter {
 public:
  std::string name() const override { return kToyFormat; }
  std::vector<std::string> extensions() const override { return {".toy"}; }
  bool recognises(const std::string& bytes) const override { return bytes.rfind("toy ", 0) == 0; }
  std::vector<ImportOption> options() const override {
    using Kind = ImportOption::Kind;
    return {{"--gain", Kind::kNumber, "each value multiplied by this (default 1)",
             "a factor (default 1)", "", ""},
            {"--skip", Kind::kCount, "frames left out at the start", "frames", "", ""},
            {"--no-classes", Kind::kSwitch, "the classes of the frames ignored",
             "the classes ignored", "", ""}};
  }

  ImportRead read(const std::string& path, const SkinLayout& layout,
                  const ImportValues& values) const override {
    std::ifstream in(path);
    std::string word;
    double rate = 0.0;
    if (!(in >> word >> rate) || word != "toy" || rate <= 0.0)
      throw Error(path + ":1", "not \"toy RATE\"");
    const double gain = values.number("--gain").value_or(1.0);
    const int64_t skip = values.count("--skip").value_or(0);
    ImportedArray array;
    ArrayRecordingOptions options;
    options.rate_hz = rate;
    std::string line;
    std::getline(in, line);
    int64_t frames = 0;
    for (int number = 2; std::getline(in, line); ++number) {
      if (line.empty()) continue;
      if (number - 2 < skip) continue;
      std::istringstream fields(line);
      std::string class_name;
      for (size_t channel = 0; channel < layout.channels.size(); ++channel) {
        double value = 0.0;
        if (!(fields >> value))
          throw Error(path + ":" + std::to_string(number),
                      "a frame needs " + std::to_string(layout.channels.size()) + " numbers");
        array.values.push_back(gain * value);
      }
      fields >> class_name;
      options.classes.push_back(values.on("--no-classes") ? "" : class_name);
      ++frames;
    }
    array.shape = {frames, static_cast<int64_t>(layout.channels.size())};
    if (values.on("--no-classes")) options.classes.clear();
    ImportRead read;
    read.recordings.push_back(recording_from_array(array, layout, options, path));
    read.recordings.back().recording.id = "toy";
    read.described = "toy text";
    read.shape = array.shape;
    return read;
  }
};

}  // namespace

void register_toy_format() { register_importer(std::make_unique<ToyImporter>()); }

std::string toy_file_text(int frames, int channels) {
  std::ostringstream text;
  text << "toy 20\n";
  for (int k = 0; k < frames; ++k) {
    for (int channel = 0; channel < channels; ++channel) text << k + channel << " ";
    if (k >= frames / 2) text << "tap";
    text << "\n";
  }
  return text.str();
}

}  // namespace tactile::test

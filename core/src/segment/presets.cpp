#include "tactile/segment/presets.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"

namespace tactile {

std::string segmenter_presets_path(const std::string& label_database) {
  const std::filesystem::path folder = std::filesystem::path(label_database).parent_path();
  return (folder / "segmenter-presets.json").string();
}

std::vector<SegmenterPreset> read_segmenter_presets(const std::string& path) {
  std::vector<SegmenterPreset> presets;
  if (!std::filesystem::exists(path)) return presets;
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot read the segmenter presets");
  std::stringstream text;
  text << in.rdbuf();
  try {
    const nlohmann::json document = nlohmann::json::parse(text.str());
    if (!document.is_object()) throw Error(path, "is not a JSON object of presets");
    for (const auto& [name, value] : document.items()) {
      SegmenterPreset preset;
      preset.name = name;
      preset.method = value.at("method").get<std::string>();
      preset.params = value.at("params").get<std::string>();
      preset.fitted_to = value.value("fitted_to", "");
      preset.held_out_event_f1 = value.value("held_out_event_f1", 0.0);
      preset.touches = value.value("touches", int64_t{0});
      presets.push_back(std::move(preset));
    }
  } catch (const nlohmann::json::exception& error) {
    throw Error(path, std::string("damaged segmenter presets (") + error.what() +
                          "): fix or remove the file");
  }
  return presets;
}

std::optional<SegmenterPreset> find_segmenter_preset(const std::string& path,
                                                     const std::string& name) {
  for (SegmenterPreset& preset : read_segmenter_presets(path))
    if (preset.name == name) return std::move(preset);
  return std::nullopt;
}

void save_segmenter_preset(const std::string& path, const SegmenterPreset& preset) {
  if (preset.name.empty()) throw Error("preset", "needs a name");
  nlohmann::json document = nlohmann::json::object();
  for (const SegmenterPreset& old : read_segmenter_presets(path))
    document[old.name] = {{"method", old.method},
                          {"params", old.params},
                          {"fitted_to", old.fitted_to},
                          {"held_out_event_f1", old.held_out_event_f1},
                          {"touches", old.touches}};
  document[preset.name] = {{"method", preset.method},
                           {"params", preset.params},
                           {"fitted_to", preset.fitted_to},
                           {"held_out_event_f1", preset.held_out_event_f1},
                           {"touches", preset.touches}};
  write_file_atomically(path, document.dump(2) + "\n", "segmenter presets");
}

}  // namespace tactile

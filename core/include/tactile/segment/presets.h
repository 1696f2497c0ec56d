#pragma once
// Named segmenter presets (a fitted segmenter, `tactile segment --fit-to ... --preset NAME`):
// a JSON file beside a label store, `segmenter-presets.json` in the store's folder, one
// object per name: {"method", "params", "fitted_to", "held_out_event_f1", "touches"}.
// `tactile segment --preset NAME` and the workbench's G run a preset's method with its
// parameters. Written atomically; a damaged file is refused by name, never overwritten.

#include <optional>
#include <string>
#include <vector>

namespace tactile {

struct SegmenterPreset {
  std::string name;
  std::string method;
  std::string params;     // "key=value,..."
  std::string fitted_to;  // the lane it was fitted to
  double held_out_event_f1 = 0.0;
  int64_t touches = 0;
};

// The presets file that belongs to a label store.
std::string segmenter_presets_path(const std::string& label_database);
// Every preset in the file, by name; none when the file is missing.
std::vector<SegmenterPreset> read_segmenter_presets(const std::string& path);
// The named preset, or nothing.
std::optional<SegmenterPreset> find_segmenter_preset(const std::string& path,
                                                     const std::string& name);
// Adds or replaces the preset of that name.
void save_segmenter_preset(const std::string& path, const SegmenterPreset& preset);

}  // namespace tactile

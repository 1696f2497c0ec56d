// The table of segmenters: one line per method, name -> function. Adding a method is one
// #include and one line in method_table().
#include <algorithm>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/segment/adaptive.h"
#include "tactile/segment/excitation.h"
#include "tactile/segment/frame_edge.h"
#include "tactile/segment/proximity.h"
#include "tactile/segment/scenario.h"
#include "tactile/segment/segmenter.h"
#include "tactile/segment/threshold.h"

namespace tactile {

namespace {

using SegmenterFunction = std::vector<Label> (*)(const Recording&, const SkinLayout&,
                                                 const Parameters&);

struct MethodEntry {
  const char* name;
  SegmenterFunction segment;
};

// Listed order is the order error messages and `--help` name the methods.
const std::vector<MethodEntry>& method_table() {
  static const std::vector<MethodEntry> table = {
      // {"name", segment_name},  (include "tactile/segment/name.h")
      {"proximity", segment_proximity},   {"threshold", segment_threshold},
      {"frame-edge", segment_frame_edge}, {"scenario", segment_scenario},
      {"excitation", segment_excitation}, {"adaptive", segment_adaptive},
  };
  return table;
}

}  // namespace

std::vector<std::string> segmenter_methods() {
  std::vector<std::string> names;
  for (const MethodEntry& entry : method_table()) names.emplace_back(entry.name);
  return names;
}

std::vector<Label> segment_recording(const std::string& method, const Recording& recording,
                                     const SkinLayout& layout, const Parameters& parameters) {
  const auto& table = method_table();
  const auto found = std::find_if(table.begin(), table.end(),
                                  [&](const MethodEntry& entry) { return method == entry.name; });
  if (found == table.end()) {
    std::string known;
    for (const MethodEntry& entry : table)
      known += (known.empty() ? "" : ", ") + std::string(entry.name);
    throw Error("method " + method,
                "unknown segmenter (known: " + (known.empty() ? "none" : known) + ")");
  }
  std::vector<Label> labels = found->segment(recording, layout, parameters);
  // Every segmenter's labels carry the same provenance, whoever wrote the method, so the
  // label store can tell them apart from manual and ground-truth labels (segmenter.h).
  for (Label& label : labels) {
    label.source = LabelSource::kSegmenter;
    label.annotator = "segmenter:" + method;
    if (label.recording.empty()) label.recording = recording.id;
  }
  return labels;
}

}  // namespace tactile

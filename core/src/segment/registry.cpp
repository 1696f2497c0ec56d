// The table of segmenters: one line per method, name -> function. Adding a method is one
// #include and one line in method_table().
#include <algorithm>
#include <functional>
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
// A method that reads a source a channel at a time, never holding the whole recording.
using SourceSegmenterFunction = std::vector<Label> (*)(const SampleSource&, const SkinLayout&,
                                                       const Parameters&,
                                                       const std::function<void(double)>&);

struct MethodEntry {
  const char* name;
  SegmenterFunction segment;
  SourceSegmenterFunction from_source = nullptr;  // null: the recording is read whole first
};

// Listed order is the order error messages and `--help` name the methods.
const std::vector<MethodEntry>& method_table() {
  static const std::vector<MethodEntry> table = {
      // {"name", segment_name},  (include "tactile/segment/name.h")
      {"proximity", segment_proximity},   {"threshold", segment_threshold},
      {"frame-edge", segment_frame_edge}, {"scenario", segment_scenario},
      {"excitation", segment_excitation}, {"adaptive", segment_adaptive, segment_adaptive},
  };
  return table;
}

const MethodEntry& method_entry(const std::string& method) {
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
  return *found;
}

// Every segmenter's labels carry the same provenance, whoever wrote the method, so the label
// store can tell them apart from manual and ground-truth labels (segmenter.h).
std::vector<Label> with_provenance(std::vector<Label> labels, const std::string& method,
                                   const std::string& recording) {
  for (Label& label : labels) {
    label.source = LabelSource::kSegmenter;
    label.annotator = "segmenter:" + method;
    if (label.recording.empty()) label.recording = recording;
  }
  return labels;
}

}  // namespace

std::vector<std::string> segmenter_methods() {
  std::vector<std::string> names;
  for (const MethodEntry& entry : method_table()) names.emplace_back(entry.name);
  return names;
}

std::vector<Label> segment_recording(const std::string& method, const Recording& recording,
                                     const SkinLayout& layout, const Parameters& parameters) {
  return with_provenance(method_entry(method).segment(recording, layout, parameters), method,
                         recording.id);
}

std::vector<Label> segment_source(const std::string& method, const SampleSource& source,
                                  const SkinLayout& layout, const Parameters& parameters,
                                  const std::function<void(double)>& step) {
  const MethodEntry& entry = method_entry(method);
  if (entry.from_source)
    return with_provenance(entry.from_source(source, layout, parameters, step), method,
                           source.info().recording_id);
  const Recording recording = read_all(source, step);
  return with_provenance(entry.segment(recording, layout, parameters), method, recording.id);
}

}  // namespace tactile

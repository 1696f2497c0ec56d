// The table of feature pipelines: one line per descriptor set, name -> factory. Adding a
// pipeline is one #include and one line in pipeline_table(); nothing else in the app changes.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/features/generic.h"

namespace tactile {

namespace {

using ExtractorFactory = std::unique_ptr<FeatureExtractor> (*)(const Parameters&);

struct PipelineEntry {
  const char* name;
  ExtractorFactory make;
};

// Listed order is the order `tactile features --list` prints.
const std::vector<PipelineEntry>& pipeline_table() {
  static const std::vector<PipelineEntry> table = {
      // {"name", make_name_extractor},  (include "tactile/features/name.h")
      {"generic", make_generic_extractor},
  };
  return table;
}

}  // namespace

std::vector<std::string> feature_pipelines() {
  std::vector<std::string> names;
  for (const PipelineEntry& entry : pipeline_table()) names.emplace_back(entry.name);
  return names;
}

std::unique_ptr<FeatureExtractor> make_feature_extractor(const std::string& name,
                                                         const Parameters& parameters) {
  const auto& table = pipeline_table();
  const auto found = std::find_if(table.begin(), table.end(),
                                  [&](const PipelineEntry& entry) { return name == entry.name; });
  if (found == table.end()) {
    std::string known;
    for (const PipelineEntry& entry : table)
      known += (known.empty() ? "" : ", ") + std::string(entry.name);
    throw Error("pipeline " + name,
                "unknown feature pipeline (known: " + (known.empty() ? "none" : known) + ")");
  }
  return found->make(parameters);
}

}  // namespace tactile

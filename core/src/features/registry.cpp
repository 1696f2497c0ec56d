// The table of feature pipelines: one line per descriptor set, name -> factory. Adding a
// pipeline is one #include and one line in pipeline_table(); nothing else in the app changes.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/features/flux.h"
#include "tactile/features/fur.h"
#include "tactile/features/generic.h"
#include "tactile/features/kaboli.h"
#include "tactile/features/koo.h"
#include "tactile/features/naya.h"
#include "tactile/features/robovie_xcorr.h"
#include "tactile/features/silvera_tawil.h"
#include "tactile/features/tsa_event.h"

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
      {"kaboli", make_kaboli_extractor},
      {"naya", make_naya_extractor},
      {"silvera_tawil", make_silvera_tawil_extractor},
      {"koo", make_koo_extractor},
      {"tsa_event", make_tsa_event_extractor},
      {"fur", make_fur_extractor},
      {"robovie_xcorr", make_robovie_xcorr_extractor},
      {"flux", make_flux_extractor},
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

std::string skin_pipeline(const std::string& layout_id) {
  // Each paper's own descriptor for the skin it built.
  static const std::pair<const char*, const char*> kOwn[] = {
      {"nao", "kaboli"}, {"tsa", "tsa_event"}, {"fur", "fur"},
      {"robovie", "robovie_xcorr"}, {"flux", "flux"}};
  for (const auto& [layout, pipeline] : kOwn)
    if (layout_id == layout) return pipeline;
  return "generic";
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

std::string effective_pipeline_parameters(const std::string& name, const std::string& parameters,
                                          const std::string& where) {
  const Parameters given = Parameters::parse(parameters, where);
  make_feature_extractor(name, given);
  for (const auto& [key, value] : given.answered())
    if (value.find_first_of(",=") != std::string::npos)
      throw Error(where, key + "=" + value + ": a value with ',' or '=' cannot be recorded");
  return given.answered_text();
}

}  // namespace tactile

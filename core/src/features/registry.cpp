// The table of feature pipelines: one line per descriptor set, name -> factory. A pipeline
// of this library is one #include and one line in pipeline_table(); one brought by a program
// or a test (a new skin's) is registered with register_feature_pipeline.
#include <algorithm>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/features/flux.h"
#include "tactile/features/fur.h"
#include "tactile/features/generic.h"
#include "tactile/features/grid.h"
#include "tactile/features/kaboli.h"
#include "tactile/features/koo.h"
#include "tactile/features/naya.h"
#include "tactile/features/raw.h"
#include "tactile/features/robovie_xcorr.h"
#include "tactile/features/rocket.h"
#include "tactile/features/silvera_tawil.h"
#include "tactile/features/stack.h"
#include "tactile/features/tsa_event.h"
#include "tactile/text.h"

namespace tactile {

namespace {

struct PipelineEntry {
  std::string name;
  ExtractorFactory make;
};

// Listed order is the order `tactile features --list` prints.
struct PipelineTable {
  std::mutex mutex;
  std::vector<PipelineEntry> entries;
};

PipelineTable& pipeline_table() {
  static PipelineTable table{
      {},
      {
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
          {"raw", make_raw_extractor},
          {"rocket", make_rocket_extractor},
          {"grid", make_grid_extractor},
          {"auto", make_auto_pipeline_extractor},
      }};
  return table;
}

// The entry's factory, copied under the lock (a registration may grow the table meanwhile).
ExtractorFactory find_factory(const std::string& name) {
  PipelineTable& table = pipeline_table();
  const std::lock_guard lock(table.mutex);
  for (const PipelineEntry& entry : table.entries)
    if (entry.name == name) return entry.make;
  return nullptr;
}

}  // namespace

std::vector<std::string> feature_pipelines() {
  PipelineTable& table = pipeline_table();
  const std::lock_guard lock(table.mutex);
  std::vector<std::string> names;
  for (const PipelineEntry& entry : table.entries) names.push_back(entry.name);
  return names;
}

void register_feature_pipeline(const std::string& name, ExtractorFactory make) {
  if (name.empty() || !make) throw Error("pipeline " + name, "needs a name and a factory");
  PipelineTable& table = pipeline_table();
  const std::lock_guard lock(table.mutex);
  for (PipelineEntry& entry : table.entries)
    if (entry.name == name) {
      entry.make = std::move(make);
      return;
    }
  table.entries.push_back({name, std::move(make)});
}

std::unique_ptr<FeatureExtractor> make_feature_extractor(const std::string& name,
                                                         const Parameters& parameters) {
  if (name.find(kStackSeparator) != std::string::npos)
    return make_stack_extractor(name, parameters);
  const ExtractorFactory make = find_factory(name);
  if (!make)
    throw Error("pipeline " + name,
                "unknown feature pipeline (known: " + joined(feature_pipelines()) + ")");
  return make(parameters);
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

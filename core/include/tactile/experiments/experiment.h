#pragma once
// Presets that rerun each paper's experiment end to end (simulate when no data is
// given, segment, extract, train, test) and report tables shaped like the paper's,
// with the paper's reported figure beside ours.

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tactile::experiments {

struct ExperimentOptions {
  std::string data_dir;  // recordings + labels.db of the skin; empty: simulate into work_dir
  std::string work_dir;  // where simulated data and intermediate files go (created)
  uint64_t seed = 1;
  bool quick = false;  // fewer subjects/repetitions, for tests and smoke runs
  std::function<void(const std::string& stage, int done, int total)> progress;
};

// A table shaped like the paper's: one row per class (or condition), columns such as
// "ours %" and "paper %" side by side.
struct ReportTable {
  std::string title;                           // e.g. "Table 5: location, stationary"
  std::vector<std::string> columns;            // header cells
  std::vector<std::vector<std::string>> rows;  // cells as printed
  std::string note;                            // one paragraph under the table
};

struct ExperimentReport {
  std::string name;   // "kaboli-location"
  std::string paper;  // "Kaboli et al., Table 5"
  std::vector<ReportTable> tables;
  nlohmann::json
      json;  // machine-readable: at least {"accuracy": ..., "paper_accuracy": ...} per table
};

using ExperimentRunner = std::function<ExperimentReport(const ExperimentOptions&)>;

// kaboli-location, kaboli-motion, kaboli-multitouch, kaboli-em, kaboli-compare,
// tsa-classifiers, fur-ml, robovie-clafic, flux-som.
std::vector<std::string> experiment_names();
// Throws tactile::Error naming an unknown experiment.
ExperimentReport run_experiment(const std::string& name, const ExperimentOptions& options);
// Fixed-width text tables with titles and notes.
std::string format_report(const ExperimentReport& report);

}  // namespace tactile::experiments

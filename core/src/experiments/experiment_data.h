#pragma once
// Shared by the experiment runners: the labelled corpus of one skin (simulated into the
// work folder, or read from --data), and small formatting helpers for report tables.

#include <string>
#include <vector>

#include "tactile/experiments/experiment.h"
#include "tactile/features/dataset.h"
#include "tactile/sim/simulator.h"

namespace tactile::experiments {

// Feature rows of every ground-truth segment of one skin. With options.data_dir empty the
// skin is first simulated into options.work_dir/<skin> with `simulation`; otherwise the
// recordings and labels.db of options.data_dir are used as they are. Stages are reported
// through options.progress. Throws tactile::Error when the corpus is unreadable or empty.
Dataset experiment_dataset(const ExperimentOptions& options, const std::string& skin,
                           const SimulationOptions& simulation, const std::string& pipeline);

// Class index per row, classes numbered in first-seen order (as evaluate() numbers them).
std::vector<int> class_indices(const Dataset& dataset, const std::vector<std::string>& classes);

// "81.5": a fraction as a percentage with one decimal.
std::string percent_text(double fraction);

// Calls options.progress when it is set.
void report_progress(const ExperimentOptions& options, const std::string& stage, int done,
                     int total);

}  // namespace tactile::experiments

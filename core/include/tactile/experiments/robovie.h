#pragma once
// The Robovie-IIF piezo-skin paper (file 003) rerun end to end.

#include "tactile/experiments/experiment.h"

namespace tactile::experiments {

// `robovie-clafic`: KNN (k = 3) leave-one-out against CLAFIC at (C1, C2) in {1, 0.15} x
// {0, 1, 2}: per-class recognition and false-alarm rates and sensor-bank sizes (Figs 9-10,
// spec §4.9-4.11).
ExperimentReport run_robovie_clafic(const ExperimentOptions& options);

}  // namespace tactile::experiments

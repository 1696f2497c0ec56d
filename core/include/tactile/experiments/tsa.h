#pragma once
// The event-triggered capacitive TSA paper (file 001) rerun end to end.

#include "tactile/experiments/experiment.h"

namespace tactile::experiments {

// `tsa-classifiers`: Table 4, per-class recall of the 10 MATLAB presets on the six touch
// behaviours T1..T6, stratified 7-fold CV with standardisation and PCA (95 % variance)
// fitted inside each training fold (spec §2.12-2.15).
ExperimentReport run_tsa_classifiers(const ExperimentOptions& options);

}  // namespace tactile::experiments

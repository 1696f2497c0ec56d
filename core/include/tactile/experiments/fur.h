#pragma once
// The smart-fur paper (file 002) rerun end to end.

#include "tactile/experiments/experiment.h"

namespace tactile::experiments {

// `fur-ml`: Table 1 — the Gaussian maximum-likelihood classifier, leave-one-out, on the first
// 10 features of the sequential-backward-selection order; per-user models; the 4-class
// grouping, retrained and mapped (spec §3.7-3.11).
ExperimentReport run_fur_ml(const ExperimentOptions& options);

}  // namespace tactile::experiments

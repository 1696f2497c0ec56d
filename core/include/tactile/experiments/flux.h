#pragma once
// The silicone tactile flux sensor paper (file 004) rerun end to end.

#include "tactile/experiments/experiment.h"

namespace tactile::experiments {

// `flux-som`: standardised PCA to 90 % variance, a 7 x 7 Kohonen SOM with neuron-to-class
// regions, and the confusion matrix of stratified 5-fold CV repeated with 5 seeds
// (spec §5.8-5.13).
ExperimentReport run_flux_som(const ExperimentOptions& options);

}  // namespace tactile::experiments

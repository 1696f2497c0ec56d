#pragma once
// Kaboli et al.'s experiments (spec §1.17-1.18) on the NAO skin: train on the back, test on
// the front (stationary, moving, multi-touch), the EM clustering of Fig. 4 and the baseline
// descriptor comparison of Table 9. Each returns tables shaped like the paper's with the
// paper's figures beside ours.

#include "tactile/experiments/experiment.h"

namespace tactile::experiments {

// kaboli-location (Table 5, E1): back stationary -> front stationary, linear SVM.
ExperimentReport run_kaboli_location(const ExperimentOptions& options);
// kaboli-motion (Tables 6, 7; E2, E3): back moving -> front moving, back stationary -> front
// moving.
ExperimentReport run_kaboli_motion(const ExperimentOptions& options);
// kaboli-multitouch (Table 8, E4): back stationary -> multi-touch split by body part.
ExperimentReport run_kaboli_multitouch(const ExperimentOptions& options);
// kaboli-em (Fig. 4): EM clusters mapped to classes on the four train/test scenarios.
ExperimentReport run_kaboli_em(const ExperimentOptions& options);
// kaboli-compare (Table 9): kaboli, naya, silvera_tawil, koo features x K-NN, tree,
// LogitBoost, SVM on the E1 split.
ExperimentReport run_kaboli_compare(const ExperimentOptions& options);

}  // namespace tactile::experiments

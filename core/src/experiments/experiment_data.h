#pragma once
// Shared by the experiment runners: the labelled corpus of one skin (simulated into the
// work folder, or read from --data), and small formatting helpers for report tables.

#include <functional>
#include <string>
#include <vector>

#include "tactile/experiments/experiment.h"
#include "tactile/features/dataset.h"
#include "tactile/ml/evaluation.h"
#include "tactile/ml/pca.h"
#include "tactile/sim/simulator.h"

namespace tactile::experiments {

// Feature rows of one skin's touches. With options.data_dir empty the skin is first
// simulated into options.work_dir/<skin> with `simulation`; otherwise the recordings and
// labels.db of options.data_dir are used as they are. With a `segmenter` method the rows are
// the segments it finds, each given the class of the ground-truth gesture it overlaps most
// (segments overlapping none are not rows); with "" they are the ground-truth segments.
// Stages are reported through options.progress. Throws tactile::Error when the corpus is
// unreadable or empty.
Dataset experiment_dataset(const ExperimentOptions& options, const std::string& skin,
                           const SimulationOptions& simulation, const std::string& pipeline,
                           const std::string& segmenter);

// The dataset's classes in the order of the skin layout's class list (the paper's table
// order), followed by any class the layout does not list, in first-seen order.
std::vector<std::string> ordered_classes(const Dataset& dataset, const std::string& skin);

// Cross-validation with the projection inside the folds: for each fold, an optional PCA
// (standardised, fitted on the training rows only) maps both halves before the classifier
// made from `specification` is fitted. Returns the confusion matrix, rows = true class,
// columns = predicted class plus a last column counting "unknown" answers.
Eigen::MatrixXi cross_validate(const Eigen::MatrixXd& x, const std::vector<int>& labels,
                               int class_count, const std::vector<ml::Fold>& folds,
                               const std::string& specification, uint64_t seed,
                               const ml::PcaOptions* pca = nullptr,
                               const std::function<void(int done, int total)>& progress = {});

// Class index per row, classes numbered in first-seen order (as evaluate() numbers them).
std::vector<int> class_indices(const Dataset& dataset, const std::vector<std::string>& classes);

// "81.5": a fraction as a percentage with one decimal.
std::string percent_text(double fraction);

// Calls options.progress when it is set.
void report_progress(const ExperimentOptions& options, const std::string& stage, int done,
                     int total);

}  // namespace tactile::experiments

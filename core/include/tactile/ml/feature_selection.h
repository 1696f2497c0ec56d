#pragma once
// Feature selection of the smart-fur paper (spec §3.8): sequential backward selection (SBS)
// and the individual ranking of features, both driven by a subset criterion (the paper's:
// leave-one-out accuracy of the Gaussian maximum-likelihood classifier).

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// Score of a feature subset (column indices, ascending); larger is better.
using SubsetCriterion = std::function<double(const std::vector<int>& features)>;

struct BackwardSelection {
  // Significance order: the last remaining feature first, then the removed ones in reverse
  // order of removal.
  std::vector<int> order;
  // rate[n-1] = criterion of the first n features of `order` (= recorded when |F| = n).
  std::vector<double> rate;
  // Features in the order they were removed, with the criterion after each removal.
  std::vector<int> removed;
  std::vector<double> removed_rate;
};

// Spec §3.8: from all features, repeatedly remove the feature whose removal leaves the best
// criterion (ties -> the highest feature index). Throws tactile::Error for feature_count < 1.
BackwardSelection sequential_backward_selection(int feature_count,
                                                const SubsetCriterion& criterion);

struct FeatureRank {
  int feature = 0;
  double rate = 0.0;
};
// Each feature alone, sorted by rate descending (ties -> lower index first).
std::vector<FeatureRank> individual_ranking(int feature_count, const SubsetCriterion& criterion);

// Leave-one-out accuracy (0..1) of a classifier made by `make` on the columns `features` of x:
// for each row, fit on all other rows and predict it. `seed` is passed to every fit.
// Throws tactile::Error on fewer than 2 rows or a row count that differs from y.
double leave_one_out_accuracy(const Matrix& x, const std::vector<int>& y, int class_count,
                              const std::vector<int>& features,
                              const std::function<std::unique_ptr<Classifier>()>& make,
                              uint64_t seed = 0);

// The paper's criterion: leave-one-out accuracy of gaussian-ml (spec §3.6) on the subset.
SubsetCriterion gaussian_ml_leave_one_out(const Matrix& x, const std::vector<int>& y,
                                          int class_count);

}  // namespace tactile::ml

#include "tactile/ml/feature_selection.h"

#include <algorithm>

#include "tactile/error.h"
#include "tactile/ml/gaussian.h"

namespace tactile::ml {

BackwardSelection sequential_backward_selection(int feature_count,
                                                const SubsetCriterion& criterion) {
  if (feature_count < 1) throw Error("feature selection", "needs at least one feature");
  std::vector<int> remaining(static_cast<size_t>(feature_count));
  for (int feature = 0; feature < feature_count; ++feature)
    remaining[static_cast<size_t>(feature)] = feature;
  const double all_features_rate = criterion(remaining);

  BackwardSelection selection;
  while (remaining.size() > 1) {
    int worst = -1;
    double best_rate = 0.0;
    for (int feature : remaining) {
      std::vector<int> without;
      without.reserve(remaining.size() - 1);
      for (int other : remaining)
        if (other != feature) without.push_back(other);
      const double rate = criterion(without);
      // Spec §3.8: ties remove the highest feature index; `remaining` is ascending.
      if (worst < 0 || rate >= best_rate) {
        worst = feature;
        best_rate = rate;
      }
    }
    remaining.erase(std::find(remaining.begin(), remaining.end(), worst));
    selection.removed.push_back(worst);
    selection.removed_rate.push_back(best_rate);
  }

  selection.order.push_back(remaining.front());
  selection.order.insert(selection.order.end(), selection.removed.rbegin(),
                         selection.removed.rend());
  // With n features left the recorded rate is removed_rate[P - 1 - n]; all P: the start.
  selection.rate.resize(static_cast<size_t>(feature_count));
  for (int n = 1; n < feature_count; ++n)
    selection.rate[static_cast<size_t>(n - 1)] =
        selection.removed_rate[static_cast<size_t>(feature_count - 1 - n)];
  selection.rate.back() = all_features_rate;
  return selection;
}

std::vector<FeatureRank> individual_ranking(int feature_count, const SubsetCriterion& criterion) {
  if (feature_count < 1) throw Error("feature selection", "needs at least one feature");
  std::vector<FeatureRank> ranking;
  for (int feature = 0; feature < feature_count; ++feature)
    ranking.push_back({feature, criterion({feature})});
  std::stable_sort(ranking.begin(), ranking.end(),
                   [](const FeatureRank& a, const FeatureRank& b) { return a.rate > b.rate; });
  return ranking;
}

double leave_one_out_accuracy(const Matrix& x, const std::vector<int>& y, int class_count,
                              const std::vector<int>& features,
                              const std::function<std::unique_ptr<Classifier>()>& make,
                              uint64_t seed) {
  const std::string where = "leave-one-out";
  const Eigen::Index rows = x.rows();
  if (rows < 2) throw Error(where, "needs at least 2 samples");
  if (static_cast<Eigen::Index>(y.size()) != rows)
    throw Error(where, "rows and labels differ in count");
  if (features.empty()) throw Error(where, "no features selected");
  Matrix selected(rows, static_cast<Eigen::Index>(features.size()));
  for (size_t column = 0; column < features.size(); ++column) {
    if (features[column] < 0 || features[column] >= x.cols())
      throw Error(where, "feature " + std::to_string(features[column]) + " out of range");
    selected.col(static_cast<Eigen::Index>(column)) = x.col(features[column]);
  }

  Matrix train(rows - 1, selected.cols());
  std::vector<int> train_labels(static_cast<size_t>(rows - 1));
  int64_t correct = 0;
  for (Eigen::Index held_out = 0; held_out < rows; ++held_out) {
    Eigen::Index target = 0;
    for (Eigen::Index row = 0; row < rows; ++row) {
      if (row == held_out) continue;
      train.row(target) = selected.row(row);
      train_labels[static_cast<size_t>(target)] = y[static_cast<size_t>(row)];
      ++target;
    }
    const std::unique_ptr<Classifier> classifier = make();
    classifier->fit(train, train_labels, class_count, seed);
    const std::vector<int> predicted = classifier->predict(selected.row(held_out));
    if (predicted.front() == y[static_cast<size_t>(held_out)]) ++correct;
  }
  return static_cast<double>(correct) / static_cast<double>(rows);
}

SubsetCriterion gaussian_ml_leave_one_out(const Matrix& x, const std::vector<int>& y,
                                          int class_count) {
  return [x, y, class_count](const std::vector<int>& features) {
    return leave_one_out_accuracy(x, y, class_count, features,
                                  [] { return std::make_unique<GaussianMaximumLikelihood>(); });
  };
}

}  // namespace tactile::ml

#include "training_checks.h"

#include <cmath>

#include "tactile/error.h"
#include "tactile/ml/checks.h"

namespace tactile::ml::training_checks {

std::vector<int64_t> check_training(const std::string& classifier, const Matrix& x,
                                    const std::vector<int>& y, int class_count) {
  check_training_set(x, y, class_count, classifier);
  std::vector<int64_t> counts(static_cast<size_t>(class_count), 0);
  for (int label : y) ++counts[static_cast<size_t>(label)];
  return counts;
}

void check_prediction(const std::string& classifier, const Matrix& x, Eigen::Index feature_count,
                      bool fitted) {
  check_fitted(fitted, classifier);
  check_query(x, feature_count, classifier);
}

}  // namespace tactile::ml::training_checks

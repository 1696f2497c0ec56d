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

uint64_t uniform_index(std::mt19937_64& engine, uint64_t count) {
  // Lemire (2019), "Fast random integer generation in an interval": the high word of
  // draw * count is uniform once the biased low range is rejected.
  unsigned __int128 product = static_cast<unsigned __int128>(engine()) * count;
  uint64_t low = static_cast<uint64_t>(product);
  if (low < count) {
    const uint64_t threshold = (0 - count) % count;
    while (low < threshold) {
      product = static_cast<unsigned __int128>(engine()) * count;
      low = static_cast<uint64_t>(product);
    }
  }
  return static_cast<uint64_t>(product >> 64);
}

}  // namespace tactile::ml::training_checks

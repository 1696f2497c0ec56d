#include "training_checks.h"

#include <cmath>

#include "tactile/error.h"

namespace tactile::ml::training_checks {

namespace {

// Row of the first non-finite value, or -1.
Eigen::Index first_non_finite_row(const Matrix& x) {
  if (x.allFinite()) return -1;
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    if (!x.row(row).allFinite()) return row;
  return -1;
}

std::string non_finite_message(const Matrix& x, Eigen::Index row) {
  Eigen::Index column = 0;
  while (column < x.cols() && std::isfinite(x(row, column))) ++column;
  return "row " + std::to_string(row) + " column " + std::to_string(column) +
         " is not a finite number";
}

}  // namespace

std::vector<int64_t> check_training(const std::string& classifier, const Matrix& x,
                                    const std::vector<int>& y, int class_count) {
  if (x.rows() == 0) throw Error(classifier, "no training samples");
  if (x.cols() == 0) throw Error(classifier, "no features");
  if (static_cast<size_t>(x.rows()) != y.size())
    throw Error(classifier, std::to_string(x.rows()) + " training rows but " +
                                std::to_string(y.size()) + " class labels");
  if (class_count < 1) throw Error(classifier, "class count must be at least 1");
  std::vector<int64_t> counts(static_cast<size_t>(class_count), 0);
  for (size_t row = 0; row < y.size(); ++row) {
    if (y[row] < 0 || y[row] >= class_count)
      throw Error(classifier, "row " + std::to_string(row) + " has class " +
                                  std::to_string(y[row]) + ", expected 0.." +
                                  std::to_string(class_count - 1));
    ++counts[static_cast<size_t>(y[row])];
  }
  const Eigen::Index bad_row = first_non_finite_row(x);
  if (bad_row >= 0) throw Error(classifier, "training " + non_finite_message(x, bad_row));
  return counts;
}

void check_prediction(const std::string& classifier, const Matrix& x, Eigen::Index feature_count,
                      bool fitted) {
  if (!fitted) throw Error(classifier, "scores asked before fit() or load()");
  if (x.cols() != feature_count)
    throw Error(classifier, "trained on " + std::to_string(feature_count) + " features, got " +
                                std::to_string(x.cols()));
  const Eigen::Index bad_row = first_non_finite_row(x);
  if (bad_row >= 0) throw Error(classifier, "test " + non_finite_message(x, bad_row));
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

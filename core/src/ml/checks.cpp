#include "tactile/ml/checks.h"

#include <cmath>

#include "tactile/error.h"

namespace tactile::ml {

namespace {

void check_finite(const Matrix& x, const std::string& where) {
  if (x.allFinite()) return;
  for (Eigen::Index column = 0; column < x.cols(); ++column)
    for (Eigen::Index row = 0; row < x.rows(); ++row)
      if (!std::isfinite(x(row, column)))
        throw Error(where, "row " + std::to_string(row) + ", feature " + std::to_string(column) +
                               " is not a finite number");
}

}  // namespace

std::vector<int64_t> check_training_set(const Matrix& x, const std::vector<int>& y, int class_count,
                                        const std::string& where) {
  if (x.rows() == 0) throw Error(where, "no training samples");
  if (x.cols() == 0) throw Error(where, "no features");
  if (class_count < 1) throw Error(where, "no classes");
  if (static_cast<Eigen::Index>(y.size()) != x.rows())
    throw Error(where,
                std::to_string(x.rows()) + " samples but " + std::to_string(y.size()) + " labels");
  for (size_t row = 0; row < y.size(); ++row)
    if (y[row] < 0 || y[row] >= class_count)
      throw Error(where, "row " + std::to_string(row) + " has class " + std::to_string(y[row]) +
                             ", outside 0.." + std::to_string(class_count - 1));
  check_finite(x, where);
  std::vector<int64_t> counts(static_cast<size_t>(class_count), 0);
  for (int label : y) ++counts[static_cast<size_t>(label)];
  return counts;
}

void check_query(const Matrix& x, Eigen::Index features, const std::string& where) {
  if (x.cols() != features)
    throw Error(where, "expected " + std::to_string(features) + " features, got " +
                           std::to_string(x.cols()));
  check_finite(x, where);
}

void check_fitted(bool fitted, const std::string& where) {
  if (!fitted) throw Error(where, "scores asked before fit() or load()");
}

}  // namespace tactile::ml

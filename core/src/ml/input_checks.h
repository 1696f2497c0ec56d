#pragma once
// Checks of the data handed to fit() and scores(): the error names the classifier and the
// first bad row, so a bad feature file is found, not learnt from.

#include <cmath>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml::input_checks {

inline void require_finite(const std::string& where, const Matrix& x) {
  if (x.allFinite()) return;
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    for (Eigen::Index column = 0; column < x.cols(); ++column)
      if (!std::isfinite(x(row, column)))
        throw Error(where, "feature " + std::to_string(column) + " of row " + std::to_string(row) +
                               " is not a finite number");
}

inline void require_training_data(const std::string& where, const Matrix& x,
                                  const std::vector<int>& y, int class_count) {
  if (x.rows() == 0) throw Error(where, "no training samples");
  if (x.cols() == 0) throw Error(where, "no features");
  if (static_cast<size_t>(x.rows()) != y.size())
    throw Error(where, std::to_string(x.rows()) + " samples but " + std::to_string(y.size()) +
                           " class labels");
  if (class_count < 1) throw Error(where, "class count must be at least 1");
  for (size_t row = 0; row < y.size(); ++row)
    if (y[row] < 0 || y[row] >= class_count)
      throw Error(where, "class " + std::to_string(y[row]) + " of row " + std::to_string(row) +
                             " is outside 0.." + std::to_string(class_count - 1));
  require_finite(where, x);
}

inline void require_query(const std::string& where, const Matrix& x, Eigen::Index features,
                          bool fitted) {
  if (!fitted) throw Error(where, "not fitted");
  if (x.cols() != features)
    throw Error(where, "expected " + std::to_string(features) + " features, got " +
                           std::to_string(x.cols()));
  require_finite(where, x);
}

}  // namespace tactile::ml::input_checks

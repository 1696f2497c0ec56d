#pragma once
// Cut points of the threshold learners (the decision tree, LogitBoost's stumps). Private to
// core/src/ml.

namespace tactile::ml {

// The midpoint between two consecutive distinct values, kept strictly above the lower one
// so that `lower < threshold` holds even when the two are adjacent doubles.
inline double midpoint(double lower, double upper) {
  const double middle = lower + (upper - lower) / 2.0;
  return lower < middle ? middle : upper;
}

}  // namespace tactile::ml

#pragma once
// Small hand-made training sets with known answers for the classifier tests: Gaussian blobs
// around given centres and the XOR square.

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <random>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml::toy {

// A one-feature matrix holding `values` in its column.
inline Matrix column(std::initializer_list<double> values) {
  Matrix x(static_cast<Eigen::Index>(values.size()), 1);
  Eigen::Index row = 0;
  for (const double value : values) x(row++, 0) = value;
  return x;
}

struct LabelledSet {
  Matrix x;
  std::vector<int> y;
};

// Box-Muller on the engine's own 53-bit uniforms, so the sets are the same everywhere.
inline double normal(std::mt19937_64& engine) {
  const auto uniform = [&] { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; };
  const double radius = std::sqrt(-2.0 * std::log(uniform()));
  return radius * std::cos(2.0 * std::numbers::pi * uniform());
}

// `per_class` points around each centre (rows of `centres`), spread `spread` in every
// dimension; class c is row c of centres.
inline LabelledSet blobs(const Matrix& centres, int per_class, double spread, uint64_t seed) {
  std::mt19937_64 engine(seed);
  LabelledSet set;
  set.x.resize(centres.rows() * per_class, centres.cols());
  for (Eigen::Index label = 0; label < centres.rows(); ++label) {
    for (int index = 0; index < per_class; ++index) {
      const Eigen::Index row = label * per_class + index;
      for (Eigen::Index column = 0; column < centres.cols(); ++column)
        set.x(row, column) = centres(label, column) + spread * normal(engine);
      set.y.push_back(static_cast<int>(label));
    }
  }
  return set;
}

// Points jittered around the four corners (±1, ±1); class 1 where the signs differ.
inline LabelledSet exclusive_or(int per_corner, double spread, uint64_t seed) {
  std::mt19937_64 engine(seed);
  LabelledSet set;
  set.x.resize(4 * per_corner, 2);
  const double corners[4][2] = {{-1, -1}, {1, 1}, {-1, 1}, {1, -1}};
  for (int corner = 0; corner < 4; ++corner) {
    for (int index = 0; index < per_corner; ++index) {
      const int row = corner * per_corner + index;
      set.x(row, 0) = corners[corner][0] + spread * normal(engine);
      set.x(row, 1) = corners[corner][1] + spread * normal(engine);
      set.y.push_back(corner < 2 ? 0 : 1);
    }
  }
  return set;
}

inline double accuracy(const std::vector<int>& predicted, const std::vector<int>& truth) {
  int64_t correct = 0;
  for (size_t index = 0; index < truth.size(); ++index) correct += predicted[index] == truth[index];
  return static_cast<double>(correct) / static_cast<double>(truth.size());
}

}  // namespace tactile::ml::toy

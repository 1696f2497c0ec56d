#pragma once
// Summaries that several core tests read their measurements by.

#include <algorithm>
#include <vector>

namespace tactile::test {

// The upper median (the middle element of the sorted values); 0 for no values.
inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace tactile::test

#pragma once
// Small labelled datasets for the ml tests: Gaussian blobs with subjects, recordings,
// segment ids and metadata, so every protocol has something to split by.

#include <random>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"

namespace tactile::ml {

// `counts[c]` rows of class "c<c>", blob centres 8 apart on the diagonal, subjects s0..s3
// in turn, side front/back in turn, segment ids 1000 + row.
// prefix + number, appended rather than `"c" + std::to_string(n)`, which trips GCC 12's
// false -Wrestrict warning once inlined.
inline std::string numbered(const char* prefix, int64_t number) {
  std::string text = prefix;
  text.append(std::to_string(number));
  return text;
}

inline Dataset blob_dataset(const std::vector<int>& counts, int dimensions, uint64_t seed,
                            double spread = 1.0) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, spread);
  Dataset dataset;
  int64_t total = 0;
  for (int count : counts) total += count;
  dataset.features.resize(total, dimensions);
  for (int column = 0; column < dimensions; ++column)
    dataset.columns.push_back({numbered("f", column), ""});
  int64_t row = 0;
  // Interleave the classes so that first-seen order is c0, c1, ...
  std::vector<int> left = counts;
  while (row < total) {
    for (size_t c = 0; c < left.size(); ++c) {
      if (left[c] == 0) continue;
      --left[c];
      for (int column = 0; column < dimensions; ++column)
        dataset.features(row, column) = normal(random) + 8.0 * static_cast<double>(c);
      dataset.classes.push_back(numbered("c", static_cast<int64_t>(c)));
      dataset.subjects.push_back(numbered("s", row % 4));
      dataset.recordings.push_back(numbered("rec", row % 3) + ".h5");
      dataset.segment_ids.push_back(1000 + row);
      dataset.metadata.push_back({{"side", row % 2 == 0 ? "front" : "back"},
                                  {"condition", row % 3 == 0 ? "moving" : "stationary"}});
      ++row;
    }
  }
  return dataset;
}

}  // namespace tactile::ml

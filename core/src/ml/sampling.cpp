#include "tactile/ml/sampling.h"

#include <utility>

namespace tactile::ml {

double uniform01(std::mt19937_64& random) {
  return static_cast<double>(random() >> 11) * 0x1.0p-53;
}

int64_t uniform_index(std::mt19937_64& random, int64_t count) {
  const auto index = static_cast<int64_t>(uniform01(random) * static_cast<double>(count));
  return index < count ? index : count - 1;  // guards the product rounding up to count
}

void shuffle(std::vector<int64_t>& items, std::mt19937_64& random) {
  for (int64_t i = static_cast<int64_t>(items.size()) - 1; i > 0; --i)
    std::swap(items[static_cast<size_t>(i)],
              items[static_cast<size_t>(uniform_index(random, i + 1))]);
}

uint64_t derive_seed(uint64_t seed, uint64_t index) {
  // splitmix64 finaliser (Steele, Lea, Flood 2014): decorrelates neighbouring inputs.
  uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace tactile::ml

#include "tactile/random.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tactile {

double uniform01(std::mt19937_64& engine) {
  // 53 random mantissa bits -> exactly representable doubles in [0, 1).
  return static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

uint64_t uniform_index(std::mt19937_64& engine, uint64_t count) {
  // Draws at or above the largest multiple of count would favour the low values.
  const uint64_t limit =
      std::numeric_limits<uint64_t>::max() - std::numeric_limits<uint64_t>::max() % count;
  uint64_t draw = engine();
  while (draw >= limit) draw = engine();
  return draw % count;
}

uint64_t derive_seed(uint64_t seed, uint64_t index) {
  // splitmix64 finaliser (Steele, Lea, Flood 2014): decorrelates neighbouring inputs.
  uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

//---- Random

double Random::uniform(double low, double high) { return low + (high - low) * uniform(); }

int64_t Random::integer(int64_t low, int64_t high) {
  if (high <= low) return low;
  const uint64_t span = static_cast<uint64_t>(high) - static_cast<uint64_t>(low) + 1;
  return low + static_cast<int64_t>(uniform_index(engine_, span));
}

double Random::normal(double mean, double stddev) {
  // Marsaglia polar method; keeps the second value for the next call.
  if (has_spare_) {
    has_spare_ = false;
    return mean + stddev * spare_;
  }
  double u = 0.0, v = 0.0, s = 0.0;
  do {
    u = uniform(-1.0, 1.0);
    v = uniform(-1.0, 1.0);
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * factor;
  has_spare_ = true;
  return mean + stddev * u * factor;
}

double Random::truncated_normal(double mean, double stddev, double limit) {
  for (int attempt = 0; attempt < 64; ++attempt) {
    const double z = normal();
    if (std::abs(z) <= limit) return mean + stddev * z;
  }
  return mean;
}

bool Random::chance(double probability) { return uniform() < probability; }

int Random::weighted(const std::vector<double>& weights) {
  double total = 0.0;
  for (const double weight : weights) total += std::max(0.0, weight);
  double draw = uniform() * total;
  for (size_t k = 0; k < weights.size(); ++k) {
    draw -= std::max(0.0, weights[k]);
    if (draw < 0.0) return static_cast<int>(k);
  }
  return weights.empty() ? 0 : static_cast<int>(weights.size()) - 1;
}

}  // namespace tactile

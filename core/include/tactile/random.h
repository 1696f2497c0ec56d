#pragma once
// Every random draw of the project, written out on the raw 64-bit output of std::mt19937_64
// (never std::*_distribution or std::shuffle, which are not specified bit for bit), so a seed
// gives the same numbers with every standard library.

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace tactile {

// Uniform in [0, 1): the top 53 bits of one draw.
double uniform01(std::mt19937_64& engine);
// Uniform in 0..count-1 (count >= 1): draw % count, redrawing the top values that would
// make the low ones more likely.
uint64_t uniform_index(std::mt19937_64& engine, uint64_t count);

// Fisher-Yates from the back: for i = n-1 .. 1, swap items i and uniform_index(i + 1).
template <typename Item>
void shuffle(std::vector<Item>& items, std::mt19937_64& engine) {
  for (size_t index = items.size(); index-- > 1;)
    std::swap(items[index], items[uniform_index(engine, index + 1)]);
}

// An independent seed for part `index` of a job (a fold, a learner): splitmix64 of
// seed + index, so parts are reproducible whatever order or thread runs them.
uint64_t derive_seed(uint64_t seed, uint64_t index);

// Draws from one engine, for generators that take many kinds of draws.
class Random {
 public:
  explicit Random(std::mt19937_64 engine) : engine_(std::move(engine)) {}
  double uniform() { return uniform01(engine_); }  // [0, 1)
  double uniform(double low, double high);         // [low, high)
  int64_t integer(int64_t low, int64_t high);      // [low, high], inclusive
  double normal(double mean = 0.0, double stddev = 1.0);
  // Normal draw kept inside [mean - limit*stddev, mean + limit*stddev] by redrawing.
  double truncated_normal(double mean, double stddev, double limit = 2.5);
  bool chance(double probability);
  // An index drawn with probability proportional to its weight (weights >= 0, not all 0).
  int weighted(const std::vector<double>& weights);
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace tactile

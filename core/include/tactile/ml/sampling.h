#pragma once
// The random draws of the ml code, written out so that a seed gives the same numbers with
// every standard library (std::uniform_int_distribution and std::shuffle are not
// specified bit for bit).

#include <cstdint>
#include <random>
#include <vector>

namespace tactile::ml {

// Uniform in [0, 1): the top 53 bits of one draw.
double uniform01(std::mt19937_64& random);
// Uniform in 0..count-1 as floor(uniform01 * count); count >= 1.
int64_t uniform_index(std::mt19937_64& random, int64_t count);
// Fisher-Yates from the back: for i = n-1 .. 1, swap items i and uniform_index(i + 1).
void shuffle(std::vector<int64_t>& items, std::mt19937_64& random);
// An independent seed for part `index` of a job (a fold, a learner): splitmix64 of
// seed + index, so parts are reproducible whatever order or thread runs them.
uint64_t derive_seed(uint64_t seed, uint64_t index);

}  // namespace tactile::ml

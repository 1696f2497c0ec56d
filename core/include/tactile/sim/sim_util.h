#pragma once
// Small building blocks shared by the skin generators: random draws, ADC quantisation,
// contact envelopes, gesture order and stream set-up.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"

namespace tactile::sim {

// Draws from one engine. Uses its own transforms of the engine's raw 64-bit output
// (not std::*_distribution), so the bytes do not depend on the standard library.
class Random {
 public:
  explicit Random(std::mt19937_64 engine) : engine_(std::move(engine)) {}
  double uniform();                           // [0, 1)
  double uniform(double low, double high);    // [low, high)
  int64_t integer(int64_t low, int64_t high);  // [low, high], inclusive
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

// An ADC: clamps `value` to [low, high] and rounds it to one of 2^bits levels; returns
// the level's value in the same units (saturation and quantisation as a device shows them).
float quantize(double value, double low, double high, int bits);

// Smooth contact envelope in [0, 1]: raised-cosine rise over `rise` s from `onset`, hold,
// raised-cosine fall over `fall` s ending at onset + duration. Zero outside.
double contact_envelope(double t, double onset, double duration, double rise, double fall);

// Minimum-jerk progress 0 -> 1 of `progress` in [0, 1] (clamped): how a hand moves from one place
// to another, starting and stopping smoothly (Flash & Hogan).
double minimum_jerk(double progress);

// Classes 0..count-1, each `repetitions` times, in a random order where no class
// follows itself when that can be avoided.
std::vector<int> shuffled_classes(int count, int repetitions, Random& random);

// A stream whose channels and units are the layout's, with `samples` rows of zeros.
Stream make_stream(const SkinLayout& layout, const std::string& name, double rate_hz, int64_t samples);

// Standard metadata of a simulated recording.
Metadata simulated_metadata(const std::string& skin, int subject, int trial, const std::string& side,
                            const std::string& condition);

}  // namespace tactile::sim

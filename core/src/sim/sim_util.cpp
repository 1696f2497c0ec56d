#include "tactile/sim/sim_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tactile/sim/simulator.h"

namespace tactile {

namespace {
// SplitMix64 finaliser: spreads nearby inputs over the whole 64-bit range.
uint64_t mix(uint64_t value) {
  value += 0x9E3779B97F4A7C15ull;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ull;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBull;
  return value ^ (value >> 31);
}

}  // namespace

std::mt19937_64 derive_engine(uint64_t seed, const std::string& purpose, int64_t a, int64_t b) {
  uint64_t state = mix(seed);
  for (unsigned char c : purpose) state = mix(state ^ c);
  state = mix(state ^ static_cast<uint64_t>(a));
  state = mix(state ^ static_cast<uint64_t>(b));
  return std::mt19937_64(state);
}

std::string simulated_recording_id(const std::string& skin, int subject, int trial) {
  char text[96];
  std::snprintf(text, sizeof(text), "%s-s%02d-t%02d", skin.c_str(), subject + 1, trial + 1);
  return text;
}

namespace sim {

double Random::uniform() {
  // 53 random mantissa bits -> exactly representable doubles in [0, 1).
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double Random::uniform(double low, double high) { return low + (high - low) * uniform(); }

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

int64_t Random::integer(int64_t low, int64_t high) {
  if (high <= low) return low;
  const uint64_t span = static_cast<uint64_t>(high - low) + 1;
  // Rejection keeps every value equally likely.
  const uint64_t limit = UINT64_MAX - UINT64_MAX % span;
  uint64_t draw = engine_();
  while (draw >= limit) draw = engine_();
  return low + static_cast<int64_t>(draw % span);
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

float quantize(double value, double low, double high, int bits) {
  const double levels = std::ldexp(1.0, bits) - 1.0;
  const double clamped = std::clamp(value, low, high);
  const double level = std::round((clamped - low) / (high - low) * levels);
  return static_cast<float>(low + level * (high - low) / levels);
}

double minimum_jerk(double progress) {
  const double p = std::clamp(progress, 0.0, 1.0);
  return p * p * p * (10.0 - 15.0 * p + 6.0 * p * p);
}

double contact_envelope(double t, double onset, double duration, double rise, double fall) {
  const double end = onset + duration;
  if (t <= onset || t >= end) return 0.0;
  rise = std::min(rise, duration * 0.5);
  fall = std::min(fall, duration * 0.5);
  if (rise > 0 && t < onset + rise)
    return 0.5 - 0.5 * std::cos(std::numbers::pi * (t - onset) / rise);
  if (fall > 0 && t > end - fall) return 0.5 - 0.5 * std::cos(std::numbers::pi * (end - t) / fall);
  return 1.0;
}

std::vector<int> shuffled_classes(int count, int repetitions, Random& random) {
  std::vector<int> order;
  for (int repetition = 0; repetition < repetitions; ++repetition)
    for (int k = 0; k < count; ++k) order.push_back(k);
  // Fisher-Yates with our own integer draws (std::shuffle's algorithm is unspecified).
  for (int64_t k = static_cast<int64_t>(order.size()) - 1; k > 0; --k)
    std::swap(order[k], order[random.integer(0, k)]);
  // Break up repeats by swapping with a later different class where one exists.
  for (size_t k = 1; k < order.size(); ++k) {
    if (order[k] != order[k - 1]) continue;
    for (size_t j = k + 1; j < order.size(); ++j)
      if (order[j] != order[k - 1]) {
        std::swap(order[k], order[j]);
        break;
      }
  }
  return order;
}

Stream make_stream(const SkinLayout& layout, const std::string& name, double rate_hz,
                   int64_t samples) {
  Stream stream;
  stream.name = name;
  stream.rate_hz = rate_hz;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples = SampleMatrix::Zero(samples, static_cast<Eigen::Index>(layout.channels.size()));
  return stream;
}

Metadata simulated_metadata(const std::string& skin, int subject, int trial,
                            const std::string& side, const std::string& condition) {
  char subject_id[16];
  std::snprintf(subject_id, sizeof(subject_id), "s%02d", subject + 1);
  Metadata metadata = {{"skin", skin},
                       {"subject", subject_id},
                       {"trial", std::to_string(trial + 1)},
                       {"source", "simulator"}};
  if (!side.empty()) metadata["side"] = side;
  if (!condition.empty()) metadata["condition"] = condition;
  return metadata;
}

}  // namespace sim
}  // namespace tactile

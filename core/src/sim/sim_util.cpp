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
  shuffle(order, random.engine());
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

Label ground_truth_label(const std::string& recording, double t0, double t1,
                         const std::string& class_name, const std::string& region) {
  Label label;
  label.recording = recording;
  label.t0 = t0;
  label.t1 = t1;
  label.class_name = class_name;
  label.region = region;
  label.annotator = "simulator";
  label.source = LabelSource::kGroundTruth;
  label.confidence = 1.0;
  return label;
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

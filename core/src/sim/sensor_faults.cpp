#include "tactile/sim/sensor_faults.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "tactile/error.h"
#include "tactile/random.h"
#include "tactile/sim/sim_util.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

// Per channel: its median (rest) and signed peak excursion in the clean recording.
struct FaultSwing {
  std::vector<float> rest;
  std::vector<float> peak;  // signed; never 0
};

FaultSwing fault_swing(const Stream& stream) {
  const int64_t samples = stream.sample_count();
  const auto channels = static_cast<size_t>(stream.channel_count());
  FaultSwing swing;
  swing.rest.assign(channels, 0.0f);
  swing.peak.assign(channels, 0.0f);
  std::vector<float> values;
  std::vector<float> spreads(channels, 0.0f);
  for (size_t c = 0; c < channels; ++c) {
    const float* column = stream.samples.col(static_cast<Eigen::Index>(c)).data();
    values.assign(column, column + samples);
    std::erase_if(values, [](float v) { return !std::isfinite(v); });
    if (values.empty()) continue;
    swing.rest[c] = stats::median(values);
    float most = 0.0f;
    for (int64_t t = 0; t < samples; ++t)
      if (std::isfinite(column[t]) && std::fabs(column[t] - swing.rest[c]) > std::fabs(most))
        most = column[t] - swing.rest[c];
    swing.peak[c] = most;
    for (float& v : values) v = std::fabs(v - swing.rest[c]);
    spreads[c] = 3.0f * 1.4826f * stats::median(values);
  }
  // Touched channels: a peak well past their noise. Their median peak and usual sign stand
  // in for the channels no touch reached.
  std::vector<float> touched;
  double sign_sum = 0.0;
  for (size_t c = 0; c < channels; ++c)
    if (std::fabs(swing.peak[c]) > 4.0f * spreads[c] && swing.peak[c] != 0.0f) {
      touched.push_back(std::fabs(swing.peak[c]));
      sign_sum += swing.peak[c] > 0 ? 1.0 : -1.0;
    }
  const float typical = touched.empty() ? 1.0f : stats::median(touched);
  const float sign = sign_sum >= 0 ? 1.0f : -1.0f;
  for (size_t c = 0; c < channels; ++c)
    if (!(std::fabs(swing.peak[c]) > 4.0f * spreads[c]) || swing.peak[c] == 0.0f)
      swing.peak[c] = sign * typical;
  return swing;
}

// Stream column -> its taxel's position and its slot among the taxel's channels.
struct FaultPlace {
  Point2 position;
  int slot = -1;  // -1: a channel of no taxel
  int taxel = -1;
};

std::vector<FaultPlace> fault_places(const Stream& stream, const SkinLayout& layout) {
  std::vector<FaultPlace> places(stream.channels.size());
  for (size_t k = 0; k < layout.taxels.size(); ++k) {
    const Taxel& taxel = layout.taxels[k];
    for (size_t slot = 0; slot < taxel.channels.size(); ++slot) {
      const int channel = taxel.channels[slot];
      if (channel < 0 || channel >= static_cast<int>(layout.channels.size())) continue;
      const auto found = std::find(stream.channels.begin(), stream.channels.end(),
                                   layout.channels[static_cast<size_t>(channel)].name);
      if (found == stream.channels.end()) continue;
      FaultPlace& place = places[static_cast<size_t>(found - stream.channels.begin())];
      place = {taxel.position, static_cast<int>(slot), static_cast<int>(k)};
    }
  }
  return places;
}

double fault_distance(Point2 a, Point2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

void fault_check_share(double value, const std::string& key, const std::string& where,
                       double high) {
  if (!(value >= 0.0 && value <= high))
    throw Error(where, key + " must lie in [0, " + std::to_string(high) + "]");
}

}  // namespace

bool SensorFaults::any() const {
  return stuck > 0 || dead > 0 || drift > 0 || crosstalk > 0 || offsets > 0 || rest > 0;
}

SensorFaults parse_sensor_faults(const std::string& text, const std::string& where) {
  SensorFaults faults;
  if (text.empty() || text == "none") return faults;
  std::string rest_of_text = text;
  if (text.rfind("realistic", 0) == 0) {
    faults.stuck = 2;
    faults.dead = 1;
    faults.drift = 0.3;
    faults.crosstalk = 0.05;
    faults.offsets = 1.0;
    faults.rest = 0.6;
    rest_of_text = text.substr(9);
    if (!rest_of_text.empty() && rest_of_text.front() != ',')
      throw Error(where, "unknown faults '" + text + "' (none, realistic, or key=value,...)");
    if (!rest_of_text.empty()) rest_of_text.erase(0, 1);
    if (rest_of_text.empty()) return faults;
  }
  const Parameters parameters = Parameters::parse(rest_of_text, where);
  parameters.expect_only({"stuck", "dead", "drift", "crosstalk", "offsets", "rest", "rest_level",
                          "rest_patch", "rest_gap"});
  faults.stuck = static_cast<int>(parameters.integer("stuck", faults.stuck));
  faults.dead = static_cast<int>(parameters.integer("dead", faults.dead));
  faults.drift = parameters.number("drift", faults.drift);
  faults.crosstalk = parameters.number("crosstalk", faults.crosstalk);
  faults.offsets = parameters.number("offsets", faults.offsets);
  faults.rest = parameters.number("rest", faults.rest);
  faults.rest_level = parameters.number("rest_level", faults.rest_level);
  faults.rest_patch = parameters.number("rest_patch", faults.rest_patch);
  faults.rest_gap = parameters.number("rest_gap", faults.rest_gap);
  if (faults.stuck < 0 || faults.dead < 0)
    throw Error(where, "stuck and dead must not be negative");
  fault_check_share(faults.drift, "drift", where, 10.0);
  fault_check_share(faults.crosstalk, "crosstalk", where, 0.5);
  fault_check_share(faults.offsets, "offsets", where, 100.0);
  fault_check_share(faults.rest, "rest", where, 1.0);
  fault_check_share(faults.rest_level, "rest_level", where, 1.0);
  fault_check_share(faults.rest_patch, "rest_patch", where, 1.0);
  if (!(faults.rest_gap > 0.0)) throw Error(where, "rest_gap must be positive");
  return faults;
}

void apply_sensor_faults(SimulatedTrial& trial, const SkinLayout& layout,
                         const SensorFaults& faults, uint64_t seed, int subject, int trial_index) {
  if (!faults.any() || trial.recording.streams.empty()) return;
  Stream& stream = trial.recording.streams.front();
  const int64_t samples = stream.sample_count();
  const auto channels = static_cast<size_t>(stream.channel_count());
  if (samples == 0 || channels == 0 || !(stream.rate_hz > 0)) return;
  Random random(derive_engine(seed, "sensor-faults", subject, trial_index));
  const FaultSwing swing = fault_swing(stream);
  const std::vector<FaultPlace> places = fault_places(stream, layout);
  const double rate = stream.rate_hz;
  const Eigen::MatrixXf clean = stream.samples;  // crosstalk reads the clean changes

  // Crosstalk: each channel picks up a share of the mean change of the same slot of its
  // nearest neighbouring taxels (those within 1.5 times the nearest distance).
  if (faults.crosstalk > 0) {
    for (size_t c = 0; c < channels; ++c) {
      if (places[c].slot < 0) continue;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t d = 0; d < channels; ++d)
        if (d != c && places[d].slot == places[c].slot && places[d].taxel != places[c].taxel)
          nearest = std::min(nearest, fault_distance(places[c].position, places[d].position));
      if (!std::isfinite(nearest)) continue;
      std::vector<size_t> neighbours;
      for (size_t d = 0; d < channels; ++d)
        if (d != c && places[d].slot == places[c].slot && places[d].taxel != places[c].taxel &&
            fault_distance(places[c].position, places[d].position) <= 1.5 * nearest + 1e-9)
          neighbours.push_back(d);
      const double share = faults.crosstalk / static_cast<double>(neighbours.size());
      for (size_t d : neighbours)
        stream.samples.col(static_cast<Eigen::Index>(c)).array() +=
            static_cast<float>(share) *
            (clean.col(static_cast<Eigen::Index>(d)).array() - swing.rest[d]);
    }
  }

  // A resting hand: in some pauses between labels, a low broad press on a patch, rising and
  // falling slowly and swaying a little, never overlapping a label (0.3 s clear each side).
  if (faults.rest > 0) {
    std::vector<std::pair<double, double>> touches;
    for (const Label& label : trial.labels) touches.emplace_back(label.t0, label.t1);
    std::sort(touches.begin(), touches.end());
    std::vector<std::pair<double, double>> pauses;
    double previous = stream.start_time;
    for (const auto& [t0, t1] : touches) {
      if (t0 - previous >= faults.rest_gap + 0.6) pauses.emplace_back(previous + 0.3, t0 - 0.3);
      previous = std::max(previous, t1);
    }
    const double end = stream.time_of(samples - 1);
    if (end - previous >= faults.rest_gap + 0.6) pauses.emplace_back(previous + 0.3, end - 0.3);
    std::vector<size_t> placed;
    for (size_t c = 0; c < channels; ++c)
      if (places[c].slot >= 0) placed.push_back(c);
    for (const auto& [from, to] : pauses) {
      if (!random.chance(faults.rest) || placed.empty()) continue;
      const Point2 centre = places[placed[static_cast<size_t>(
                                       random.integer(0, static_cast<int64_t>(placed.size()) - 1))]]
                                .position;
      std::vector<double> distances;
      for (size_t c : placed) distances.push_back(fault_distance(places[c].position, centre));
      std::vector<double> sorted = distances;
      std::sort(sorted.begin(), sorted.end());
      const auto reach_index = std::min(
          sorted.size() - 1,
          static_cast<size_t>(std::ceil(faults.rest_patch * static_cast<double>(sorted.size()))));
      const double reach = std::max(sorted[reach_index], 1e-9);
      const double sway_period = random.uniform(2.0, 5.0);
      const double sway_phase = random.uniform(0.0, 2.0 * std::numbers::pi);
      const double duration = to - from;
      const double ramp = std::min(0.5, duration / 4.0);
      const auto [first, last] = sample_range(stream, from, to);
      for (size_t k = 0; k < placed.size(); ++k) {
        if (distances[k] > reach) continue;
        const size_t c = placed[k];
        const double weight = 1.0 - 0.5 * (distances[k] / reach) * (distances[k] / reach);
        const double amplitude = faults.rest_level * weight * swing.peak[c];
        for (int64_t t = first; t < last; ++t) {
          const double time = stream.time_of(t);
          const double sway =
              1.0 + 0.15 * std::sin(2.0 * std::numbers::pi * time / sway_period + sway_phase);
          stream.samples(t, static_cast<Eigen::Index>(c)) += static_cast<float>(
              amplitude * sway * sim::contact_envelope(time, from, duration, ramp, ramp));
        }
      }
    }
  }

  // Offsets and drift: an uncalibrated rest that wanders slowly (a ramp and a slow wave).
  const double span = std::max(1.0 / rate, static_cast<double>(samples) / rate);
  for (size_t c = 0; c < channels; ++c) {
    const double offset = faults.offsets * random.uniform(-1.0, 1.0) * std::fabs(swing.peak[c]);
    const double drift = faults.drift * random.uniform(0.5, 1.0) * (random.chance(0.5) ? 1 : -1) *
                         std::fabs(swing.peak[c]);
    const double wave_period = random.uniform(0.5, 1.5) * span;
    const double wave_phase = random.uniform(0.0, 2.0 * std::numbers::pi);
    if (offset == 0.0 && drift == 0.0) continue;
    for (int64_t t = 0; t < samples; ++t) {
      const double progress = static_cast<double>(t) / rate / span;
      const double wander =
          0.6 * progress +
          0.4 * std::sin(2.0 * std::numbers::pi * progress * span / wave_period + wave_phase);
      stream.samples(t, static_cast<Eigen::Index>(c)) +=
          static_cast<float>(offset + drift * wander);
    }
  }

  // Stuck and dead channels, at most an eighth of the channels together.
  const auto allowed = static_cast<int64_t>(std::max<size_t>(1, channels / 8));
  std::vector<size_t> order(channels);
  for (size_t c = 0; c < channels; ++c) order[c] = c;
  shuffle(order, random.engine());
  int64_t used = 0;
  for (int k = 0; k < faults.stuck && used < allowed; ++k, ++used) {
    const size_t c = order[static_cast<size_t>(used)];
    const auto from = static_cast<int64_t>(random.uniform(0.0, 0.5) * static_cast<double>(samples));
    const float value = stream.samples(from, static_cast<Eigen::Index>(c)) +
                        static_cast<float>(random.uniform(0.3, 1.0)) * swing.peak[c];
    stream.samples.col(static_cast<Eigen::Index>(c)).tail(samples - from).setConstant(value);
  }
  for (int k = 0; k < faults.dead && used < allowed; ++k, ++used)
    stream.samples.col(static_cast<Eigen::Index>(order[static_cast<size_t>(used)])).setZero();

  std::ostringstream note;
  note << "stuck=" << faults.stuck << ",dead=" << faults.dead << ",drift=" << faults.drift
       << ",crosstalk=" << faults.crosstalk << ",offsets=" << faults.offsets
       << ",rest=" << faults.rest;
  trial.recording.metadata["faults"] = note.str();
}

}  // namespace tactile

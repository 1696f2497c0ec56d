// Simulated smart fur (paper 002): a subject approaches the robot's head from the front or
// the back and performs slap, pat, fondle, stroke, tickle and push gestures on it; the
// pressure matrix under the plush records them at 15 Hz, 10 bit.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "fur/fur_hand.h"
#include "fur/fur_sensor.h"
#include "tactile/error.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile {

namespace {

using sim::fur::Approach;
using sim::fur::ContactPart;
using sim::fur::Episode;
using sim::fur::FurSensor;

// The paper's five testers gave 399 gestures, about 13 per class each: five per class in
// one trial makes three trials a subject's share.
constexpr int kFurRepetitions = 5;
// Sub-steps per frame: a slap lasts two or three frames, so the hand moves on a finer clock
// and the microcontroller's low-pass turns it into frames.
constexpr int kSubsteps = 16;
constexpr double kFrameNoiseCounts = 0.6;
// Calibration press of spec §3.3 with the soft-tipped 2.5 cm cylinder of paper 002 Fig 5.
// The paper does not give the reference force; a light one keeps the cell's response graded,
// so that firm gestures exceed it (saturate at 1 after normalisation) and tickling does not.
constexpr double kReferenceForceNewton = 0.8;
constexpr double kReferenceDiameterMm = 25.0;
constexpr double kReferenceRiseSeconds = 0.3;
constexpr double kReferenceHoldSeconds = 1.5;
// Spec §3.2: the 0.2 Hz first-order high-pass the calibration peak is measured after.
constexpr double kHighPassHz = 0.2;

struct PlannedGesture {
  int class_index = 0;
  double start = 0.0, end = 0.0;  // first and last instant of contact
  size_t first_episode = 0, episode_count = 0;
};

// Spec §3.3: r_c = peak of the high-passed response of cell c to the reference press,
// pressed on each cell in turn (rising over 0.3 s, then held), read at the frame rate.
std::string calibration_peaks(FurSensor& sensor, int channels, double rate) {
  std::vector<double> peaks(static_cast<size_t>(channels), 0.0);
  const double rc = 1.0 / (2.0 * std::numbers::pi * kHighPassHz), dt = 1.0 / rate;
  const double alpha = rc / (rc + dt);
  const int frames = static_cast<int>((kReferenceRiseSeconds + kReferenceHoldSeconds) * rate);
  for (int cell = 0; cell < sensor.cell_count(); ++cell) {
    double previous = 1023.0 - sensor.rest_reading(cell), filtered = 0.0, peak = 0.0;
    for (int frame = 1; frame <= frames; ++frame) {
      const double share = std::min(1.0, frame * dt / kReferenceRiseSeconds);
      const double force = kReferenceForceNewton * (0.5 - 0.5 * std::cos(std::numbers::pi * share));
      const double u = 1023.0 - sensor.reading_under_reference(cell, force, kReferenceDiameterMm);
      filtered = alpha * (filtered + u - previous);
      previous = u;
      peak = std::max(peak, filtered);
    }
    peaks[sensor.channel(cell)] = peak;
  }
  std::string text;
  char number[32];
  for (size_t k = 0; k < peaks.size(); ++k) {
    std::snprintf(number, sizeof(number), k ? ",%.1f" : "%.1f", peaks[k]);
    text += number;
  }
  return text;
}

// The layout group of kind "region" carrying most of the gesture's force over time.
std::string touched_region(const SkinLayout& layout, const FurSensor& sensor,
                           const std::vector<double>& impulse) {
  std::string best = "all";
  double best_impulse = 0.0;
  for (const Group& group : layout.groups) {
    if (group.kind != "region") continue;
    double total = 0.0;
    for (int cell = 0; cell < sensor.cell_count(); ++cell)
      if (std::find(group.taxels.begin(), group.taxels.end(), sensor.taxel_id(cell)) !=
          group.taxels.end())
        total += impulse[cell];
    if (total > best_impulse) {
      best_impulse = total;
      best = group.id;
    }
  }
  return best;
}

}  // namespace

SimulatedTrial simulate_fur_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial) {
  if (subject < 0) throw Error("--subjects", "subject index must not be negative");
  if (trial < 0) throw Error("--trials", "trial index must not be negative");
  if (options.repetitions < 0) throw Error("--repetitions", "must not be negative");
  if (layout.classes.empty()) throw Error("layout " + layout.id, "has no classes to perform");
  std::vector<sim::fur::Gesture> gestures;
  for (const std::string& name : layout.classes) gestures.push_back(sim::fur::gesture_of(name));
  const double rate = layout.sample_rate_hz > 0 ? layout.sample_rate_hz : 15.0;
  const int repetitions = options.repetitions > 0 ? options.repetitions : kFurRepetitions;

  Random device(derive_engine(options.seed, "fur-device"));
  FurSensor sensor(layout, device);
  const std::string calibration =
      calibration_peaks(sensor, static_cast<int>(layout.channels.size()), rate);
  const sim::fur::HeadMap map = sim::fur::head_map(layout);
  Random subject_random(derive_engine(options.seed, "fur-subject", subject));
  const sim::fur::SubjectHabits habits = sim::fur::draw_habits(map, subject_random);
  Random random(derive_engine(options.seed, "fur-trial", subject, trial));
  // Testers came from the front in half of the trials and from behind in the other half.
  const Approach approach = (trial % 2 == 0) == (habits.first_approach == Approach::kFront)
                                ? Approach::kFront
                                : Approach::kBack;

  //---- Plan: gestures in shuffled order, rests drawn independently of the class
  const std::vector<int> order =
      sim::shuffled_classes(static_cast<int>(gestures.size()), repetitions, random);
  std::vector<Episode> episodes;
  std::vector<PlannedGesture> planned;
  double time = random.uniform(2.0, 3.0);
  for (size_t k = 0; k < order.size(); ++k) {
    PlannedGesture gesture;
    gesture.class_index = order[k];
    gesture.first_episode = episodes.size();
    for (const Episode& episode :
         sim::fur::plan_gesture(gestures[order[k]], habits, approach, map, time, random))
      episodes.push_back(episode);
    gesture.episode_count = episodes.size() - gesture.first_episode;
    gesture.start = time;
    gesture.end = time;
    for (size_t e = gesture.first_episode; e < episodes.size(); ++e)
      gesture.end = std::max(gesture.end, episodes[e].onset + episodes[e].duration);
    planned.push_back(gesture);
    time =
        gesture.end + (k + 1 < order.size() ? random.uniform(1.2, 2.8) : random.uniform(2.0, 3.0));
  }
  const int64_t frames = static_cast<int64_t>(std::ceil(time * rate));

  //---- Physics: hand on the fur, sensor, ADC, microcontroller, at kSubsteps per frame
  Random noise(std::mt19937_64(random.engine()()));
  Stream stream = sim::make_stream(layout, "skin", rate, frames);
  // The quiescent level wanders slowly over a recording (temperature, humidity).
  const double drift_rate = random.normal(0.0, 0.02) / std::max(time, 1.0);
  const double dt = 1.0 / (rate * kSubsteps);
  std::vector<std::vector<double>> impulse(planned.size(),
                                           std::vector<double>(sensor.cell_count(), 0.0));
  std::vector<ContactPart> parts;
  size_t gesture_cursor = 0;
  for (int64_t frame = 0; frame < frames; ++frame) {
    sensor.draw_contact_jitter(noise);
    for (int step = 0; step < kSubsteps; ++step) {
      const double t = (frame * kSubsteps + step - (kSubsteps - 1)) * dt;
      while (gesture_cursor < planned.size() && planned[gesture_cursor].end < t) ++gesture_cursor;
      sensor.clear_pressure();
      parts.clear();
      if (gesture_cursor < planned.size() && planned[gesture_cursor].start <= t) {
        const PlannedGesture& gesture = planned[gesture_cursor];
        for (size_t e = 0; e < gesture.episode_count; ++e)
          sim::fur::contact_parts(episodes[gesture.first_episode + e], t, parts);
      }
      for (const ContactPart& part : parts) sensor.press(part);
      sensor.set_drift(1.0 + drift_rate * t);
      sensor.advance(dt);
      if (!parts.empty()) {
        auto& total = impulse[gesture_cursor];
        for (int cell = 0; cell < sensor.cell_count(); ++cell)
          total[cell] += sensor.cell_force()[cell] * dt;
      }
    }
    for (int cell = 0; cell < sensor.cell_count(); ++cell)
      stream.samples(frame, sensor.channel(cell)) = sim::quantize(
          sensor.filtered()[cell] + noise.normal(0.0, kFrameNoiseCounts), 0.0, 1023.0, 10);
  }

  //---- Recording and ground truth
  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = simulated_recording_id("fur", subject, trial);
  recording.layout_id = "fur";
  recording.metadata = sim::simulated_metadata("fur", subject, trial, "", "");
  recording.metadata["approach"] = sim::fur::approach_name(approach);
  recording.metadata["repetitions"] = std::to_string(repetitions);
  recording.metadata["signal"] = "raw ADC counts, falling under pressure (use 1023 - raw)";
  recording.metadata["calibration_peak"] = calibration;
  recording.streams.push_back(std::move(stream));

  for (size_t k = 0; k < planned.size(); ++k) {
    result.labels.push_back(sim::ground_truth_label(recording.id, planned[k].start, planned[k].end,
                                                    layout.classes[planned[k].class_index],
                                                    touched_region(layout, sensor, impulse[k])));
  }
  return result;
}

}  // namespace tactile

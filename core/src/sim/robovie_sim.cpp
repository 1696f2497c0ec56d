// Robovie-IIF (paper 003): one scripted 15-stage session per subject and trial, recorded by
// 274 piezo films, with the stage commands as a second stream and one label per stage.

#include "tactile/sim/robovie_sim.h"

#include <algorithm>
#include <cmath>

#include "robovie/robovie_scenario.h"
#include "tactile/error.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile {

namespace {

using sim::robovie::Films;

// Contact impulse (N s) below which a stage counts as untouched: a finger's poke (a few N
// for a fifth of a second) is above it, a hand that only grazes a film's edge is not.
constexpr double kTouchedImpulse = 0.1;

// The body part that carried the most contact force over [t0, t1), or "all" when nobody
// touched. Measured on the contact loads before the sensor, i.e. what really happened.
std::string touched_part(const Films& films, const SampleMatrix& contact_load, double rate_hz,
                         double t0, double t1) {
  const int64_t first =
      std::clamp<int64_t>(static_cast<int64_t>(std::ceil(t0 * rate_hz)), 0, contact_load.rows());
  const int64_t last = std::clamp<int64_t>(static_cast<int64_t>(std::ceil(t1 * rate_hz)), first,
                                           contact_load.rows());
  if (last <= first) return "all";
  const Eigen::VectorXd per_film =
      contact_load.middleRows(first, last - first).colwise().sum().cast<double>().transpose() /
      rate_hz;
  std::vector<double> per_part(films.body_parts.size(), 0.0);
  for (int64_t film = 0; film < films.count(); ++film)
    per_part[films.body_part[film]] += per_film[film];
  const auto most = std::max_element(per_part.begin(), per_part.end());
  if (most == per_part.end() || *most < kTouchedImpulse) return "all";
  return films.body_parts[most - per_part.begin()];
}

}  // namespace

SimulatedTrial simulate_robovie_trial(const SkinLayout& layout, const SimulationOptions& options,
                                      int subject, int trial) {
  using namespace sim::robovie;
  if (subject < 0) throw Error("subject", "must be 0 or more, got " + std::to_string(subject));
  if (trial < 0) throw Error("trial", "must be 0 or more, got " + std::to_string(trial));
  const Films films = films_of(layout);
  const Habits habits = draw_habits(options.seed, subject);
  const Session session = play_session(films, layout.classes, habits, options.seed, subject, trial);

  const double rate = kSampleRate;
  const int64_t samples = static_cast<int64_t>(std::ceil(session.end * rate));
  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = simulated_recording_id("robovie", subject, trial);
  recording.layout_id = "robovie";
  recording.metadata = sim::simulated_metadata("robovie", subject, trial, "", "");
  recording.metadata["approach"] = approach_name(session.approach);
  recording.metadata["robot"] = "moving";  // it gestures while it speaks

  Stream skin = sim::make_stream(layout, "skin", rate, samples);
  for (const Contact& contact : session.contacts)
    add_contact_load(films, contact, rate, skin.samples);

  // One label per stage, from its command to the next (Sec. IV-C: auto-labelled).
  const int stages = static_cast<int>(session.commands.size());
  for (int stage = 0; stage < stages; ++stage) {
    const double t0 = session.commands[stage];
    const double t1 =
        stage + 1 < stages ? session.commands[stage + 1] : static_cast<double>(samples) / rate;
    result.labels.push_back(
        sim::ground_truth_label(recording.id, t0, t1, layout.classes[stage],
                                touched_part(films, skin.samples, rate, t0, t1)));
  }

  // The labels above name the part the hands pressed; the rubber spreads it from here on.
  spread_through_skin(films, skin.samples);
  const Robot robot = make_robot(films, options.seed);
  const Eigen::MatrixXf angles = joint_angles(session.moves, rate, samples);
  add_joint_load(robot, angles, skin.samples);
  Random noise(derive_engine(options.seed, "robovie-noise", subject, trial));
  piezo_output(robot, angles, rate, noise, skin.samples);
  recording.streams.push_back(std::move(skin));

  // The operator's start command of each stage, as sent: irregular time stamps.
  Stream commands;
  commands.name = "commands";
  commands.rate_hz = 0.0;
  commands.channels = {"stage"};
  commands.units = {""};
  commands.samples.resize(stages, 1);
  for (int stage = 0; stage < stages; ++stage)
    commands.samples(stage, 0) = static_cast<float>(stage);
  commands.timestamps = session.commands;
  recording.streams.push_back(std::move(commands));
  return result;
}

}  // namespace tactile

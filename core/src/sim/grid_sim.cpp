// A large uncalibrated pressure grid touched with seven social gestures (grid_sim.h): the
// hand's contact patches as pressure over time, then the sensor's counts.

#include "tactile/sim/grid_sim.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tactile/error.h"
#include "tactile/sim/sim_util.h"

namespace tactile {

namespace {

enum GridGesture { kTap, kPat, kPush, kStroke, kSlap, kTickle, kSqueeze, kGridGestureCount };

// Touches per gesture in one trial by default: five subjects give 350 touches, about the
// 330 of the inflatable robot's set.
constexpr int kGridRepetitions = 10;
// 10-bit ADC; the pressure at which a taxel reads half its span above rest.
constexpr double kGridFullCount = 1023.0;
constexpr double kGridSpanCounts = 620.0;
// Share of a row's summed response that leaks onto every taxel of that row (the shared row
// line of a resistive matrix).
constexpr double kRowCrosstalk = 0.01;
// Share of the whole grid's summed response every taxel feels: pressing an inflated body
// raises its air pressure everywhere.
constexpr double kBodyCoupling = 0.0005;

// The smallest contact patch's semi-axis, taxels.
constexpr double kSmallestPatch = 0.6;

// How one person touches: kept over that person's trials.
struct GridHabits {
  double hand = 1.0;    // contact size scale
  double force = 1.0;   // pressure scale
  double pace = 1.0;    // duration scale (> 1: slower)
  double pause = 1.0;   // pause scale
  double rests = 0.15;  // chance that a hand rests lightly during a long pause
};

// One contact patch: an elliptic pressure bump moving from `from` to `to` (minimum jerk)
// with an optional back-and-forth wobble, under a raised-cosine envelope.
struct Patch {
  double onset = 0.0, duration = 0.0, rise = 0.0, fall = 0.0;
  double force = 0.0;
  double row0 = 0.0, column0 = 0.0, row1 = 0.0, column1 = 0.0;
  double along = 1.0, across = 1.0, angle = 0.0;  // semi-axes (taxels), orientation (rad)
  double wobble = 0.0, wobble_hz = 0.0;           // back and forth along `angle`, taxels
  double flutter = 0.0;                           // share of force that flutters at wobble_hz
};

GridHabits draw_grid_habits(uint64_t seed, int subject) {
  Random random(derive_engine(seed, "grid-subject", subject));
  GridHabits habits;
  habits.hand = random.uniform(0.75, 1.35);
  habits.force = random.uniform(0.5, 1.8);
  habits.pace = random.uniform(0.6, 1.6);
  habits.pause = random.uniform(0.6, 1.6);
  habits.rests = random.uniform(0.05, 0.3);
  return habits;
}

// The patches of one gesture starting at `start`; returns its end. Its contacts (grid_contacts)
// are its touches.
double add_gesture(int gesture, double start, int64_t rows, int64_t columns,
                   const GridHabits& habits, Random& random, std::vector<Patch>& patches) {
  const double last_row = static_cast<double>(rows - 1),
               last_column = static_cast<double>(columns - 1);
  // This touch's size, force and pace: wide and overlapping between gestures, as people vary.
  const double size = habits.hand * std::exp(random.uniform(std::log(0.5), std::log(2.0)));
  const double force = habits.force * std::exp(random.uniform(std::log(0.6), std::log(1.6)));
  const double pace = habits.pace * std::exp(random.uniform(std::log(0.7), std::log(1.5)));
  // Hand gestures done with a few fingers instead, now and then.
  const double hand = random.chance(0.3) ? 0.4 : 1.0;
  const double angle = random.uniform(0.0, std::numbers::pi);
  const double row = random.uniform(0.0, last_row), column = random.uniform(0.0, last_column);
  Patch patch;
  patch.onset = start;
  patch.row0 = patch.row1 = row;
  patch.column0 = patch.column1 = column;
  patch.angle = angle;
  double end = start;
  auto add = [&](Patch made) {
    // A fingertip covers at least one taxel's middle wherever it lands.
    made.along = std::max(made.along, kSmallestPatch);
    made.across = std::max(made.across, kSmallestPatch);
    patches.push_back(made);
    end = std::max(end, made.onset + made.duration);
  };
  switch (gesture) {
    case kTap:  // a fingertip, briefly
      patch.along = patch.across = 0.45 * size;
      patch.duration = random.uniform(0.08, 0.3) * pace;
      patch.rise = patch.fall = 0.03;
      patch.force = 0.8 * force;
      add(patch);
      break;
    case kPat: {  // a flat hand, two or three light pats
      patch.along = 2.0 * size * hand;
      patch.across = 1.6 * size * hand;
      const int64_t pats = random.integer(1, 3);
      double at = start;
      for (int64_t k = 0; k < pats; ++k) {
        patch.onset = at;
        patch.duration = random.uniform(0.1, 0.3) * pace;
        patch.rise = patch.fall = 0.05;
        patch.force = 0.55 * force * random.uniform(0.8, 1.2);
        add(patch);
        at += patch.duration + random.uniform(0.08, 0.2) * pace;
      }
      break;
    }
    case kPush:  // fingers or palm pressed and held
      patch.along = random.uniform(0.6, 2.0) * size * hand;
      patch.across = patch.along * random.uniform(0.7, 1.0);
      patch.duration = random.uniform(0.4, 1.8) * pace;
      patch.rise = 0.25 * pace;
      patch.fall = 0.2 * pace;
      patch.force = 0.8 * force;
      add(patch);
      break;
    case kStroke: {  // a palm drawn across, along its long axis
      patch.along = 1.8 * size * hand;
      patch.across = 1.2 * size * hand;
      const double reach = random.uniform(0.15, 0.6) * std::max(last_row, last_column);
      patch.row1 = std::clamp(row + reach * std::sin(angle), 0.0, last_row);
      patch.column1 = std::clamp(column + reach * std::cos(angle), 0.0, last_column);
      patch.duration = random.uniform(0.4, 1.4) * pace;
      patch.rise = patch.fall = 0.15 * pace;
      patch.force = 0.5 * force;
      add(patch);
      break;
    }
    case kSlap:  // a whole hand, hard and short
      patch.along = 2.2 * size * hand;
      patch.across = 1.8 * size * hand;
      patch.duration = random.uniform(0.06, 0.22) * pace;
      patch.rise = 0.02;
      patch.fall = 0.03;
      patch.force = 1.2 * force;
      add(patch);
      break;
    case kTickle: {  // fingertips wiggling back and forth, lightly
      const int64_t fingers = random.integer(2, 4);
      const double duration = random.uniform(0.5, 1.6) * pace;
      const double gap = 1.6 * habits.hand;
      for (int64_t finger = 0; finger < fingers; ++finger) {
        Patch tip = patch;
        const double offset =
            (static_cast<double>(finger) - 0.5 * static_cast<double>(fingers - 1)) * gap;
        tip.row0 = tip.row1 = std::clamp(row + offset * std::cos(angle), 0.0, last_row);
        tip.column0 = tip.column1 = std::clamp(column - offset * std::sin(angle), 0.0, last_column);
        tip.along = tip.across = 0.5 * size;
        tip.onset = start + random.uniform(0.0, 0.1);
        tip.duration = duration - (tip.onset - start);
        tip.rise = tip.fall = 0.1;
        tip.force = 0.4 * force;
        tip.wobble = random.uniform(0.6, 1.5) * habits.hand;
        tip.wobble_hz = random.uniform(3.0, 6.0);
        tip.flutter = 0.6;
        add(tip);
      }
      break;
    }
    case kSqueeze: {  // a hug: a large share of the grid, slowly, breathing
      const double extent = std::min(last_row, last_column) + 1.0;
      patch.along = random.uniform(0.2, 0.45) * extent * habits.hand;
      patch.across = patch.along * random.uniform(0.6, 0.9);
      patch.duration = random.uniform(0.8, 2.4) * pace;
      patch.rise = 0.4 * pace;
      patch.fall = 0.3 * pace;
      patch.force = 0.9 * force;
      patch.wobble_hz = random.uniform(0.4, 0.8);
      patch.flutter = 0.15;
      add(patch);
      break;
    }
    default:
      throw Error("grid simulator", "no gesture " + std::to_string(gesture));
  }
  return end;
}

// The touches of one gesture made of patches[first...]: a contact is a set of patches that
// overlap in time (a tickle's fingers); a release between two patches (a pat's pats) is a
// boundary, so each contact is its own labelled touch of the gesture's class (issue 26: "the
// release between them is the boundary, however short").
void add_grid_contacts(int gesture, const std::vector<Patch>& patches, size_t first,
                       std::vector<GridTouch>& touches) {
  std::vector<size_t> order;
  for (size_t k = first; k < patches.size(); ++k) order.push_back(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return patches[a].onset < patches[b].onset; });
  const size_t before = touches.size();
  for (size_t k : order) {
    const Patch& patch = patches[k];
    const double end = patch.onset + patch.duration;
    if (touches.size() > before && patch.onset < touches.back().t1) {
      GridTouch& touch = touches.back();
      touch.t1 = std::max(touch.t1, end);
      touch.radius = std::max(patch.along, patch.across);
      touch.force = patch.force;
      continue;
    }
    GridTouch touch;
    touch.gesture = gesture;
    touch.t0 = patch.onset;
    touch.t1 = end;
    touch.row = patch.row0;
    touch.column = patch.column0;
    touch.radius = std::max(patch.along, patch.across);
    touch.force = patch.force;
    touches.push_back(touch);
  }
}

// Pauses down to a fraction of a second, log-uniform up to a few seconds.
double draw_pause(const GridHabits& habits, Random& random) {
  return habits.pause * std::exp(random.uniform(std::log(0.3), std::log(3.0)));
}

// The gesture order: each class `repetitions` times, no class twice in a row where that can
// be avoided, except the taps, which come in bursts of one to three.
std::vector<int> grid_order(int repetitions, Random& random) {
  std::vector<int> others;
  for (int gesture : sim::shuffled_classes(kGridGestureCount, repetitions, random))
    if (gesture != kTap) others.push_back(gesture);
  std::vector<int> order = others;
  int taps = repetitions;
  while (taps > 0) {
    const int burst = std::min<int>(taps, static_cast<int>(random.integer(1, 3)));
    const auto at =
        static_cast<std::ptrdiff_t>(random.integer(0, static_cast<int64_t>(order.size())));
    order.insert(order.begin() + at, static_cast<size_t>(burst), kTap);
    taps -= burst;
  }
  return order;
}

// The touches of a trial in time order and every patch that presses (the resting hands'
// too); `seconds` the recording's length.
std::vector<GridTouch> play_grid_session(int64_t rows, int64_t columns,
                                         const SimulationOptions& options, int subject, int trial,
                                         std::vector<Patch>& patches, double& seconds) {
  const GridHabits habits = draw_grid_habits(options.seed, subject);
  Random random(derive_engine(options.seed, "grid-touches", subject, trial));
  const int repetitions = options.repetitions > 0 ? options.repetitions : kGridRepetitions;
  const std::vector<int> order = grid_order(repetitions, random);
  std::vector<GridTouch> touches;
  double t = random.uniform(1.5, 3.0);
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t first = patches.size();
    t = add_gesture(order[k], t, rows, columns, habits, random, patches);
    add_grid_contacts(order[k], patches, first, touches);
    const bool burst = order[k] == kTap && k + 1 < order.size() && order[k + 1] == kTap;
    const double pause =
        burst ? random.uniform(0.12, 0.35) * habits.pace : draw_pause(habits, random);
    // A hand left resting lightly on the skin in a long pause: not a gesture, not labelled.
    if (!burst && pause > 1.2 && random.chance(habits.rests)) {
      Patch resting;
      resting.onset = t + 0.3;
      resting.duration = pause - 0.6;
      resting.rise = resting.fall = 0.25;
      resting.force = random.uniform(0.06, 0.15) * habits.force;
      resting.row0 = resting.row1 = random.uniform(0.0, static_cast<double>(rows - 1));
      resting.column0 = resting.column1 = random.uniform(0.0, static_cast<double>(columns - 1));
      resting.along = 2.5 * habits.hand;
      resting.across = 1.8 * habits.hand;
      resting.angle = random.uniform(0.0, std::numbers::pi);
      patches.push_back(resting);
    }
    t += pause;
  }
  seconds = t + 1.5;
  return touches;
}

// What patches press on taxel (row, column) at time t.
double patch_pressure(const Patch& patch, double t, double row, double column) {
  const double envelope =
      sim::contact_envelope(t, patch.onset, patch.duration, patch.rise, patch.fall);
  if (envelope <= 0.0) return 0.0;
  const double progress = sim::minimum_jerk((t - patch.onset) / patch.duration);
  const double phase = 2.0 * std::numbers::pi * patch.wobble_hz * (t - patch.onset);
  const double swing = patch.wobble * std::sin(phase);
  const double c = std::cos(patch.angle), s = std::sin(patch.angle);
  const double centre_row = patch.row0 + (patch.row1 - patch.row0) * progress + swing * s;
  const double centre_column =
      patch.column0 + (patch.column1 - patch.column0) * progress + swing * c;
  const double d_row = row - centre_row, d_column = column - centre_column;
  const double along = d_column * c + d_row * s, across = -d_column * s + d_row * c;
  const double q =
      along * along / (patch.along * patch.along) + across * across / (patch.across * patch.across);
  if (q > 16.0) return 0.0;
  const double flutter = 1.0 - patch.flutter * 0.5 * (1.0 - std::cos(phase));
  // A flattened bump: a hand presses evenly in its middle and fades at its edge.
  return patch.force * envelope * flutter * std::exp(-q * q * 0.5 - q * 0.5);
}

int64_t grid_rows_of(const SkinLayout& layout) {
  int64_t rows = 0;
  for (const Group& group : layout.groups)
    if (group.kind == "row") ++rows;
  if (!is_generic_layout_id(layout.id) || layout.id.rfind("grid:", 0) != 0 || rows < 1 ||
      static_cast<int64_t>(layout.taxels.size()) % rows != 0)
    throw Error("layout " + layout.id, "the grid simulator needs a grid:RxC layout");
  return rows;
}

}  // namespace

const std::vector<std::string>& grid_gesture_classes() {
  static const std::vector<std::string> classes = {"tap",  "pat",    "push",   "stroke",
                                                   "slap", "tickle", "squeeze"};
  return classes;
}

std::string grid_recording_id(const std::string& layout_id, int subject, int trial) {
  std::string skin = layout_id;
  std::replace(skin.begin(), skin.end(), ':', '-');
  return simulated_recording_id(skin, subject, trial);
}

std::vector<GridTouch> plan_grid_touches(int64_t rows, int64_t columns,
                                         const SimulationOptions& options, int subject, int trial,
                                         double& seconds) {
  std::vector<Patch> patches;
  return play_grid_session(rows, columns, options, subject, trial, patches, seconds);
}

SimulatedTrial simulate_grid_trial(const SkinLayout& layout, const SimulationOptions& options,
                                   int subject, int trial) {
  if (subject < 0) throw Error("subject", "must be 0 or more, got " + std::to_string(subject));
  if (trial < 0) throw Error("trial", "must be 0 or more, got " + std::to_string(trial));
  if (options.repetitions < 0) throw Error("--repetitions", "must not be negative");
  const int64_t rows = grid_rows_of(layout);
  const int64_t columns = static_cast<int64_t>(layout.taxels.size()) / rows;
  const int64_t taxels = rows * columns;

  std::vector<Patch> patches;
  double seconds = 0.0;
  const std::vector<GridTouch> touches =
      play_grid_session(rows, columns, options, subject, trial, patches, seconds);
  const double rate = kGridRateHz;
  const auto samples = static_cast<int64_t>(std::ceil(seconds * rate));

  // The device: one per seed and grid, whoever touches it.
  Random device(derive_engine(options.seed, "grid-sensor", rows, columns));
  Eigen::ArrayXd offset(taxels), gain(taxels), noise(taxels), drift(taxels), drift_hz(taxels),
      drift_phase(taxels);
  for (int64_t k = 0; k < taxels; ++k) {
    offset(k) = device.uniform(40.0, 220.0);
    gain(k) = device.uniform(0.75, 1.25);
    noise(k) = device.uniform(0.8, 2.5);
    drift(k) = device.uniform(1.0, 6.0);
    drift_hz(k) = 1.0 / device.uniform(60.0, 240.0);
    drift_phase(k) = device.uniform(0.0, 2.0 * std::numbers::pi);
  }
  // About one taxel in a hundred is broken: dead ones read 0, stuck ones a fixed high count.
  std::vector<int> broken(static_cast<size_t>(taxels), 0);  // 0 fine, 1 dead, 2 stuck
  const int64_t broken_count = std::max<int64_t>(1, taxels / 100);
  for (int64_t k = 0; k < broken_count; ++k)
    broken[static_cast<size_t>(device.integer(0, taxels - 1))] = k % 2 == 0 ? 1 : 2;
  const double stuck_count = std::round(device.uniform(900.0, 1000.0));

  // Pressure per frame and taxel, then the sensor.
  Eigen::MatrixXd pressure = Eigen::MatrixXd::Zero(samples, taxels);
  for (const Patch& patch : patches) {
    const auto first = std::max<int64_t>(0, static_cast<int64_t>(std::floor(patch.onset * rate)));
    const auto last = std::min<int64_t>(
        samples, static_cast<int64_t>(std::ceil((patch.onset + patch.duration) * rate)) + 1);
    for (int64_t frame = first; frame < last; ++frame) {
      const double time = static_cast<double>(frame) / rate;
      for (int64_t k = 0; k < taxels; ++k)
        pressure(frame, k) += patch_pressure(patch, time, static_cast<double>(k / columns),
                                             static_cast<double>(k % columns));
    }
  }
  // A taxel's response saturates: half its span at pressure 1.
  Eigen::MatrixXd response =
      (pressure.array() / (pressure.array() + 1.0)).matrix() * kGridSpanCounts;
  response.array().rowwise() *= gain.transpose();
  Eigen::MatrixXd leak = Eigen::MatrixXd::Zero(samples, taxels);
  for (int64_t row = 0; row < rows; ++row) {
    const Eigen::VectorXd line =
        response.middleCols(row * columns, columns).rowwise().sum() * kRowCrosstalk;
    leak.middleCols(row * columns, columns).colwise() += line;
  }
  leak.colwise() += response.rowwise().sum() * kBodyCoupling;

  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = grid_recording_id(layout.id, subject, trial);
  recording.layout_id = layout.id;
  recording.metadata = sim::simulated_metadata(layout.id, subject, trial, "", "");
  recording.metadata["units"] = "counts (10-bit, uncalibrated)";
  Stream stream = sim::make_stream(layout, "skin", rate, samples);
  Random draws(derive_engine(options.seed, "grid-noise", subject, trial));
  const double common_drift = draws.uniform(-8.0, 8.0) / std::max(1.0, seconds);
  const double trial_phase = draws.uniform(0.0, 2.0 * std::numbers::pi);
  for (int64_t frame = 0; frame < samples; ++frame) {
    const double time = static_cast<double>(frame) / rate;
    for (int64_t k = 0; k < taxels; ++k) {
      const int state = broken[static_cast<size_t>(k)];
      const double wander = drift(k) * std::sin(2.0 * std::numbers::pi * drift_hz(k) * time +
                                                drift_phase(k) + trial_phase);
      const double value = offset(k) + wander + common_drift * time + response(frame, k) +
                           leak(frame, k) + draws.normal(0.0, noise(k));
      const double count = state == 1 ? 0.0 : state == 2 ? stuck_count : std::round(value);
      stream.samples(frame, k) = static_cast<float>(std::clamp(count, 0.0, kGridFullCount));
    }
  }
  recording.streams.push_back(std::move(stream));

  for (const GridTouch& touch : touches) {
    result.labels.push_back(
        sim::ground_truth_label(recording.id, touch.t0, touch.t1,
                                grid_gesture_classes()[static_cast<size_t>(touch.gesture)], "all"));
  }
  return result;
}

}  // namespace tactile

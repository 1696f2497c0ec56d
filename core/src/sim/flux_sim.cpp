// Simulated recordings of the silicone flux sensor (paper 004): a fingertip pressing on one of
// the four zones or sliding across them, seen through the sensor's mechanics (load spreading
// through the cover, lateral stretch, visco-elastic creep and ~7 s relaxation), its temperature
// dependent gain and baseline, and its constant-current, 10-bit read-out.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/sim/flux_sensor.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile {

namespace {

using sim::FingerContact;
using sim::FluxGeometry;

constexpr int kFluxRepetitions = 10;
// The paper's relaxation, "almost 7 seconds" (§5.2).
constexpr double kRelaxationTime = 7.0;  // s
// Rest between gestures, drawn independently of the class. The spec's analysis window is 5 s
// from onset and its segmenter waits until every channel is back under 5 % for 0.5 s; with a
// 7 s relaxation that takes 10-15 s after a firm press, so the experimenter waits that long.
constexpr double kRestMin = 15.0, kRestMax = 21.0;  // s
constexpr double kMainsHz = 50.0;

//---- Subjects and gestures

// A subject's habits: nobody is told how hard, how long or where to touch.
struct Subject {
  double touch_force;         // N, mean press force
  double caress_force_ratio;  // a caress is lighter than a press, by this much
  double finger_spread;       // mm, footprint standard deviation across the finger
  double finger_elongation;   // footprint along / across
  double finger_angle;        // rad, long axis of the footprint from the u axis
  double hold_time;           // s, mean press duration
  double press_rise;          // s, time to load (and unload) the finger
  double caress_time;         // s, mean time to slide across the sensor
  double aim_bias;            // mm, habitual offset of presses from a zone's centre line
  double preferred_v;         // share of the sensor's length where the finger lands
  double caress_tilt;         // rad, angle of the sliding path to the u axis
  double caress_inset;        // mm, how far inside the first zone a slide starts
  double tremor_hz, tremor_depth;
};

Subject draw_subject(Random& random) {
  Subject subject;
  subject.touch_force = random.uniform(1.0, 2.8);
  subject.caress_force_ratio = random.uniform(0.55, 0.95);
  subject.finger_spread = random.uniform(2.8, 4.2);
  subject.finger_elongation = random.uniform(1.1, 1.5);
  subject.finger_angle = random.uniform(0.0, std::numbers::pi);
  subject.hold_time = random.uniform(0.25, 1.2);
  subject.press_rise = random.uniform(0.04, 0.15);
  subject.caress_time = random.uniform(0.55, 1.35);
  subject.aim_bias = random.truncated_normal(0.0, 1.5);
  subject.preferred_v = random.uniform(0.3, 0.7);
  subject.caress_tilt = random.truncated_normal(0.0, 0.15);
  subject.caress_inset = random.uniform(0.0, 7.0);
  subject.tremor_hz = random.uniform(8.0, 12.0);
  subject.tremor_depth = random.uniform(0.01, 0.04);
  return subject;
}

// What a class asks of the hand: a press on one zone, or a slide from one zone to another.
struct ClassIntent {
  bool slide = false;
  int from_zone = 0;  // 1-based zone number
  int to_zone = 0;
};

// Reads the paper's class names as the layout spells them: touch<k>, caress<a><b>.
ClassIntent parse_class(const std::string& name, const std::string& where) {
  auto digit = [&](size_t at) {
    if (at >= name.size() || name[at] < '1' || name[at] > '9')
      throw Error(where, "class \"" + name + "\" is not touch<zone> or caress<from><to>");
    return name[at] - '0';
  };
  ClassIntent intent;
  if (name.rfind("touch", 0) == 0 && name.size() == 6) {
    intent.from_zone = intent.to_zone = digit(5);
  } else if (name.rfind("caress", 0) == 0 && name.size() == 8) {
    intent.slide = true;
    intent.from_zone = digit(6);
    intent.to_zone = digit(7);
  } else {
    throw Error(where, "class \"" + name + "\" is not touch<zone> or caress<from><to>");
  }
  return intent;
}

// Where a zone lies on the surface: the union of its serpentines' rectangles along u.
struct Zone {
  std::string group;
  double u0 = 0.0, u1 = 0.0;
  double centre() const { return 0.5 * (u0 + u1); }
};

std::vector<Zone> zones_of(const SkinLayout& layout, const FluxGeometry& geometry,
                           const std::string& where) {
  std::vector<Zone> zones;
  for (int number = 1;; ++number) {
    const Group* group = layout.find_group("zone" + std::to_string(number));
    if (group == nullptr) break;
    Zone zone{group->id, 1e300, -1e300};
    for (int64_t id : group->taxels)
      for (const sim::Serpentine& serpentine : geometry.serpentines)
        if (serpentine.taxel_id == id) {
          zone.u0 = std::min(zone.u0, serpentine.u0);
          zone.u1 = std::max(zone.u1, serpentine.u1);
        }
    if (zone.u1 < zone.u0) throw Error(where, "group " + group->id + " holds no serpentine");
    zones.push_back(zone);
  }
  if (zones.empty()) throw Error(where, "no zone groups (zone1, zone2, ...)");
  return zones;
}

// One gesture as the hand performs it.
struct FluxGesture {
  int class_index = 0;
  std::string region;
  double onset = 0.0, duration = 0.0, rise = 0.0, fall = 0.0;     // s
  double force = 0.0;                                             // N, at full contact
  double u_start = 0.0, v_start = 0.0, u_end = 0.0, v_end = 0.0;  // mm
  double tremor_phase = 0.0;
  double end() const { return onset + duration; }
};

// Log-normal factor with median 1: habits vary from one repetition to the next.
double jitter(Random& random, double spread) {
  return std::exp(random.truncated_normal(0.0, spread));
}

FluxGesture plan_gesture(const ClassIntent& intent, const std::vector<Zone>& zones,
                         const FluxGeometry& geometry, const Subject& subject, Random& random,
                         const std::string& where, const std::string& class_name) {
  const int zone_count = static_cast<int>(zones.size());
  if (intent.from_zone > zone_count || intent.to_zone > zone_count)
    throw Error(where, "class \"" + class_name + "\" names a zone the layout lacks");
  const Zone& from = zones[intent.from_zone - 1];
  const Zone& to = zones[intent.to_zone - 1];
  const double margin = 2.0;  // mm: the finger's centre stays on the sensor
  auto on_surface_v = [&](double v) { return std::clamp(v, margin, geometry.height - margin); };

  FluxGesture gesture;
  gesture.v_start = on_surface_v(subject.preferred_v * geometry.height + random.normal(0.0, 4.0));
  if (!intent.slide) {
    gesture.duration = std::clamp(subject.hold_time * jitter(random, 0.3), 0.12, 3.0);
    gesture.rise = subject.press_rise * jitter(random, 0.2);
    gesture.fall = subject.press_rise * jitter(random, 0.2);
    gesture.force = subject.touch_force * jitter(random, 0.15);
    gesture.u_start = std::clamp(from.centre() + subject.aim_bias + random.normal(0.0, 1.5), margin,
                                 geometry.width - margin);
    // The fingertip rolls a little while it presses.
    gesture.u_end = gesture.u_start + random.normal(0.0, 0.5);
    gesture.v_end = on_surface_v(gesture.v_start + random.normal(0.0, 0.5));
    // Ground truth region: the zone under the finger (nearly always the one aimed at).
    const Zone* touched = &zones[0];
    for (const Zone& zone : zones)
      if (std::abs(zone.centre() - gesture.u_start) < std::abs(touched->centre() - gesture.u_start))
        touched = &zone;
    gesture.region = touched->group;
  } else {
    const double direction = to.centre() >= from.centre() ? 1.0 : -1.0;
    const double inset = std::max(subject.caress_inset + random.normal(0.0, 1.5), 0.0);
    const double outset = std::max(subject.caress_inset + random.normal(0.0, 1.5), 0.0);
    gesture.u_start = direction > 0 ? from.u0 + inset : from.u1 - inset;
    gesture.u_end = direction > 0 ? to.u1 - outset : to.u0 + outset;
    const double tilt = subject.caress_tilt + random.normal(0.0, 0.08);
    gesture.v_end =
        on_surface_v(gesture.v_start + std::abs(gesture.u_end - gesture.u_start) * std::tan(tilt));
    gesture.duration = std::clamp(subject.caress_time * jitter(random, 0.15), 0.4, 2.0);
    gesture.rise = 0.8 * subject.press_rise * jitter(random, 0.2);
    gesture.fall = 0.8 * subject.press_rise * jitter(random, 0.2);
    gesture.force = subject.touch_force * subject.caress_force_ratio * jitter(random, 0.15);
    gesture.region = "all";  // a slide crosses every zone
  }
  gesture.tremor_phase = random.uniform(0.0, 2.0 * std::numbers::pi);
  return gesture;
}

// The finger at time t: position along a minimum-jerk path, force under the contact envelope.
FingerContact finger_at(const FluxGesture& gesture, const Subject& subject, double t) {
  const double s = std::clamp((t - gesture.onset) / gesture.duration, 0.0, 1.0);
  // Flash & Hogan minimum-jerk profile: s' = 10 s^3 - 15 s^4 + 6 s^5.
  const double progress = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
  FingerContact contact;
  contact.u = gesture.u_start + (gesture.u_end - gesture.u_start) * progress;
  contact.v = gesture.v_start + (gesture.v_end - gesture.v_start) * progress;
  const double tremor =
      1.0 + subject.tremor_depth *
                std::sin(2.0 * std::numbers::pi * subject.tremor_hz * t + gesture.tremor_phase);
  contact.force =
      gesture.force * tremor *
      sim::contact_envelope(t, gesture.onset, gesture.duration, gesture.rise, gesture.fall);
  contact.spread_across = subject.finger_spread;
  contact.spread_along = subject.finger_spread * subject.finger_elongation;
  contact.angle = subject.finger_angle;
  return contact;
}

//---- The device

// Manufacturing spread between serpentines of the one device every subject touched.
struct SerpentineTolerance {
  double baseline = 1.0, gain = 1.0, relaxation = kRelaxationTime, hum = 0.0;
};

std::vector<SerpentineTolerance> draw_tolerances(uint64_t seed, size_t count) {
  Random random(derive_engine(seed, "flux-sensor"));
  std::vector<SerpentineTolerance> tolerances(count);
  for (SerpentineTolerance& tolerance : tolerances) {
    tolerance.baseline = 1.0 + random.truncated_normal(0.0, 0.015);
    tolerance.gain = 1.0 + random.truncated_normal(0.0, 0.05);
    tolerance.relaxation = kRelaxationTime * (1.0 + random.truncated_normal(0.0, 0.04));
    tolerance.hum = random.uniform(0.1, 0.4);  // counts of mains pickup on the wiring
  }
  return tolerances;
}

// Room temperature during a trial: a start value, a slow linear drift and a slow wander
// (Ornstein-Uhlenbeck, 2 min correlation), stepped every 0.1 s.
class RoomTemperature {
 public:
  explicit RoomTemperature(Random& random)
      : start_(random.uniform(16.0, 34.0)), drift_per_s_(random.normal(0.0, 1.5) / 600.0) {}
  double start() const { return start_; }
  double step(Random& random, double t, double dt) {
    const double keep = std::exp(-dt / kWanderTime);
    wander_ = wander_ * keep + kWanderSpread * std::sqrt(1.0 - keep * keep) * random.normal();
    return start_ + drift_per_s_ * t + wander_;
  }

 private:
  static constexpr double kWanderTime = 120.0;  // s
  static constexpr double kWanderSpread = 0.2;  // degC
  double start_, drift_per_s_, wander_ = 0.0;
};

// Amplifier noise for a million samples a channel, cheaply: the sum of four 16-bit uniforms of
// one engine draw (Irwin-Hall), scaled to unit variance. Gaussian to within its +-3.5 sd tails.
double noise(Random& random) {
  const uint64_t bits = random.engine()();
  const double sum = static_cast<double>((bits & 0xFFFF) + ((bits >> 16) & 0xFFFF) +
                                         ((bits >> 32) & 0xFFFF) + (bits >> 48)) /
                     65536.0;
  return (sum - 2.0) * std::sqrt(3.0);
}

// The device's ADC, sim::quantize(value, 0, 1023, 10) for a 10-bit converter whose levels are
// whole counts, written out for the hot loop: clamp, then round half up (value is not negative).
static_assert((1 << sim::kFluxAdcBits) - 1 == sim::kFluxAdcMax);
float adc_counts(double value) {
  return static_cast<float>(static_cast<int>(std::clamp(value, 0.0, sim::kFluxAdcMax) + 0.5));
}

// What the device records while the hand performs `gestures`: one row per sample until
// `duration`, one column per real serpentine channel, in ADC counts.
Stream record_skin(const SkinLayout& layout, const FluxGeometry& geometry,
                   const std::vector<FluxGesture>& gestures, const Subject& subject, uint64_t seed,
                   double rate, double duration, Random& random, RoomTemperature& room) {
  const int64_t count = static_cast<int64_t>(std::ceil(duration * rate));
  // The stream holds the device's real channels only; the virtual sums are preprocessing's.
  std::vector<int> real_channels;
  for (const sim::Serpentine& serpentine : geometry.serpentines)
    real_channels.push_back(serpentine.layout_channel);
  std::sort(real_channels.begin(), real_channels.end());
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate;
  for (int channel : real_channels) {
    stream.channels.push_back(layout.channels[channel].name);
    stream.units.push_back(layout.channels[channel].unit);
  }
  const size_t serpentine_count = geometry.serpentines.size();
  std::vector<Eigen::Index> column(serpentine_count);
  for (size_t k = 0; k < serpentine_count; ++k)
    column[k] = std::find(real_channels.begin(), real_channels.end(),
                          geometry.serpentines[k].layout_channel) -
                real_channels.begin();
  stream.samples.resize(count, static_cast<Eigen::Index>(real_channels.size()));

  const std::vector<SerpentineTolerance> tolerances = draw_tolerances(seed, serpentine_count);
  std::vector<sim::ViscoelasticSerpentine> serpentines;
  for (const SerpentineTolerance& tolerance : tolerances)
    serpentines.emplace_back(rate, tolerance.relaxation);
  const double mains_phase = random.uniform(0.0, 2.0 * std::numbers::pi);
  constexpr double kNoiseCounts = 0.5;  // amplifier and ADC noise, rms
  const double counts_per_ohm = sim::flux_counts_per_ohm();
  const int64_t temperature_step = std::max<int64_t>(1, std::llround(0.1 * rate));

  std::vector<double> pressures(serpentine_count, 0.0);
  std::vector<double> baseline_counts(serpentine_count), counts_per_kpa(serpentine_count);
  size_t active = 0;
  bool touching = false;
  for (int64_t n = 0; n < count; ++n) {
    const double t = static_cast<double>(n) / rate;
    if (n % temperature_step == 0) {
      const double temperature = room.step(random, t, temperature_step / rate);
      for (size_t k = 0; k < serpentine_count; ++k) {
        baseline_counts[k] =
            sim::flux_baseline_ohm(temperature) * tolerances[k].baseline * counts_per_ohm;
        counts_per_kpa[k] =
            sim::flux_gain_ohm_per_kpa(temperature) * tolerances[k].gain * counts_per_ohm;
      }
    }
    while (active < gestures.size() && t >= gestures[active].end()) ++active;
    if (active < gestures.size() && t > gestures[active].onset) {
      sim::serpentine_pressures(geometry, finger_at(gestures[active], subject, t),
                                pressures.data());
      touching = true;
    } else if (touching) {
      std::fill(pressures.begin(), pressures.end(), 0.0);
      touching = false;
    }
    const double mains = std::sin(2.0 * std::numbers::pi * kMainsHz * t + mains_phase);
    for (size_t k = 0; k < serpentine_count; ++k) {
      const double response = serpentines[k].step(pressures[k]);
      const double value = baseline_counts[k] + counts_per_kpa[k] * response +
                           tolerances[k].hum * mains + kNoiseCounts * noise(random);
      stream.samples(n, column[k]) = adc_counts(value);
    }
  }

  return stream;
}

}  // namespace

//---- The generator

SimulatedTrial simulate_flux_trial(const SkinLayout& layout, const SimulationOptions& options,
                                   int subject_index, int trial_index) {
  const std::string where = "layout " + layout.id;
  if (options.repetitions < 0)
    throw Error("--repetitions", "must be 0 (the skin's default) or more");
  if (subject_index < 0 || trial_index < 0)
    throw Error("flux simulator", "subject and trial are 0-based and not negative");
  if (layout.classes.empty()) throw Error(where, "no classes to simulate");
  const double rate = layout.sample_rate_hz > 0 ? layout.sample_rate_hz : 1000.0;
  const FluxGeometry geometry = sim::flux_geometry(layout);
  const std::vector<Zone> zones = zones_of(layout, geometry, where);
  std::vector<ClassIntent> intents;
  for (const std::string& name : layout.classes) intents.push_back(parse_class(name, where));

  Random habits(derive_engine(options.seed, "flux-subject", subject_index));
  const Subject subject = draw_subject(habits);
  Random random(derive_engine(options.seed, "flux-trial", subject_index, trial_index));

  // The sequence of gestures and rests.
  const int repetitions = options.repetitions > 0 ? options.repetitions : kFluxRepetitions;
  const std::vector<int> order =
      sim::shuffled_classes(static_cast<int>(layout.classes.size()), repetitions, random);
  std::vector<FluxGesture> gestures;
  double clock = random.uniform(2.0, 4.0);  // lead-in at rest: V0 is taken at start-up
  for (int class_index : order) {
    FluxGesture gesture = plan_gesture(intents[class_index], zones, geometry, subject, random,
                                       where, layout.classes[class_index]);
    gesture.class_index = class_index;
    gesture.onset = clock;
    clock = gesture.end() + random.uniform(kRestMin, kRestMax);
    gestures.push_back(gesture);
  }

  RoomTemperature room(random);
  SimulatedTrial result;
  result.recording.streams.push_back(
      record_skin(layout, geometry, gestures, subject, options.seed, rate, clock, random, room));
  result.recording.id = simulated_recording_id("flux", subject_index, trial_index);
  result.recording.layout_id = layout.id;
  result.recording.metadata =
      sim::simulated_metadata("flux", subject_index, trial_index, "", options.condition);
  char temperature_text[32];
  std::snprintf(temperature_text, sizeof(temperature_text), "%.2f", room.start());
  result.recording.metadata["temperature_c"] = temperature_text;

  for (const FluxGesture& gesture : gestures) {
    result.labels.push_back(
        sim::ground_truth_label(result.recording.id, gesture.onset, gesture.end(),
                                layout.classes[gesture.class_index], gesture.region));
  }
  return result;
}

}  // namespace tactile

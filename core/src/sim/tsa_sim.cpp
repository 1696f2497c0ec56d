// The `tsa` touch plan: subjects with their habits, six touch behaviours (paper 001 Table 2)
// performed one after another on sheets of the robot's shell, and ground-truth labels.
//
// What separates the classes is only what the hand does: a fingertip, a finger pad or a palm
// (how many pads it covers), how long it stays (taps vs pokes vs slides) and whether and how
// it moves (the ten directions of Fig. 8). The sensor below is the same for every class.

#include "tactile/sim/tsa_sim.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tactile/error.h"
#include "tactile/sim/sim_util.h"

namespace tactile {

namespace sim::tsa {

//---- Names -----------------------------------------------------------------------------------

const char* hand_name(Hand hand) {
  switch (hand) {
    case Hand::kFinger:
      return "finger";
    case Hand::kFingertip:
      return "fingertip";
    case Hand::kPalm:
      return "palm";
  }
  return "finger";
}

const char* direction_name(Direction direction) {
  switch (direction) {
    case Direction::kNone:
      return "none";
    case Direction::kClockwise:
      return "clockwise";
    case Direction::kCounterClockwise:
      return "counter-clockwise";
    case Direction::kLeftToRight:
      return "left->right";
    case Direction::kRightToLeft:
      return "right->left";
    case Direction::kUpToDown:
      return "up->down";
    case Direction::kDownToUp:
      return "down->up";
    case Direction::kUpperLeftToLowerRight:
      return "upper-left->lower-right";
    case Direction::kLowerRightToUpperLeft:
      return "lower-right->upper-left";
    case Direction::kLowerLeftToUpperRight:
      return "lower-left->upper-right";
    case Direction::kUpperRightToLowerLeft:
      return "upper-right->lower-left";
  }
  return "none";
}

Point2 direction_vector(Direction direction) {
  const double diagonal = std::numbers::sqrt2 / 2.0;
  switch (direction) {
    case Direction::kLeftToRight:
      return {1.0, 0.0};
    case Direction::kRightToLeft:
      return {-1.0, 0.0};
    case Direction::kUpToDown:
      return {0.0, 1.0};
    case Direction::kDownToUp:
      return {0.0, -1.0};
    case Direction::kUpperLeftToLowerRight:
      return {diagonal, diagonal};
    case Direction::kLowerRightToUpperLeft:
      return {-diagonal, -diagonal};
    case Direction::kLowerLeftToUpperRight:
      return {diagonal, -diagonal};
    case Direction::kUpperRightToLowerLeft:
      return {-diagonal, diagonal};
    default:
      return {0.0, 0.0};
  }
}

namespace {

constexpr int kClassCount = 6;  // T1..T6
constexpr int kDirectionCount = 10;

enum class Motion { kTap, kPoke, kSlide };

// A subject's habits: drawn once per subject, so they persist across trials.
struct Habits {
  bool male = true;
  double finger_half_width = 6.0;  // mm, contact of the finger pad
  double finger_elongation = 1.3;  // length / width of that contact
  double palm_half_width = 15.0;   // mm, palm contact on the curved shell
  double palm_elongation = 1.2;
  double tap_duration = 0.18;    // s of contact in a momentary tap
  double poke_duration = 0.45;   // s a poking fingertip stays pressed
  double slow_speed = 11.0;      // mm/s of a slow slide
  double finger_speed = 55.0;    // mm/s of a finger slide
  double palm_speed = 95.0;      // mm/s of a palm sweep
  double stroke_length = 23.0;   // mm of a straight finger stroke
  double palm_preference = 0.4;  // chance of using the palm where the hand is free (T1, T2)
  double orientation = 1.57;     // rad, long axis of the hand on the map
  Point2 aim_offset;             // mm, where a subject's aimed strokes centre on a sheet
  double bow = 0.0;              // mm, sideways curve of straight strokes
  double approach = 0.03;        // s from the field's reach to the skin lying flat
  double coupling = 1.0;         // body-to-ground coupling of the hand
  std::vector<double> location_weights;
  std::vector<double> direction_weights;
};

int weighted_index(const std::vector<double>& weights, Random& random) {
  double total = 0.0;
  for (double weight : weights) total += weight;
  double draw = random.uniform(0.0, total);
  for (size_t k = 0; k < weights.size(); ++k) {
    if (draw < weights[k]) return static_cast<int>(k);
    draw -= weights[k];
  }
  return static_cast<int>(weights.size()) - 1;
}

Habits draw_habits(uint64_t seed, int subject, size_t location_count) {
  Random random(derive_engine(seed, "tsa-subject", subject));
  Habits habits;
  // The paper's two groups, adult male and female, alternate so every split holds both.
  habits.male = subject % 2 == 0;
  // Contact sizes on a hard shell at light force: finger pads about 10 mm wide (male) vs
  // 9 mm (female), a little longer than wide; palms lie only partly on the curved shell.
  habits.finger_half_width = random.truncated_normal(habits.male ? 5.0 : 4.4, 0.4);
  habits.finger_elongation = random.uniform(1.15, 1.35);
  habits.palm_half_width = random.truncated_normal(habits.male ? 16.0 : 13.5, 1.3);
  habits.palm_elongation = random.uniform(1.1, 1.3);
  const double speed_factor = habits.male ? random.uniform(0.95, 1.25) : random.uniform(0.8, 1.05);
  habits.tap_duration = random.uniform(0.14, 0.28);
  habits.poke_duration = random.uniform(0.25, 0.8);
  habits.slow_speed = random.uniform(6.0, 16.0) * speed_factor;
  habits.finger_speed = random.uniform(35.0, 90.0) * speed_factor;
  habits.palm_speed = random.uniform(60.0, 140.0) * speed_factor;
  habits.stroke_length = random.uniform(15.0, 32.0);
  habits.palm_preference = random.uniform(0.1, 0.8);
  habits.orientation = random.uniform(0.0, std::numbers::pi);
  habits.aim_offset = {random.normal(0.0, 3.0), random.normal(0.0, 3.0)};
  habits.bow = random.uniform(-3.0, 3.0);
  habits.approach = random.uniform(0.02, 0.05);
  habits.coupling = random.uniform(0.88, 1.12);
  for (size_t k = 0; k < location_count; ++k) {
    const double weight = random.uniform();
    habits.location_weights.push_back(0.05 + weight * weight);
  }
  for (int k = 0; k < kDirectionCount; ++k)
    habits.direction_weights.push_back(random.uniform(0.1, 1.0));
  return habits;
}

struct Place {
  std::vector<std::string> locations;                // location ids, in layout order
  std::vector<std::vector<int>> sheets_by_location;  // sheet indices per location
};

Place index_places(const std::vector<Sheet>& sheets) {
  Place place;
  for (size_t s = 0; s < sheets.size(); ++s) {
    const auto found =
        std::find(place.locations.begin(), place.locations.end(), sheets[s].location);
    const size_t index = static_cast<size_t>(found - place.locations.begin());
    if (found == place.locations.end()) {
      place.locations.push_back(sheets[s].location);
      place.sheets_by_location.emplace_back();
    }
    place.sheets_by_location[index].push_back(static_cast<int>(s));
  }
  return place;
}

// Table 2 of paper 001, as a hand performs it.
Hand hand_of_class(int class_index, const Habits& habits, Random& random) {
  switch (class_index) {
    case 0:  // T1 random momentary tapping: finger or palm
    case 1:  // T2 random slow sliding: finger or palm
      return random.chance(habits.palm_preference) ? Hand::kPalm : Hand::kFinger;
    case 2:
      return Hand::kFinger;  // T3 finger sliding
    case 3:
      return Hand::kFingertip;  // T4 random finger poking
    default:
      return Hand::kPalm;  // T5 palm momentary tapping, T6 palm momentary sliding
  }
}

Motion motion_of_class(int class_index) {
  switch (class_index) {
    case 0:
    case 4:
      return Motion::kTap;
    case 3:
      return Motion::kPoke;
    default:
      return Motion::kSlide;
  }
}

Footprint shape_of_hand(Hand hand, const Habits& habits, Random& random) {
  Footprint shape;
  shape.angle = habits.orientation + random.normal(0.0, 0.3);
  switch (hand) {
    case Hand::kFinger:
      shape.half_width = habits.finger_half_width * random.truncated_normal(1.0, 0.05);
      shape.half_length = shape.half_width * habits.finger_elongation;
      break;
    case Hand::kFingertip:  // only the tip presses when poking
      shape.half_width = 0.7 * habits.finger_half_width * random.truncated_normal(1.0, 0.08);
      shape.half_length = shape.half_width * 1.1;
      break;
    case Hand::kPalm:  // how flat the palm lands on the shell's curve varies
      shape.half_width = habits.palm_half_width * random.truncated_normal(1.0, 0.07);
      shape.half_length = shape.half_width * habits.palm_elongation;
      break;
  }
  return shape;
}

// Plans one touch of `class_index` with its contact starting at `start_time`.
Touch plan_touch(int class_index, double start_time, const Habits& habits,
                 const std::vector<Sheet>& sheets, const Place& place, Random& random) {
  Touch touch;
  touch.class_index = class_index;
  touch.hand = hand_of_class(class_index, habits, random);
  const int location = weighted_index(habits.location_weights, random);
  const std::vector<int>& candidates = place.sheets_by_location[location];
  touch.sheet = candidates[random.integer(0, static_cast<int64_t>(candidates.size()) - 1)];
  const Sheet& sheet = sheets[touch.sheet];
  touch.shape = shape_of_hand(touch.hand, habits, random);
  touch.approach = habits.approach * random.uniform(0.8, 1.2);
  const bool palm = touch.hand == Hand::kPalm;
  // "Random" behaviours land anywhere on the sheet; the others aim at it.
  const bool random_place =
      class_index == 0 || class_index == 1 || class_index == 3 || class_index == 4;
  const double spread = palm ? 1.0 * sheet.pitch : 1.6 * sheet.pitch;
  Point2 centre = sheet.centre;
  if (random_place) {
    centre.x += random.uniform(-spread, spread);
    centre.y += random.uniform(-spread, spread);
  } else {
    centre.x += habits.aim_offset.x + random.normal(0.0, 2.5);
    centre.y += habits.aim_offset.y + random.normal(0.0, 2.5);
  }

  double duration = 0.0;
  const Motion motion = motion_of_class(class_index);
  if (motion != Motion::kSlide) {
    // A tap lasts long enough to be converted once by every pad it covers (> one frame).
    duration = motion == Motion::kTap
                   ? std::max(0.13, random.truncated_normal(habits.tap_duration, 0.03))
                   : std::max(0.2, random.truncated_normal(habits.poke_duration, 0.08));
    touch.start = centre;
    // A pressed hand does not stand perfectly still.
    touch.end = {centre.x + random.normal(0.0, 0.4), centre.y + random.normal(0.0, 0.4)};
  } else {
    touch.direction = static_cast<Direction>(1 + weighted_index(habits.direction_weights, random));
    double speed = class_index == 1   ? habits.slow_speed
                   : class_index == 2 ? habits.finger_speed
                                      : habits.palm_speed;
    speed *= random.truncated_normal(1.0, 0.12);
    double path_length = 0.0;
    if (touch.direction == Direction::kClockwise ||
        touch.direction == Direction::kCounterClockwise) {
      touch.start = centre;  // the circle's centre
      touch.radius = palm ? random.uniform(8.0, 11.0) : random.uniform(5.5, 8.5);
      touch.start_angle = random.uniform(0.0, 2.0 * std::numbers::pi);
      const double turns = random.uniform(0.85, 1.25);
      // Positive angles turn from +x towards +y: clockwise on the y-down map.
      touch.sweep =
          (touch.direction == Direction::kClockwise ? 1.0 : -1.0) * turns * 2.0 * std::numbers::pi;
      path_length = touch.radius * std::abs(touch.sweep);
    } else {
      // A palm must sweep further than a finger to move its contact across a sheet.
      path_length = habits.stroke_length * (palm ? 1.5 : 1.0) * random.uniform(0.8, 1.2);
      const Point2 unit = direction_vector(touch.direction);
      touch.start = {centre.x - unit.x * path_length / 2, centre.y - unit.y * path_length / 2};
      touch.end = {centre.x + unit.x * path_length / 2, centre.y + unit.y * path_length / 2};
      touch.bow = habits.bow * random.truncated_normal(1.0, 0.3);
    }
    // Nobody slides for ever: a slow circle speeds up rather than lasting over 6 s.
    duration = std::clamp(path_length / speed, 0.15, 6.0);
  }
  touch.contact_start = start_time;
  touch.contact_end = start_time + duration;
  return touch;
}

}  // namespace
}  // namespace sim::tsa

//---- The generator ---------------------------------------------------------------------------

SimulatedTrial simulate_tsa_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial) {
  using namespace sim;
  using namespace sim::tsa;
  if (options.repetitions < 0)
    throw Error("--repetitions", "must be 0 (the skin's default) or more, not " +
                                     std::to_string(options.repetitions));
  if (subject < 0 || trial < 0)
    throw Error("tsa simulator", "subject and trial are 0-based and cannot be negative");
  if (static_cast<int>(layout.classes.size()) != kClassCount)
    throw Error(layout.id, "tsa simulator needs the six classes T1..T6, layout has " +
                               std::to_string(layout.classes.size()));

  const std::vector<Sheet> sheets = layout_sheets(layout);
  const Place place = index_places(sheets);
  const Device device = make_device(layout, sheets, options.seed);
  const Habits habits = draw_habits(options.seed, subject, place.locations.size());
  Random random(derive_engine(options.seed, "tsa-trial", subject, trial));
  Random noise(derive_engine(options.seed, "tsa-trial-noise", subject, trial));

  const int repetitions = options.repetitions > 0 ? options.repetitions : kDefaultRepetitions;
  const std::vector<int> order = shuffled_classes(kClassCount, repetitions, random);
  std::vector<Touch> touches;
  touches.reserve(order.size());
  double time = random.uniform(1.5, 2.5);  // lead-in of rest
  for (int class_index : order) {
    Touch touch = plan_touch(class_index, 0.0, habits, sheets, place, random);
    const double duration = touch.contact_end - touch.contact_start;
    touch.contact_start = time + touch.approach;
    touch.contact_end = touch.contact_start + duration;
    // Rest drawn independently of the class, counted from the hand leaving the field.
    time = touch.contact_end + touch.approach + random.uniform(1.0, 2.5);
    touches.push_back(touch);
  }
  const double tail = random.uniform(1.5, 2.5);
  const double end_time =
      touches.empty() ? time : touches.back().contact_end + touches.back().approach + tail;
  const auto frames = static_cast<int64_t>(std::ceil(end_time / kFramePeriod));

  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = simulated_recording_id("tsa", subject, trial);
  recording.layout_id = "tsa";
  recording.metadata = simulated_metadata("tsa", subject, trial, "", "");
  recording.metadata["group"] = habits.male ? "male" : "female";
  recording.metadata["repetitions"] = std::to_string(repetitions);
  recording.metadata["front_end"] =
      "raw 12-bit converter counts, 5 fF per count, rising with touch; "
      "before the IIR smoothing of eq. (3)";
  recording.streams.push_back(make_stream(layout, "skin", 1.0 / kFramePeriod, frames));
  render_front_end(sheets, device, touches, habits.coupling, noise,
                   recording.streams.front().samples);

  for (const Touch& touch : touches) {
    Label label =
        sim::ground_truth_label(recording.id, touch.contact_start, touch.contact_end,
                                layout.classes[touch.class_index], sheets[touch.sheet].location);
    label.note = std::string("hand=") + hand_name(touch.hand) +
                 " direction=" + direction_name(touch.direction) +
                 " sheet=" + sheets[touch.sheet].id;
    result.labels.push_back(std::move(label));
  }
  return result;
}

}  // namespace tactile

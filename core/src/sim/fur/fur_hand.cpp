#include "fur_hand.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tactile/error.h"

namespace tactile::sim::fur {

namespace {

constexpr double kPi = std::numbers::pi;

// How much one person's repetitions of a gesture differ (log-normal sd of force, duration,
// speed and extent of motion), how much one person's idea of a gesture differs from another's
// (per-gesture force, duration and motion), and how much more often a person kneads when asked
// to fondle than uses any one of the other motions (docs/SIMULATION.md: estimates, chosen so
// that fondle's recall and confusions come out as Table 1's row).
constexpr double kRepeatForce = 0.2;
constexpr double kRepeatDuration = 0.2;
constexpr double kRepeatSpeed = 0.15;
constexpr double kRepeatMotion = 0.2;
constexpr double kHabitGesture = 0.3;
constexpr double kFondleKnead = 2.5;

// A multiplier around 1 whose logarithm is normal: habits and per-gesture variation.
double log_normal(Random& random, double spread) {
  return std::exp(random.truncated_normal(0.0, spread, 2.0));
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

Point2 along(Point2 point, double heading, double forward, double sideways) {
  const double c = std::cos(heading), s = std::sin(heading);
  return {point.x + forward * c - sideways * s, point.y + forward * s + sideways * c};
}

// Fingers point over the head away from the person: a person in front reaches over the
// crown (fingers towards the lower rows, +y on the map), a person behind reaches up.
double approach_heading(Approach approach) {
  return approach == Approach::kFront ? kPi / 2.0 : -kPi / 2.0;
}

}  // namespace

Gesture gesture_of(const std::string& class_name) {
  static const char* const names[kGestureCount] = {"slap",   "pat",    "fondle",
                                                   "stroke", "tickle", "push"};
  for (int k = 0; k < kGestureCount; ++k)
    if (class_name == names[k]) return static_cast<Gesture>(k);
  throw Error("layout class " + class_name,
              "the fur simulator performs only slap, pat, fondle, stroke, tickle and push");
}

const char* approach_name(Approach approach) {
  return approach == Approach::kFront ? "front" : "back";
}

//---- Head map ------------------------------------------------------------------------------

double HeadMap::half_width_at(double y) const {
  if (row_y.empty()) return 0.0;
  if (y <= row_y.front()) return row_half_width.front();
  if (y >= row_y.back()) return row_half_width.back();
  const auto upper = std::upper_bound(row_y.begin(), row_y.end(), y);
  const size_t k = static_cast<size_t>(upper - row_y.begin());
  const double share = (y - row_y[k - 1]) / (row_y[k] - row_y[k - 1]);
  return row_half_width[k - 1] + share * (row_half_width[k] - row_half_width[k - 1]);
}

Point2 HeadMap::clamp(Point2 point, double margin) const {
  const double low = top + margin, high = bottom - margin;
  point.y = low <= high ? std::clamp(point.y, low, high) : 0.5 * (top + bottom);
  const double half = std::max(0.0, half_width_at(point.y) - margin);
  point.x = std::clamp(point.x, centre_x - half, centre_x + half);
  return point;
}

HeadMap head_map(const SkinLayout& layout) {
  HeadMap map;
  if (layout.taxels.empty()) throw Error("layout " + layout.id, "has no taxels to touch");
  const auto [low, high] = layout.bounds();
  map.centre_x = 0.5 * (low.x + high.x);
  map.top = high.y;
  map.bottom = low.y;
  std::vector<std::pair<double, double>> extents;  // (row centre y, half width)
  for (const Taxel& taxel : layout.taxels) {
    map.top = std::min(map.top, taxel.position.y - taxel.size.y / 2);
    map.bottom = std::max(map.bottom, taxel.position.y + taxel.size.y / 2);
    extents.emplace_back(taxel.position.y,
                         std::abs(taxel.position.x - map.centre_x) + taxel.size.x / 2);
  }
  std::sort(extents.begin(), extents.end());
  for (const auto& [y, half] : extents) {
    if (!map.row_y.empty() && y - map.row_y.back() < 1.0) {
      map.row_half_width.back() = std::max(map.row_half_width.back(), half);
      continue;
    }
    map.row_y.push_back(y);
    map.row_half_width.push_back(half);
  }
  return map;
}

//---- Habits --------------------------------------------------------------------------------

SubjectHabits draw_habits(const HeadMap& map, Random& random) {
  SubjectHabits habits;
  const double height = map.bottom - map.top;
  habits.force_scale = log_normal(random, 0.2);
  habits.speed_scale = log_normal(random, 0.18);
  habits.duration_scale = log_normal(random, 0.2);
  habits.hand_scale = random.uniform(0.88, 1.12);
  habits.heading_offset = random.truncated_normal(0.0, 0.3, 2.0);
  // From the front the hand lands on the crown (upper rows); from behind on the back of
  // the head (middle and lower rows). People differ in how far left or right they reach.
  habits.front_spot = {map.centre_x + random.normal(0.0, 40.0),
                       map.top + height * (0.18 + random.truncated_normal(0.0, 0.06, 2.0))};
  habits.back_spot = {map.centre_x + random.normal(0.0, 40.0),
                      map.top + height * (0.7 + random.truncated_normal(0.0, 0.07, 2.0))};
  for (int k = 0; k < kGestureCount; ++k) {
    habits.gesture_force[k] = log_normal(random, kHabitGesture);
    habits.gesture_duration[k] = log_normal(random, kHabitGesture);
    habits.gesture_motion[k] = log_normal(random, kHabitGesture);
  }
  habits.pat_count = static_cast<int>(random.integer(2, 5));
  habits.stroke_count = static_cast<int>(random.integer(1, 3));
  habits.tickle_fingers = static_cast<int>(random.integer(2, 4));
  habits.first_approach = random.chance(0.5) ? Approach::kFront : Approach::kBack;
  // Drawn last, so that the habits above stay what they were for each seed. People name the
  // same gesture by different motions (paper 002 §4: "different ideas of the touch gestures").
  for (double& weight : habits.fondle_styles) weight = -std::log(random.uniform(1e-9, 1.0));
  habits.fondle_styles[0] += kFondleKnead;
  habits.pats_with_fingers = random.chance(0.35);
  habits.strokes_with_fingertips = random.chance(0.3);
  habits.pushes_with_fingers = random.chance(0.3);
  habits.tickles_by_brushing = random.chance(0.4);
  return habits;
}

//---- Contact parts -------------------------------------------------------------------------

void contact_parts(const Episode& episode, double t, std::vector<ContactPart>& parts) {
  const double envelope =
      contact_envelope(t, episode.onset, episode.duration, episode.rise, episode.fall);
  if (envelope <= 0.0) return;
  const double local = t - episode.onset;
  const double progress = smoothstep(local / episode.duration);
  Point2 palm = {episode.start.x + (episode.end.x - episode.start.x) * progress,
                 episode.start.y + (episode.end.y - episode.start.y) * progress};
  const double wiggle = episode.wiggle_amplitude *
                        std::sin(2.0 * kPi * episode.wiggle_frequency * local + episode.phase);
  palm = along(palm, episode.heading, wiggle, 0.0);

  const double scale = episode.hand_scale;
  const double total = episode.force * envelope;
  const double palm_half_length = 42.0 * scale;
  if (!episode.fingertips_only)
    parts.push_back(
        {palm, palm_half_length, 40.0 * scale, episode.heading, total * episode.palm_share});

  const int fingers = std::max(1, episode.fingers);
  const double finger_total = episode.fingertips_only ? total : total * (1.0 - episode.palm_share);
  for (int k = 0; k < fingers; ++k) {
    const double sideways = (k - 0.5 * (fingers - 1)) * 19.0 * scale;
    const double finger_phase =
        2.0 * kPi * episode.knead_frequency * local + episode.phase + 2.1 * k;
    double share = 1.0;
    if (episode.fingertips_only && !episode.tips_lift) {
      share = 1.0 + 0.3 * std::sin(finger_phase);
    } else if (episode.fingertips_only) {
      // Tickling fingertips touch down and lift off in turn.
      const double lift = std::max(0.0, std::sin(finger_phase));
      share = 2.0 * lift * lift;
    } else {
      share = 1.0 + episode.knead_depth * std::sin(finger_phase);
    }
    const double force = finger_total * share / fingers;
    if (force <= 0.0) continue;
    if (episode.fingertips_only)
      parts.push_back({along(palm, episode.heading, palm_half_length + 58.0 * scale, sideways),
                       9.0 * scale, 8.0 * scale, episode.heading, force});
    else
      parts.push_back({along(palm, episode.heading, palm_half_length + 30.0 * scale, sideways),
                       24.0 * scale, 9.0 * scale, episode.heading, force});
  }
}

//---- Gestures ------------------------------------------------------------------------------

std::vector<Episode> plan_gesture(Gesture gesture, const SubjectHabits& habits, Approach approach,
                                  const HeadMap& map, double onset, Random& random) {
  const int index = static_cast<int>(gesture);
  const double force =
      habits.force_scale * habits.gesture_force[index] * log_normal(random, kRepeatForce);
  const double duration =
      habits.duration_scale * habits.gesture_duration[index] * log_normal(random, kRepeatDuration);
  const double speed = habits.speed_scale * log_normal(random, kRepeatSpeed);
  const double motion = habits.gesture_motion[index] * log_normal(random, kRepeatMotion);
  const Point2 spot = approach == Approach::kFront ? habits.front_spot : habits.back_spot;
  const double margin = 30.0 * habits.hand_scale;
  const Point2 centre =
      map.clamp({spot.x + random.normal(0.0, 30.0), spot.y + random.normal(0.0, 15.0)}, margin);
  const double heading =
      approach_heading(approach) + habits.heading_offset + random.truncated_normal(0.0, 0.15, 2.0);

  Episode base;
  base.onset = onset;
  base.start = base.end = centre;
  base.heading = heading;
  base.hand_scale = habits.hand_scale;
  base.phase = random.uniform(0.0, 2.0 * kPi);

  std::vector<Episode> episodes;
  switch (gesture) {
    case Gesture::kSlap: {
      // A flat hand hits and bounces off: one short, hard impact.
      Episode slap = base;
      slap.duration = random.uniform(0.12, 0.2) * std::sqrt(duration);
      slap.rise = 0.025;
      slap.fall = 0.05;
      slap.force = 38.0 * force;
      slap.palm_share = 0.55;
      episodes.push_back(slap);
      break;
    }
    case Gesture::kPat: {
      // Several light taps of the flat hand, lifted in between (paper 002 §4: the
      // segmenter's one-second hysteresis keeps them one segment).
      const int count = std::max(2, habits.pat_count + static_cast<int>(random.integer(-1, 1)));
      const double period = random.uniform(0.32, 0.55) / speed;
      double start = onset;
      for (int k = 0; k < count; ++k) {
        Episode pat = base;
        pat.onset = start;
        pat.duration = random.uniform(0.14, 0.24);
        pat.rise = 0.04;
        pat.fall = 0.05;
        pat.force = 20.0 * force * random.uniform(0.8, 1.2);
        pat.palm_share = 0.45;
        if (habits.pats_with_fingers) {  // the fingers' flat ends, the palm held off
          pat.force *= 0.6;
          pat.palm_share = 0.1;
        }
        pat.start = pat.end = map.clamp(
            {centre.x + random.normal(0.0, 10.0), centre.y + random.normal(0.0, 10.0)}, margin);
        episodes.push_back(pat);
        start += std::max(period, pat.duration + 0.12);
      }
      break;
    }
    case Gesture::kFondle: {
      // "Fondle" names no one motion (paper 002 §4; its confusions in Table 1 spread over pat,
      // stroke, tickle and push): each time, a person kneads the fur, or caresses it as in a
      // light stroke, plays in it with the fingertips as in a slow tickle, rests the hand on it
      // and presses, or pats it softly, in proportions of their own.
      const int style = random.weighted(habits.fondle_styles);
      if (style > 0) {
        static const Gesture kAlike[] = {Gesture::kStroke, Gesture::kTickle, Gesture::kPush,
                                         Gesture::kPat};
        static const double kForce[] = {0.8, 1.3, 0.55, 0.7};
        static const double kSpeed[] = {0.8, 0.6, 1.0, 0.8};
        SubjectHabits alike = habits;
        alike.force_scale *= kForce[style - 1];
        alike.speed_scale *= kSpeed[style - 1];
        return plan_gesture(kAlike[style - 1], alike, approach, map, onset, random);
      }
      // Kneading: the hand rests on the fur and kneads it with the fingers, wandering a little.
      Episode fondle = base;
      fondle.duration = random.uniform(2.2, 4.5) * duration;
      fondle.rise = 0.4;
      fondle.fall = 0.4;
      fondle.force = 13.0 * force;
      fondle.palm_share = 0.35;
      fondle.knead_depth = 0.6;
      fondle.knead_frequency = random.uniform(0.6, 1.4) * speed;
      fondle.wiggle_amplitude = 5.0 * motion;
      fondle.wiggle_frequency = fondle.knead_frequency;
      const double wander = random.uniform(0.0, 2.0 * kPi);
      fondle.end = map.clamp(along(centre, wander, 25.0 * motion, 0.0), margin);
      episodes.push_back(fondle);
      break;
    }
    case Gesture::kStroke: {
      // The flat hand glides along the fur towards the person and ends at the preferred spot
      // (from the front: up to the crown's front edge, from behind: down the back of the
      // head), lifted to return.
      const int count =
          std::clamp(habits.stroke_count + static_cast<int>(random.integer(0, 1)), 1, 3);
      const double direction = heading + kPi + random.truncated_normal(0.0, 0.2, 2.0);
      const double length = random.uniform(110.0, 190.0) * motion;
      double start = onset;
      for (int k = 0; k < count; ++k) {
        Episode stroke = base;
        stroke.onset = start;
        stroke.duration = random.uniform(0.6, 1.3) / speed * std::sqrt(duration);
        stroke.rise = 0.15;
        stroke.fall = 0.2;
        stroke.force = 15.0 * force * random.uniform(0.85, 1.15);
        stroke.palm_share = 0.4;
        if (habits.strokes_with_fingertips) {  // fingertips drawn through the fur
          stroke.fingertips_only = true;
          stroke.tips_lift = false;
          stroke.fingers = 4;
          stroke.force = 7.0 * std::sqrt(force) * random.uniform(0.85, 1.15);
        }
        stroke.start = map.clamp(along(centre, direction, -length, 0.0), margin);
        stroke.end = centre;
        episodes.push_back(stroke);
        start += stroke.duration + random.uniform(0.3, 0.55);
      }
      break;
    }
    case Gesture::kTickle: {
      // Fingertips only, light, scratching back and forth quickly, lifting in turn.
      Episode tickle = base;
      tickle.duration = random.uniform(1.6, 3.6) * duration;
      tickle.rise = 0.1;
      tickle.fall = 0.1;
      // Pressing harder would no longer tickle: people vary less here than in firm touches.
      tickle.force = 0.4 * std::sqrt(force);
      tickle.fingertips_only = true;
      tickle.fingers = habits.tickle_fingers;
      tickle.wiggle_amplitude = random.uniform(6.0, 14.0) * motion;
      tickle.wiggle_frequency = random.uniform(4.0, 8.0) * speed;
      tickle.knead_frequency = tickle.wiggle_frequency;
      const double wander = random.uniform(0.0, 2.0 * kPi);
      tickle.end = map.clamp(along(centre, wander, 20.0 * motion, 0.0), margin);
      if (habits.tickles_by_brushing) {  // light fingertips brushed to and fro over a span
        tickle.wiggle_amplitude = random.uniform(25.0, 50.0) * motion;
        tickle.wiggle_frequency = random.uniform(1.5, 3.0) * speed;
        tickle.tips_lift = false;
      }
      episodes.push_back(tickle);
      break;
    }
    case Gesture::kPush: {
      // A firm, sustained push of the palm to move the robot; the head yields a little.
      Episode push = base;
      // Sustained: however brief a person's habits, a push that moves the robot outlasts a second.
      push.duration = std::max(1.2, random.uniform(1.8, 4.0) * duration);
      push.rise = random.uniform(0.35, 0.7);
      push.fall = random.uniform(0.2, 0.4);
      push.force = 32.0 * force;
      push.palm_share = 0.7;
      if (habits.pushes_with_fingers) {  // the fingers' pads, the palm off the fur
        push.force = 20.0 * force;
        push.palm_share = 0.15;
      }
      push.end = map.clamp(along(centre, heading, 10.0, 0.0), margin);
      episodes.push_back(push);
      break;
    }
  }
  // The location drawn above is where the hand's force lands; the palm sits behind it,
  // towards the person (it may hang off the fur, where nothing is sensed).
  for (Episode& episode : episodes) {
    const double reach = episode.fingertips_only
                             ? 100.0 * episode.hand_scale
                             : (1.0 - episode.palm_share) * 72.0 * episode.hand_scale;
    episode.start = along(episode.start, episode.heading, -reach, 0.0);
    episode.end = along(episode.end, episode.heading, -reach, 0.0);
  }
  return episodes;
}

}  // namespace tactile::sim::fur

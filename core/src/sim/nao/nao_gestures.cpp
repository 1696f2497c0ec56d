// The hand of the NAO simulator: what each of the paper's nine touch classes (Table 3) does with
// which parts of the hand, how hard, how fast and for how long. The skin never sees the class:
// it sees only footprints, heights and forces (nao_skin.cpp).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "nao_model.h"
#include "tactile/error.h"

namespace tactile::sim::nao {

namespace {

// A hand starts and ends a gesture out of the proximity sensors' 200 mm range.
constexpr double kOutOfRange = 230.0;
// Hovering parts of the hand (the palm behind the fingertips, the fist above its base) stay at
// least this high above the skin while the fingers touch: the fingers are straight or curled
// under the hand, not flat beside the touched cells.
constexpr double kHoverClearance = 60.0;
constexpr double kFingerSpacing = 17.0;  // mm between neighbouring fingers of an adult hand

// The hand's frame on the map: `origin` where the hand is placed, `along` the fingers'
// direction, `across` from the index to the little finger.
struct HandFrame {
  Point2 origin;
  Point2 along;
  Point2 across;
  double angle = 0.0;  // of `along`, rad
  Point2 at(double u, double v) const {
    return {origin.x + u * along.x + v * across.x, origin.y + u * along.y + v * across.y};
  }
};

// Contact intervals of one hand part, with the force envelope and the lift between them.
struct Touches {
  std::vector<double> starts, ends, peaks;  // s, s, N
  double rise = 0.02, fall = 0.03;          // s
  double lift = 20.0;                       // mm, highest point between two touches

  double force(double t) const {
    double total = 0.0;
    for (size_t k = 0; k < starts.size(); ++k)
      total += peaks[k] * contact_envelope(t, starts[k], ends[k] - starts[k], rise, fall);
    return total;
  }
  // Height above the skin: descending at `approach` mm/s before the first touch, lifted
  // between touches, rising at `retreat` mm/s after the last one.
  double height(double t, double approach, double retreat) const {
    if (starts.empty()) return kOutOfRange;
    if (t <= starts.front()) return std::min(kOutOfRange, (starts.front() - t) * approach);
    if (t >= ends.back()) return std::min(kOutOfRange, (t - ends.back()) * retreat);
    for (size_t k = 0; k < starts.size(); ++k) {
      if (t < ends[k] && t > starts[k]) return 0.0;
      if (k + 1 < starts.size() && t >= ends[k] && t <= starts[k + 1]) {
        const double gap = starts[k + 1] - ends[k];
        const double arc = lift * std::sin(kPi * (t - ends[k]) / gap);
        return std::min({arc, (t - ends[k]) * retreat, (starts[k + 1] - t) * approach});
      }
    }
    return 0.0;
  }
  void add(double start, double end, double peak) {
    starts.push_back(start);
    ends.push_back(end);
    peaks.push_back(peak);
  }
};

struct Pose {
  Point2 centre;
  double height = 0.0;
  double force = 0.0;
};

// Everything a class needs to place and time its hand.
struct Context {
  const SideArea& side;
  const SubjectHabits& habits;
  Random& random;
  double rate_hz;
  double contact_start;  // s
  double approach;       // mm/s
  double retreat;        // mm/s
  HandFrame hand;
  Gesture& gesture;
};

HandPart make_part(double semi_major, double semi_minor, double angle, double texture_width,
                   double friction) {
  HandPart part;
  part.semi_major = semi_major;
  part.semi_minor = semi_minor;
  part.angle = angle;
  part.texture_width = texture_width;
  part.friction = friction;
  return part;
}

// Samples `part` from `begin` to `end` seconds with `pose_at(t)`.
template <class PoseAt>
void sample_part(HandPart part, double begin, double end, const Context& context, PoseAt pose_at) {
  part.first_sample = static_cast<int64_t>(std::floor(begin * context.rate_hz));
  const int64_t last = static_cast<int64_t>(std::ceil(end * context.rate_hz)) + 1;
  const size_t count = static_cast<size_t>(std::max<int64_t>(1, last - part.first_sample));
  part.x.resize(count);
  part.y.resize(count);
  part.height.resize(count);
  part.force.resize(count);
  for (size_t k = 0; k < count; ++k) {
    const double t =
        static_cast<double>(part.first_sample + static_cast<int64_t>(k)) / context.rate_hz;
    const Pose pose = pose_at(t);
    part.x[k] = static_cast<float>(pose.centre.x);
    part.y[k] = static_cast<float>(pose.centre.y);
    part.height[k] = static_cast<float>(std::max(0.0, pose.height));
    part.force[k] = static_cast<float>(std::max(0.0, pose.force));
  }
  context.gesture.parts.push_back(std::move(part));
}

// A part that keeps still relative to the hand at (u, v) and touches as `touches` says; `slide`
// moves it on the map during the gesture (mm, relative to its rest place).
template <class Slide>
void add_touching_part(const Context& context, const HandPart& shape, double u, double v,
                       const Touches& touches, Slide slide) {
  const double begin = touches.starts.front() - kOutOfRange / context.approach;
  const double end = touches.ends.back() + kOutOfRange / context.retreat;
  const Point2 rest = context.hand.at(u, v);
  sample_part(shape, begin, end, context, [&](double t) {
    const Point2 offset = slide(t);
    return Pose{{rest.x + offset.x, rest.y + offset.y},
                touches.height(t, context.approach, context.retreat),
                touches.force(t)};
  });
}

// A part that only hovers `clearance` mm above the touching parts (following their heights).
template <class Slide>
void add_hovering_part(const Context& context, const HandPart& shape, double u, double v,
                       const Touches& touches, double clearance, Slide slide) {
  const double begin = touches.starts.front() - kOutOfRange / context.approach;
  const double end = touches.ends.back() + kOutOfRange / context.retreat;
  const Point2 rest = context.hand.at(u, v);
  sample_part(shape, begin, end, context, [&](double t) {
    const Point2 offset = slide(t);
    return Pose{
        {rest.x + offset.x, rest.y + offset.y},
        std::min(kOutOfRange, touches.height(t, context.approach, context.retreat) + clearance),
        0.0};
  });
}

Point2 no_slide(double) { return {0.0, 0.0}; }

// An open hand: palm at the frame's origin and four fingers ahead of it. `shares` of the force
// go to the palm and to each finger.
void add_open_hand(const Context& context, const Touches& touches, double finger_spread,
                   auto slide) {
  const double scale = context.habits.hand_scale;
  const double palm_share = 0.6, finger_share = 0.1;
  Touches palm = touches;
  for (double& peak : palm.peaks) peak *= palm_share;
  add_touching_part(context, make_part(38.0 * scale, 35.0 * scale, context.hand.angle, 30.0, 0.6),
                    0.0, 0.0, palm, slide);
  Touches finger = touches;
  for (double& peak : finger.peaks) peak *= finger_share;
  for (int k = 0; k < 4; ++k) {
    const double v = (k - 1.5) * finger_spread * scale;
    const double u = (k == 0 || k == 3 ? 58.0 : 66.0) * scale;  // index and little finger shorter
    add_touching_part(context, make_part(26.0 * scale, 7.5 * scale, context.hand.angle, 10.0, 0.6),
                      u, v, finger, slide);
  }
}

// The palm above fingertips or finger pads placed around the frame's origin.
void add_hovering_palm(const Context& context, const Touches& touches, auto slide) {
  const double scale = context.habits.hand_scale;
  const double clearance = kHoverClearance + context.random.uniform(0.0, 20.0);
  add_hovering_part(context, make_part(38.0 * scale, 35.0 * scale, context.hand.angle, 30.0, 0.6),
                    -60.0 * scale, 0.0, touches, clearance, slide);
}

// Across-offsets of `count` fingers side by side, centred on the frame.
double finger_offset(int index, int count, double scale) {
  return (index - 0.5 * (count - 1)) * kFingerSpacing * scale;
}

//---- The nine classes (paper 000, Table 3) ----------------------------------------------------

// Pat: two instances of contact with the palm, relatively close together.
void pat(Context& context) {
  Random& random = context.random;
  const double speed = context.habits.speed_scale;
  Touches touches;
  touches.rise = random.uniform(0.015, 0.03) / speed;
  touches.fall = random.uniform(0.02, 0.04) / speed;
  touches.lift = random.uniform(25.0, 50.0);
  const double first = random.uniform(0.07, 0.14) / speed;
  const double gap = random.uniform(0.15, 0.35) / speed;
  const double second = random.uniform(0.07, 0.14) / speed;
  const double peak = random.uniform(5.0, 10.0) * context.habits.force_scale;
  const double t0 = context.contact_start;
  touches.add(t0, t0 + first, peak);
  touches.add(t0 + first + gap, t0 + first + gap + second, peak * random.uniform(0.7, 1.1));
  // The second pat lands a little beside the first.
  const Point2 shift{random.normal(0.0, 5.0), random.normal(0.0, 5.0)};
  const double moved = t0 + first, landed = t0 + first + gap;
  context.hand.origin = context.hand.at(-25.0 * context.habits.hand_scale, 0.0);
  add_open_hand(context, touches, kFingerSpacing, [=](double t) {
    const double progress = minimum_jerk((t - moved) / (landed - moved));
    return Point2{shift.x * progress, shift.y * progress};
  });
}

// Poke: brief contact with the tips of one or more straightened fingers.
void poke(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  const int fingers = random.chance(habits.poke_two_fingers) ? 2 : 1;
  Touches touches;
  touches.rise = random.uniform(0.03, 0.06) / habits.speed_scale;
  touches.fall = random.uniform(0.03, 0.05) / habits.speed_scale;
  const double duration = random.uniform(0.12, 0.3) / habits.speed_scale;
  const double peak = random.uniform(2.0, 5.0) * habits.force_scale / fingers;
  touches.add(context.contact_start, context.contact_start + duration, peak);
  // A poke is aimed: at the visible cell nearest to where this person likes to touch, with a
  // few millimetres of aiming error.
  const SideArea& side = context.side;
  Point2 target = side.centres.front();
  for (const Point2& centre : side.centres)
    if (std::hypot(centre.x - context.hand.origin.x, centre.y - context.hand.origin.y) <
        std::hypot(target.x - context.hand.origin.x, target.y - context.hand.origin.y))
      target = centre;
  context.hand.origin = {target.x + random.truncated_normal(0.0, 3.0),
                         target.y + random.truncated_normal(0.0, 3.0)};
  const double tremor_phase = random.uniform(0.0, 2.0 * kPi);
  for (int k = 0; k < fingers; ++k) {
    // Straight fingers held together touch with their tips about 10 mm apart.
    const double v = fingers == 1 ? 0.0 : (k - 0.5) * 10.0 * habits.hand_scale;
    Touches finger = touches;
    finger.peaks[0] *= random.uniform(0.8, 1.2);
    const HandPart tip =
        make_part(4.5 * habits.hand_scale, 4.0 * habits.hand_scale, context.hand.angle, 5.0, 0.6);
    add_touching_part(context, tip, 0.0, v, finger, [=](double t) {
      const double tremor = 0.3 * std::sin(2.0 * kPi * 10.0 * t + tremor_phase);  // mm
      return Point2{tremor, tremor};
    });
  }
  add_hovering_palm(context, touches, no_slide);
}

// Punch: brief contact applied by the base of a closed fist.
void punch(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  Touches touches;
  touches.rise = random.uniform(0.008, 0.015) / habits.speed_scale;
  touches.fall = random.uniform(0.02, 0.04) / habits.speed_scale;
  const double duration = random.uniform(0.06, 0.13) / habits.speed_scale;
  touches.add(context.contact_start, context.contact_start + duration,
              random.uniform(18.0, 35.0) * habits.force_scale);
  const double scale = habits.hand_scale;
  add_touching_part(context, make_part(22.0 * scale, 14.0 * scale, context.hand.angle, 20.0, 0.7),
                    0.0, 0.0, touches, no_slide);
  // The rest of the fist above its base.
  add_hovering_part(context, make_part(45.0 * scale, 35.0 * scale, context.hand.angle, 30.0, 0.6),
                    0.0, 0.0, touches, kHoverClearance, no_slide);
}

// Push: prolonged contact with the fingers or the palm.
void push(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  const bool palm = random.chance(habits.push_with_palm);
  Touches touches;
  touches.rise = random.uniform(0.15, 0.4) / habits.speed_scale;
  touches.fall = random.uniform(0.15, 0.35) / habits.speed_scale;
  const double duration = random.uniform(1.5, 3.5) * habits.duration_scale;
  const double peak =
      (palm ? random.uniform(6.0, 14.0) : random.uniform(3.0, 8.0)) * habits.force_scale;
  touches.add(context.contact_start, context.contact_start + duration, peak);
  // Holding still is not perfect: a slow sway of a few millimetres.
  const double sway_frequency = random.uniform(0.3, 0.8),
               sway_phase = random.uniform(0.0, 2.0 * kPi);
  const double sway = random.uniform(0.5, 2.0);
  auto slide = [=](double t) {
    const double s = sway * std::sin(2.0 * kPi * sway_frequency * t + sway_phase);
    return Point2{s, 0.5 * s};
  };
  if (palm) {
    context.hand.origin = context.hand.at(-25.0 * habits.hand_scale, 0.0);
    add_open_hand(context, touches, kFingerSpacing, slide);
    return;
  }
  const int fingers = std::clamp(habits.fingers, 2, 4);
  for (int k = 0; k < fingers; ++k) {
    Touches finger = touches;
    finger.peaks[0] /= fingers;
    add_touching_part(
        context,
        make_part(18.0 * habits.hand_scale, 7.5 * habits.hand_scale, context.hand.angle, 8.0, 0.6),
        0.0, finger_offset(k, fingers, habits.hand_scale), finger, slide);
  }
  add_hovering_palm(context, touches, slide);
}

// Rub: prolonged contact with the palm moving tangentially.
void rub(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  Touches touches;
  touches.rise = random.uniform(0.12, 0.3) / habits.speed_scale;
  touches.fall = random.uniform(0.12, 0.3) / habits.speed_scale;
  const double duration = random.uniform(1.5, 3.5) * habits.duration_scale;
  touches.add(context.contact_start, context.contact_start + duration,
              random.uniform(3.0, 8.0) * habits.force_scale);
  const Point2 direction =
      random.chance(habits.rub_across) ? context.hand.across : context.hand.along;
  const double amplitude = habits.rub_amplitude * random.uniform(0.8, 1.2);
  const double frequency = habits.rub_frequency * random.uniform(0.85, 1.15);
  const double start = context.contact_start;
  context.hand.origin = context.hand.at(-25.0 * habits.hand_scale, 0.0);
  add_open_hand(context, touches, kFingerSpacing, [=](double t) {
    const double s = amplitude * std::sin(2.0 * kPi * frequency * std::max(0.0, t - start));
    return Point2{s * direction.x, s * direction.y};
  });
}

// Scratch: fingertips or nails moving tangentially (quick short strokes toward the palm).
void scratch(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  const int fingers = std::clamp(habits.fingers, 2, 4);
  Touches touches;
  touches.rise = random.uniform(0.04, 0.08);
  touches.fall = random.uniform(0.04, 0.08);
  const double duration = random.uniform(1.2, 3.0) * habits.duration_scale;
  touches.add(context.contact_start, context.contact_start + duration, 0.0);
  const double amplitude = random.uniform(5.0, 12.0) * habits.hand_scale;
  const double frequency = habits.scratch_frequency * random.uniform(0.85, 1.15);
  const double start = context.contact_start;
  const Point2 along = context.hand.along;
  for (int k = 0; k < fingers; ++k) {
    Touches finger = touches;
    finger.peaks[0] = random.uniform(0.5, 1.3) * habits.force_scale;
    const double phase = random.normal(0.0, 0.3);
    // A nail's edge: long across the finger, thin along it.
    const HandPart nail = make_part(3.5 * habits.hand_scale, 1.5 * habits.hand_scale,
                                    context.hand.angle + 0.5 * kPi, 0.4, 0.45);
    const double u = (k == 0 || k == fingers - 1) ? -4.0 : 2.0;  // middle fingers reach further
    add_touching_part(
        context, nail, u, finger_offset(k, fingers, habits.hand_scale), finger, [=](double t) {
          const double cycle = 2.0 * kPi * frequency * std::max(0.0, t - start) + phase;
          const double s = -0.5 * amplitude * (1.0 - std::cos(cycle));
          return Point2{s * along.x, s * along.y};
        });
  }
  add_hovering_palm(context, touches, no_slide);
}

// Slap: brief contact with an open hand.
void slap(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  Touches touches;
  touches.rise = random.uniform(0.008, 0.018) / habits.speed_scale;
  touches.fall = random.uniform(0.02, 0.035) / habits.speed_scale;
  const double duration = random.uniform(0.05, 0.11) / habits.speed_scale;
  touches.add(context.contact_start, context.contact_start + duration,
              random.uniform(12.0, 25.0) * habits.force_scale);
  context.hand.origin = context.hand.at(-30.0 * habits.hand_scale, 0.0);
  add_open_hand(context, touches, 19.0, no_slide);
}

// Stroke: the fingers moving together across the skin, in one or more sweeps.
void stroke(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  const int fingers = std::clamp(habits.fingers, 2, 4);
  const Point2 direction = random.chance(habits.stroke_across)
                               ? context.hand.across
                               : Point2{-context.hand.along.x, -context.hand.along.y};
  // A sweep crosses most of the patch: start and end inside it.
  const SideArea& side = context.side;
  const double extent = std::abs(direction.x) * (side.high.x - side.low.x) +
                        std::abs(direction.y) * (side.high.y - side.low.y);
  const double length = std::min(random.uniform(60.0, 100.0), extent - 15.0);
  const double speed = habits.stroke_speed * random.uniform(0.85, 1.15);
  const double sweep = length / speed;
  const double back = 0.5 * sweep + random.uniform(0.1, 0.25);
  Touches touches;
  touches.rise = random.uniform(0.04, 0.07);
  touches.fall = random.uniform(0.04, 0.07);
  touches.lift = random.uniform(20.0, 40.0);
  const int sweeps =
      std::clamp(habits.stroke_sweeps + static_cast<int>(random.integer(-1, 1)), 1, 3);
  for (int k = 0; k < sweeps; ++k) {
    const double begin = context.contact_start + k * (sweep + back);
    touches.add(begin, begin + sweep, 0.0);
  }
  // The sweep is centred on the patch, nudged toward where this person likes to touch.
  const Point2 centre{side.centre.x + 0.4 * habits.preferred_offset.x,
                      side.centre.y + 0.4 * habits.preferred_offset.y};
  context.hand.origin = {centre.x - 0.5 * length * direction.x,
                         centre.y - 0.5 * length * direction.y};
  const std::vector<double> starts = touches.starts, ends = touches.ends;
  auto slide = [=](double t) {
    // On the skin: forward along the sweep; in the air between sweeps: back to the start.
    double travelled = 0.0;
    for (size_t k = 0; k < starts.size(); ++k) {
      if (t < starts[k]) break;
      if (t <= ends[k]) {
        travelled = minimum_jerk((t - starts[k]) / (ends[k] - starts[k]));
        break;
      }
      const bool last = k + 1 == starts.size();
      travelled = last ? 1.0 : 1.0 - minimum_jerk((t - ends[k]) / (starts[k + 1] - ends[k]));
    }
    return Point2{travelled * length * direction.x, travelled * length * direction.y};
  };
  for (int k = 0; k < fingers; ++k) {
    Touches finger = touches;
    const double peak = random.uniform(0.4, 1.2) * habits.force_scale;
    for (double& value : finger.peaks) value = peak * random.uniform(0.85, 1.15);
    const HandPart pad =
        make_part(16.0 * habits.hand_scale, 7.5 * habits.hand_scale, context.hand.angle, 8.0, 0.55);
    add_touching_part(context, pad, 0.0, finger_offset(k, fingers, habits.hand_scale), finger,
                      slide);
  }
  add_hovering_palm(context, touches, slide);
}

// Tickle: fingertips each moving independently and repeatedly along the skin.
void tickle(Context& context) {
  Random& random = context.random;
  const SubjectHabits& habits = context.habits;
  const int fingers = std::clamp(habits.fingers + 1, 2, 4);
  const double duration = random.uniform(1.5, 3.0) * habits.duration_scale;
  const double t0 = context.contact_start;
  // The whole hand wanders slowly while the fingers flick.
  const double wander = random.uniform(4.0, 10.0), wander_frequency = random.uniform(0.3, 0.7);
  Touches envelope;  // for the palm: the span of all the fingers' touches
  envelope.add(t0, t0 + duration, 0.0);
  for (int k = 0; k < fingers; ++k) {
    Touches finger;
    const double period = habits.tickle_period * random.uniform(0.8, 1.25);
    const double touching = period * random.uniform(0.45, 0.65);
    finger.rise = finger.fall = 0.25 * touching;
    finger.lift = random.uniform(5.0, 15.0);
    // The first finger starts the contact; the others join within one of their cycles.
    for (double start = t0 + (k == 0 ? 0.0 : random.uniform(0.0, period));
         start + touching <= t0 + duration; start += period * random.uniform(0.9, 1.1))
      finger.add(start, start + touching, random.uniform(0.2, 0.7) * habits.force_scale);
    if (finger.starts.empty()) continue;
    const double heading = context.hand.angle + kPi + random.uniform(-1.0, 1.0);
    const Point2 direction{std::sin(heading), -std::cos(heading)};
    const double reach = random.uniform(4.0, 12.0);
    const std::vector<double> starts = finger.starts, ends = finger.ends;
    const HandPart tip =
        make_part(5.0 * habits.hand_scale, 4.5 * habits.hand_scale, context.hand.angle, 1.5, 0.5);
    add_touching_part(
        context, tip, 0.0, finger_offset(k, fingers, habits.hand_scale), finger, [=](double t) {
          // Slides `reach` mm during each touch and returns in the air.
          double progress = 0.0;
          for (size_t j = 0; j < starts.size(); ++j) {
            if (t < starts[j]) break;
            if (t <= ends[j]) {
              progress = (t - starts[j]) / (ends[j] - starts[j]);
              break;
            }
            const double next = j + 1 < starts.size() ? starts[j + 1] : ends[j] + 0.2;
            progress = 1.0 - std::clamp((t - ends[j]) / (next - ends[j]), 0.0, 1.0);
          }
          const double drift = wander * std::sin(2.0 * kPi * wander_frequency * (t - t0));
          return Point2{progress * reach * direction.x + drift,
                        progress * reach * direction.y + 0.5 * drift};
        });
  }
  add_hovering_palm(context, envelope, no_slide);
}

// The contact span of a gesture: first and last instant any part presses on the skin.
void find_contact_span(Gesture& gesture, double rate_hz) {
  double first = 1e300, last = -1e300;
  for (const HandPart& part : gesture.parts) {
    for (size_t k = 0; k < part.force.size(); ++k) {
      if (part.force[k] <= 0.0f) continue;
      const double t = static_cast<double>(part.first_sample + static_cast<int64_t>(k)) / rate_hz;
      first = std::min(first, t);
      last = std::max(last, t);
    }
  }
  if (first > last) throw Error("nao simulator", "a gesture without contact (hand model error)");
  // The envelope is zero at its ends: contact begins one sample before the first loaded one.
  gesture.contact_start = std::max(0.0, first - 1.0 / rate_hz);
  gesture.contact_end = last + 1.0 / rate_hz;
}

}  // namespace

int64_t Gesture::last_sample() const {
  int64_t last = 0;
  for (const HandPart& part : parts) last = std::max(last, part.last_sample());
  return last;
}

void shift_gesture(Gesture& gesture, int64_t samples, double rate_hz) {
  for (HandPart& part : gesture.parts) part.first_sample += samples;
  gesture.contact_start += static_cast<double>(samples) / rate_hz;
  gesture.contact_end += static_cast<double>(samples) / rate_hz;
}

SubjectHabits draw_habits(Random& random) {
  SubjectHabits habits;
  habits.force_scale = random.uniform(0.6, 1.5);
  habits.speed_scale = random.uniform(0.7, 1.4);
  habits.duration_scale = random.uniform(0.7, 1.4);
  habits.hand_scale = random.uniform(0.85, 1.12);
  habits.approach_speed = random.uniform(200.0, 500.0);
  habits.preferred_offset = {random.normal(0.0, 15.0), random.normal(0.0, 12.0)};
  habits.preferred_angle = random.uniform(-0.8, 0.8);
  habits.poke_two_fingers = random.uniform(0.0, 0.6);
  habits.push_with_palm = random.uniform(0.2, 0.9);
  habits.fingers = static_cast<int>(random.integer(2, 4));
  habits.rub_frequency = random.uniform(1.5, 3.0);
  habits.rub_amplitude = random.uniform(12.0, 30.0);
  habits.rub_across = random.uniform(0.1, 0.9);
  habits.scratch_frequency = random.uniform(3.0, 6.0);
  habits.stroke_speed = random.uniform(100.0, 250.0);
  habits.stroke_across = random.uniform(0.1, 0.6);
  habits.stroke_sweeps = static_cast<int>(random.integer(1, 3));
  habits.tickle_period = random.uniform(0.15, 0.3);
  return habits;
}

Gesture build_gesture(const std::string& class_name, const SideArea& side,
                      const SubjectHabits& habits, Random& random, double start, double rate_hz) {
  Gesture gesture;
  const bool impact = class_name == "punch" || class_name == "slap";
  // Hits come down fast; other touches approach at the person's own pace.
  const double approach = (impact ? random.uniform(800.0, 1500.0) * habits.speed_scale
                                  : habits.approach_speed * random.uniform(0.8, 1.2));
  const double retreat = habits.approach_speed * random.uniform(0.7, 1.3);
  // Where and how the hand is placed: the person's habit, varied a little each time.
  const double angle = habits.preferred_angle + random.normal(0.0, 0.2);
  HandFrame hand;
  hand.angle = angle;
  hand.along = {std::sin(angle), -std::cos(angle)};
  hand.across = {std::cos(angle), std::sin(angle)};
  const double margin = 12.0;
  hand.origin = {std::clamp(side.centre.x + habits.preferred_offset.x + random.normal(0.0, 8.0),
                            side.low.x + margin, side.high.x - margin),
                 std::clamp(side.centre.y + habits.preferred_offset.y + random.normal(0.0, 8.0),
                            side.low.y + margin, side.high.y - margin)};
  Context context{side,     habits,  random, rate_hz, start + kOutOfRange / approach,
                  approach, retreat, hand,   gesture};
  if (class_name == "pat")
    pat(context);
  else if (class_name == "poke")
    poke(context);
  else if (class_name == "punch")
    punch(context);
  else if (class_name == "push")
    push(context);
  else if (class_name == "rub")
    rub(context);
  else if (class_name == "scratch")
    scratch(context);
  else if (class_name == "slap")
    slap(context);
  else if (class_name == "stroke")
    stroke(context);
  else if (class_name == "tickle")
    tickle(context);
  else
    throw Error(
        "layout class \"" + class_name + "\"",
        "the nao simulator knows pat, poke, punch, push, rub, scratch, slap, stroke, tickle");
  find_contact_span(gesture, rate_hz);
  return gesture;
}

}  // namespace tactile::sim::nao

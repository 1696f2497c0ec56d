// A person's hands on the Robovie skin: every gesture is contact patches on the map (where
// the hand presses, how hard, how it moves) plus the joint motion it forces on the robot.

#include "robovie_gestures.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tactile::sim::robovie {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

MapArea united(const MapArea& a, const MapArea& b) {
  return {{std::min(a.low.x, b.low.x), std::min(a.low.y, b.low.y)},
          {std::max(a.high.x, b.high.x), std::max(a.high.y, b.high.y)}};
}

}  // namespace

Point2 Hands::spot(const MapArea& area, double u, double v, double scatter_mm) {
  const Point2 base = area.at(u, v);
  const double x = base.x + habits_.reach.x + random_.normal(0.0, scatter_mm);
  const double y = base.y + habits_.reach.y + random_.normal(0.0, scatter_mm);
  return {std::clamp(x, area.low.x - 10.0, area.high.x + 10.0),
          std::clamp(y, area.low.y - 10.0, area.high.y + 10.0)};
}

double Hands::force(double base) {
  return base * habits_.force * random_.truncated_normal(1.0, 0.15, 2.0);
}

double Hands::tap(double t, const MapArea& area, double base_force, bool finger_tip) {
  Contact contact;
  contact.onset = t;
  contact.duration = finger_tip ? random_.uniform(0.12, 0.3) : random_.uniform(0.1, 0.2);
  contact.rise = 0.03;
  contact.fall = 0.05;
  contact.force = force(base_force);
  const double u = random_.uniform(0.2, 0.8);  // own statements: argument order is unspecified
  const double v = random_.uniform(0.2, 0.8);
  contact.center = spot(area, u, v, 8.0);
  contact.half_size = finger_tip ? finger() : palm();
  add(contact);
  return contact.end();
}

double Hands::hold(double t, const MapArea& area, double base_force, double duration) {
  Contact contact;
  contact.onset = t;
  contact.duration = duration;
  contact.rise = 0.3;
  contact.fall = 0.3;
  contact.force = force(base_force);
  contact.center = spot(area, 0.5, 0.5, 10.0);
  contact.half_size = palm();
  // A resting hand is never quite still.
  contact.pulse_depth = 0.1;
  contact.pulse_hz = random_.uniform(0.2, 0.5);
  contact.phase = random_.uniform(0.0, kTwoPi);
  add(contact);
  return contact.end();
}

double Hands::pats(double t, const MapArea& area, int count) {
  const double rate = 2.2 * habits_.tempo * random_.uniform(0.9, 1.1);
  double end = t;
  for (int k = 0; k < count; ++k) {
    Contact contact;
    contact.onset = t + k / rate + random_.normal(0.0, 0.02);
    contact.duration = random_.uniform(0.1, 0.18);
    contact.rise = 0.03;
    contact.fall = 0.05;
    contact.force = force(10.0);
    contact.center = spot(area, 0.5, 0.5, 10.0);
    contact.half_size = palm();
    add(contact);
    // The pat pushes the head down a little: the neck's skin bends with it.
    move(Joint::kHead, JointMove::Shape::kBump, contact.onset, 0.3, 0.002 * contact.force);
    end = std::max(end, contact.end());
  }
  return end;
}

double Hands::strokes(double t, const MapArea& area, int count) {
  double onset = t;
  for (int k = 0; k < count; ++k) {
    Contact contact;
    contact.onset = onset;
    contact.duration = random_.uniform(0.8, 1.3) / habits_.tempo;
    contact.rise = 0.15;
    contact.fall = 0.2;
    contact.force = force(4.0);
    contact.center = spot(area, 0.5, 0.1, 8.0);
    contact.half_size = palm();
    // From the top of the area to its bottom over the stroke.
    contact.velocity = {random_.normal(0.0, 10.0),
                        0.8 * (area.high.y - area.low.y) / contact.duration};
    add(contact);
    onset = contact.end() + random_.uniform(0.3, 0.7);
  }
  return onset;
}

double Hands::grip(double t, const std::string& hand, double base_force, double duration,
                   double pulse_hz, double depth) {
  Contact palm_side;
  palm_side.onset = t;
  palm_side.duration = duration;
  palm_side.rise = 0.25;
  palm_side.fall = 0.25;
  palm_side.force = force(base_force);
  palm_side.center = spot(area(hand, View::kFront), 0.5, 0.5, 6.0);
  palm_side.half_size = palm();
  palm_side.pulse_depth = depth;
  palm_side.pulse_hz = pulse_hz;
  // The grip slides a few mm along the hand with each pump.
  palm_side.sway = {0.0, 5.0};
  palm_side.sway_hz = pulse_hz;
  add(palm_side);
  Contact fingers = palm_side;
  fingers.force = force(0.6 * base_force);
  fingers.center = spot(area(hand, View::kBack), 0.5, 0.5, 6.0);
  fingers.half_size = {35.0 * habits_.hand_size, 25.0 * habits_.hand_size};
  fingers.phase = 0.3;
  add(fingers);
  return t + duration;
}

double Hands::hand_shake(double t, int pumps, double hold_after) {
  const double pump_hz = 2.0 * habits_.tempo * random_.uniform(0.85, 1.15);
  const double settle = 0.4;
  const double crossfade = 0.25;  // the grip's ramp: pumping fades into a still hold
  const double pump_time = pumps / pump_hz;
  grip(t, "hand-right", 20.0, settle + pump_time + crossfade, pump_hz, 0.35);
  if (hold_after > 0.0)
    grip(t + settle + pump_time, "hand-right", 20.0, hold_after + crossfade, 0.0, 0.0);
  // Pumping moves the whole arm a few cm: a few hundredths of a radian at the shoulder.
  move(Joint::kRightArm, JointMove::Shape::kOscillation, t + settle, pump_time,
       random_.uniform(0.04, 0.08), pump_hz);
  if (habits_.two_handed_shake) {
    // The other hand covers the back of the robot's hand.
    Contact cover;
    cover.onset = t + 0.3;
    cover.duration = std::max(0.6, settle + pump_time + hold_after - 0.3);
    cover.rise = 0.3;
    cover.fall = 0.3;
    cover.force = force(6.0);
    cover.center = spot(area("hand-right", View::kBack), 0.5, 0.5, 6.0);
    cover.half_size = palm();
    add(cover);
  }
  return t + settle + pump_time;
}

double Hands::tickle(double t, double duration) {
  const int bursts = static_cast<int>(random_.integer(1, 3));
  const double gap = random_.uniform(0.4, 1.2);
  const double burst = std::max(0.8, (duration - (bursts - 1) * gap) / bursts);
  const MapArea belly_front = area("chest-lower", View::kFront);
  const MapArea belly_back = area("back-lower", View::kBack);
  double onset = t;
  for (int b = 0; b < bursts; ++b) {
    for (const char* side : {"side-right", "side-left"}) {
      const View view = random_.chance(habits_.tickle_front) ? View::kFront : View::kBack;
      const MapArea side_area = area(side, view);
      // Fingers wander off the side towards the belly (or the back's middle).
      const double middle = (view == View::kFront ? belly_front : belly_back).center().x;
      const double inward = middle > side_area.center().x ? 1.0 : -1.0;
      const double hz = habits_.tickle_hz * habits_.tempo * random_.uniform(0.9, 1.1);
      for (int k = 0; k < habits_.fingers; ++k) {
        Contact finger_tip;
        finger_tip.onset = onset + random_.uniform(0.0, 0.15);
        finger_tip.duration = burst;
        finger_tip.rise = 0.1;
        finger_tip.fall = 0.1;
        finger_tip.force = force(2.2);
        finger_tip.center = spot(side_area, 0.5, 0.25 + 0.2 * k, 6.0);
        finger_tip.center.x += inward * random_.uniform(0.0, habits_.tickle_belly);
        finger_tip.half_size = finger();
        finger_tip.velocity = {0.0, random_.normal(0.0, 8.0)};
        finger_tip.sway = {random_.uniform(3.0, 6.0), random_.uniform(8.0, 14.0)};
        finger_tip.sway_hz = hz;
        // Fingers lift between scratches.
        finger_tip.pulse_depth = 0.8;
        finger_tip.pulse_hz = hz;
        finger_tip.phase = 2.1 * k + random_.uniform(0.0, kTwoPi);
        add(finger_tip);
      }
    }
    onset += burst + gap;
  }
  return onset - gap + 0.15;
}

double Hands::hug(double t, double hold) {
  const MapArea back = united(area("back-upper", View::kBack), area("back-lower", View::kBack));
  const MapArea chest =
      united(area("chest-upper", View::kFront), area("chest-lower", View::kFront));
  const double rise = random_.uniform(0.6, 1.2);
  const double fall = random_.uniform(0.4, 0.8);
  const double duration = rise + hold + fall;
  const double breathing = random_.uniform(0.2, 0.35);
  const double hands_y = area("back-upper", View::kBack).high.y + habits_.hug_height;
  for (double side : {-1.0, 1.0}) {
    Contact palm_on_back;
    palm_on_back.onset = t;
    palm_on_back.duration = duration;
    palm_on_back.rise = rise;
    palm_on_back.fall = fall;
    palm_on_back.force = force(12.0);
    palm_on_back.center = {back.center().x + side * random_.uniform(45.0, 75.0),
                           hands_y + random_.normal(0.0, 15.0)};
    palm_on_back.half_size = palm();
    palm_on_back.pulse_depth = 0.15;
    palm_on_back.pulse_hz = breathing;
    palm_on_back.phase = random_.uniform(0.0, kTwoPi);
    add(palm_on_back);
  }
  for (const char* side : {"side-right", "side-left"}) {
    Contact forearm;
    forearm.onset = t + 0.1;
    forearm.duration = duration - 0.1;
    forearm.rise = rise;
    forearm.fall = fall;
    forearm.force = force(7.0);
    forearm.center = area(side, View::kBack).center();
    forearm.center.y += 0.5 * habits_.hug_height;
    forearm.half_size = {25.0, 70.0};
    forearm.pulse_depth = 0.15;
    forearm.pulse_hz = breathing;
    add(forearm);
  }
  // The person's own chest against the robot's: a wide, soft pressure.
  Contact torso;
  torso.onset = t + 0.2;
  torso.duration = duration - 0.3;
  torso.rise = rise;
  torso.fall = fall;
  torso.force = force(14.0);
  torso.center = chest.center();
  torso.center.y += 0.5 * habits_.hug_height;
  torso.half_size = {80.0, 110.0};
  torso.pulse_depth = 0.2;
  torso.pulse_hz = breathing;
  add(torso);
  if (habits_.pats_while_hugging) {
    const double onset = t + rise + random_.uniform(0.3, 1.0);
    pats(onset, area("back-upper", View::kBack), static_cast<int>(random_.integer(2, 4)));
  }
  move(Joint::kWaist, JointMove::Shape::kBump, t, duration, random_.uniform(0.03, 0.06));
  return t + duration;
}

double Hands::pokes(double t, int count) {
  static const char* const kParts[] = {"chest-upper",    "chest-lower", "upper-arm-right",
                                       "upper-arm-left", "side-right",  "side-left",
                                       "forearm-right",  "forearm-left"};
  double onset = t, end = t;
  for (int k = 0; k < count; ++k) {
    const char* part = kParts[random_.integer(0, 7)];
    end = std::max(end, tap(onset, area(part, View::kFront), 4.0, true));
    onset += random_.uniform(0.5, 1.2) / habits_.tempo;
  }
  return end;
}

double Hands::swing_hands(double t, double duration, double amplitude) {
  const double swing_hz = 0.9 * habits_.tempo * random_.uniform(0.8, 1.2);
  grip(t, "hand-right", 10.0, duration, 2.0 * swing_hz, 0.3);
  grip(t, "hand-left", 10.0, duration, 2.0 * swing_hz, 0.3);
  for (Joint arm : {Joint::kRightArm, Joint::kLeftArm})
    move(arm, JointMove::Shape::kOscillation, t + 0.3, std::max(0.6, duration - 0.6),
         amplitude * random_.uniform(0.8, 1.2), swing_hz);
  return t + duration;
}

double Hands::high_fives(double t, int count) {
  double onset = t, end = t;
  for (int k = 0; k < count; ++k) {
    const bool left = k % 2 == 1;
    Contact slap;
    slap.onset = onset;
    slap.duration = random_.uniform(0.07, 0.12);
    slap.rise = 0.02;
    slap.fall = 0.04;
    slap.force = force(15.0);
    slap.center = spot(area(left ? "hand-left" : "hand-right", View::kFront), 0.5, 0.5, 8.0);
    slap.half_size = palm();
    add(slap);
    move(left ? Joint::kLeftArm : Joint::kRightArm, JointMove::Shape::kBump, onset, 0.4, 0.06);
    end = slap.end();
    onset += random_.uniform(0.6, 1.0) / habits_.tempo;
  }
  return end;
}

double Hands::lift_by_sides(double t) {
  const double duration = random_.uniform(1.5, 3.0) * habits_.patience;
  for (const char* side : {"side-right", "side-left"}) {
    Contact lift;
    lift.onset = t;
    lift.duration = duration;
    lift.rise = 0.4;
    lift.fall = 0.4;
    lift.force = force(20.0);
    lift.center = spot(area(side, View::kFront), 0.5, 0.6, 8.0);
    lift.half_size = palm();
    lift.velocity = {0.0, -15.0};  // the hands slide up as they lift
    add(lift);
  }
  move(Joint::kWaist, JointMove::Shape::kBump, t, duration, random_.uniform(0.04, 0.08));
  return t + duration;
}

double Hands::cheeks(double t) {
  const MapArea face = area("face", View::kFront);
  const double duration = random_.uniform(1.0, 2.5) * habits_.patience;
  const double rub_hz = random_.uniform(0.8, 1.5);
  for (double u : {0.08, 0.92}) {
    Contact cheek;
    cheek.onset = t + random_.uniform(0.0, 0.2);
    cheek.duration = duration;
    cheek.rise = 0.3;
    cheek.fall = 0.3;
    cheek.force = force(5.0);
    cheek.center = spot(face, u, 0.65, 6.0);
    cheek.half_size = {30.0 * habits_.hand_size, 40.0 * habits_.hand_size};
    cheek.sway = {0.0, 4.0};
    cheek.sway_hz = rub_hz;
    add(cheek);
  }
  return t + duration + 0.2;
}

}  // namespace tactile::sim::robovie

#pragma once
// What a person's hands do on the robot: pats, strokes, a hand shake, tickling, a hug...
// each written as contact patches on the skin map and the joint motion it forces.
// Private to the Robovie simulator.

#include <vector>

#include "robovie_scenario.h"

namespace tactile::sim::robovie {

class Hands {
 public:
  Hands(const Films& films, const Habits& habits, Random& random, Session& session)
      : films_(films), habits_(habits), random_(random), session_(session) {}

  // Each gesture starts at `t` (s) and returns when it is done as an observer would see it;
  // the last contact may outlast that (a hand still held, fingers still tickling).
  double tap(double t, const MapArea& area, double base_force, bool finger);
  double hold(double t, const MapArea& area, double base_force, double duration);
  double pats(double t, const MapArea& area, int count);
  double strokes(double t, const MapArea& area, int count);
  // Grips the robot's right hand and pumps `pumps` times; keeps holding `hold_after` s
  // more (returned time is the end of pumping).
  double hand_shake(double t, int pumps, double hold_after);
  double tickle(double t, double duration);
  double hug(double t, double hold);
  double pokes(double t, int count);
  double swing_hands(double t, double duration, double amplitude);
  double high_fives(double t, int count);
  double lift_by_sides(double t);
  double cheeks(double t);

  MapArea area(const std::string& part, View view) const { return body_area(films_, part, view); }

 private:
  // A point of `area` at fractions (u, v), moved by the person's habitual reach and a
  // little scatter, kept on the area grown by 10 mm.
  Point2 spot(const MapArea& area, double u, double v, double scatter_mm);
  // A habit force (N) for this person in this moment.
  double force(double base);
  Point2 palm() const { return {40.0 * habits_.hand_size, 45.0 * habits_.hand_size}; }
  Point2 finger() const { return {8.0 * habits_.hand_size, 10.0 * habits_.hand_size}; }
  void add(const Contact& contact) { session_.contacts.push_back(contact); }
  void move(Joint joint, JointMove::Shape shape, double onset, double duration, double amplitude,
            double frequency_hz = 0.0) {
    session_.moves.push_back({joint, shape, onset, duration, amplitude, frequency_hz});
  }
  // One grip on a hand (palm on the front films, fingers wrapped to the back), returning the
  // time it ends; pulses at `pulse_hz` with `depth` while it lasts.
  double grip(double t, const std::string& hand, double base_force, double duration,
              double pulse_hz, double depth);

  const Films& films_;
  const Habits& habits_;
  Random& random_;
  Session& session_;
};

}  // namespace tactile::sim::robovie

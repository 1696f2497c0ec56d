#pragma once
// The scripted session of paper 003 (Table I): the robot speaks 15 stages, a subject answers
// with touches (or not), the robot gestures while it speaks. Private to the simulator.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/sim/robovie_sim.h"

namespace tactile::sim::robovie {

// A subject's habits: drawn once per subject from (seed, subject), so they persist over
// the subject's trials. Nobody is told how long, how hard or exactly where to touch.
struct Habits {
  double force = 1.0;       // multiplies every touch force
  double tempo = 1.0;       // multiplies rhythmic rates (pats, pumping, tickling)
  double patience = 1.0;    // multiplies how long touches and answers last
  double touchiness = 0.3;  // probability of touching where the robot did not ask
  double hand_size = 1.0;   // multiplies palm and finger sizes
  Point2 reach;             // mm: where this person's hands land, off a body part's centre
  double hug_height = 0.0;  // mm: taller people hug higher on the back (map y grows down)
  bool two_handed_shake = false;
  bool strokes_head = false;  // strokes instead of patting when asked for a pat
  bool pats_while_hugging = false;
  int pat_count = 4;
  int fingers = 3;             // fingers per hand when tickling
  double tickle_hz = 6.0;      // finger scratching rate
  double tickle_front = 0.7;   // share of tickling on the front of the sides (else reaching around)
  double tickle_belly = 15.0;  // mm the fingers wander from the sides towards the belly
  int play_style = 0;          // 0 pokes, 1 holds hands and swings, 2 high-fives
  int cute_style = 0;          // 0 strokes the head, 1 holds the cheeks, 2 light pats, 3 no touch
  int whee_style = 0;          // 0 swings its hands up, 1 lifts it by the sides, 2 claps its hands
  int bye_style = 0;           // 0 hand shake, 1 pat on the head, 2 short hug, 3 waves, no touch
};

Habits draw_habits(uint64_t seed, int subject);

// Where the subject starts, 2 m from the robot (paper 003, Sec. IV-C): in front, 45 degrees
// to the robot's right, 45 degrees to its left.
enum class Approach { kFront, kRight, kLeft };
const char* approach_name(Approach approach);

// One trial as it happened: the touches, the robot's movements, the stage commands.
struct Session {
  std::vector<Contact> contacts;
  std::vector<JointMove> moves;
  std::vector<double> commands;  // s, start command of each stage, increasing
  double end = 0.0;              // s, end of the recording
  Approach approach = Approach::kFront;
};

// Plays the 15 stages (names in `stages`, Table I order). Touches and timing draw from
// (seed, "robovie-trial", subject, trial); the robot's own gestures from "robovie-motion".
Session play_session(const Films& films, const std::vector<std::string>& stages,
                     const Habits& habits, uint64_t seed, int subject, int trial);

}  // namespace tactile::sim::robovie

#pragma once
// The hand of the smart-fur simulator: a subject's habits, the contact episodes one
// gesture is made of, and the ellipses of palm, fingers and fingertips an episode
// presses onto the unwrapped head map at a given instant.

#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/sim/sim_util.h"

namespace tactile::sim::fur {

// The six gestures of paper 002, in the layout's class order.
enum class Gesture { kSlap, kPat, kFondle, kStroke, kTickle, kPush };
constexpr int kGestureCount = 6;

// Gesture for a class name of the layout; throws tactile::Error for a name the fur
// hand cannot perform.
Gesture gesture_of(const std::string& class_name);

enum class Approach { kFront, kBack };
const char* approach_name(Approach approach);

// How one person touches: drawn once per subject, so habits persist across trials.
// Per-gesture multipliers carry "different ideas of the touch gestures" (paper 002 §4).
struct SubjectHabits {
  double force_scale = 1.0;
  double speed_scale = 1.0;
  double duration_scale = 1.0;
  double hand_scale = 1.0;
  double heading_offset = 0.0;   // radians, added to the approach's finger direction
  Point2 front_spot, back_spot;  // preferred touch location for each approach (map mm)
  double gesture_force[kGestureCount] = {};
  double gesture_duration[kGestureCount] = {};
  double gesture_motion[kGestureCount] = {};
  int pat_count = 3;
  int stroke_count = 1;
  int tickle_fingers = 3;
  Approach first_approach = Approach::kFront;
  // How often this person fondles by kneading, or as in a stroke, a tickle, a push or a pat.
  std::vector<double> fondle_styles = {1.0, 1.0, 1.0, 1.0, 1.0};
  bool pats_with_fingers = false;        // else the flat hand
  bool strokes_with_fingertips = false;  // else the flat hand
  bool pushes_with_fingers = false;      // else the palm
  bool tickles_by_brushing = false;      // else scratching in place
};

// Where on the map a hand may be placed: the head's rows get wider further down.
struct HeadMap {
  double top = 0.0, bottom = 0.0;             // y range of the cells (map mm)
  double centre_x = 0.0;                      // the head's midline
  std::vector<double> row_y, row_half_width;  // half width of the cell area per row centre
  double half_width_at(double y) const;
  // Keeps a palm centre far enough inside the cells that the hand stays on the fur.
  Point2 clamp(Point2 point, double margin) const;
};
HeadMap head_map(const SkinLayout& layout);

SubjectHabits draw_habits(const HeadMap& map, Random& random);

// One continuous contact of the hand (or fingertips) with the fur.
struct Episode {
  double onset = 0.0, duration = 0.0, rise = 0.0, fall = 0.0;  // force envelope (s)
  Point2 start, end;        // palm centre moves from start to end (smoothstep in time)
  double heading = 0.0;     // direction the fingers point (radians, map x towards map y)
  double force = 0.0;       // peak total normal force (N)
  double palm_share = 0.5;  // part of the force carried by the palm
  bool fingertips_only = false;
  bool tips_lift = true;  // fingertips touch down and lift off in turn (else they stay on)
  int fingers = 4;
  double hand_scale = 1.0;
  // Scratching or kneading: the hand oscillates along the fingers and each finger's force
  // is modulated, with a phase per finger (tickling lifts the fingertips off between strokes).
  double wiggle_amplitude = 0.0, wiggle_frequency = 0.0;
  double knead_depth = 0.0, knead_frequency = 0.0;
  double phase = 0.0;
};

// One contact ellipse on the map: semi-axes along and across `angle`, force in newtons.
struct ContactPart {
  Point2 centre;
  double half_length = 0.0, half_width = 0.0, angle = 0.0;
  double force = 0.0;
};

// Appends the parts an episode presses at time t (nothing outside its envelope).
void contact_parts(const Episode& episode, double t, std::vector<ContactPart>& parts);

// The episodes of one gesture starting at `onset`, performed by a subject from an approach.
std::vector<Episode> plan_gesture(Gesture gesture, const SubjectHabits& habits, Approach approach,
                                  const HeadMap& map, double onset, Random& random);

}  // namespace tactile::sim::fur

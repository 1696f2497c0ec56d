#pragma once
// The NAO Cellular Skin simulator's internal model (paper 000, Kaboli et al.; spec §1):
// a hand made of footprint parts that move over one side's cells (nao_gestures.cpp), and the
// skin that turns them into force, proximity, acceleration and temperature (nao_skin.cpp).
// Private to core/src/sim; the public entry point is simulate_nao_trial (nao_sim.cpp).

#include <Eigen/Core>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/sim/sim_util.h"

namespace tactile::sim::nao {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kGravity = 9.81;  // m/s^2 per g

//---- Hand -------------------------------------------------------------------------------------

// One part of the hand (palm, a finger, a fingertip, a nail, the base of a fist, or a part that
// only hovers) over the time of one gesture, sampled at the skin's rate. Its footprint is an
// ellipse on the map; its pressure is a paraboloid over that ellipse.
struct HandPart {
  double semi_major = 0.0;  // mm, along `angle`
  double semi_minor = 0.0;  // mm
  double angle = 0.0;       // rad, direction of the major axis on the map
  // Width of the strip of skin whose surface texture the part averages while it slides: a nail
  // edge feels every ridge (broadband vibration), a finger pad or a palm smooths them out.
  double texture_width = 8.0;  // mm
  double friction = 0.6;       // kinetic friction coefficient against the silicone
  int64_t first_sample = 0;    // recording sample of x[0]
  // Per sample: footprint centre (mm), height of the footprint above the cell plane (mm) and
  // normal force pressed into the skin (N, 0 when not in contact).
  std::vector<float> x, y, height, force;

  int64_t last_sample() const { return first_sample + static_cast<int64_t>(x.size()); }
};

// A subject's habits, drawn once per subject so they persist across trials (nobody was told
// how long, how hard or where to touch).
struct SubjectHabits {
  double force_scale = 1.0;        // how hard this person presses and hits
  double speed_scale = 1.0;        // how fast they move
  double duration_scale = 1.0;     // how long they hold prolonged touches
  double hand_scale = 1.0;         // hand size
  double approach_speed = 300.0;   // mm/s, hand descending onto the skin
  Point2 preferred_offset;         // mm from the side's centre where they tend to touch
  double preferred_angle = 0.0;    // rad, finger direction relative to "fingers up the map"
  double poke_two_fingers = 0.3;   // probability of poking with two fingers instead of one
  double push_with_palm = 0.5;     // probability of pushing with the palm (else fingers)
  int fingers = 3;                 // fingers used for scratch, stroke, tickle
  double rub_frequency = 2.0;      // Hz, back and forth
  double rub_amplitude = 20.0;     // mm
  double rub_across = 0.5;         // probability of rubbing across the fingers' direction
  double scratch_frequency = 4.0;  // Hz
  double stroke_speed = 150.0;     // mm/s
  double stroke_across = 0.3;      // probability of stroking across the fingers' direction
  int stroke_sweeps = 2;           // sweeps per stroke
  double tickle_period = 0.22;     // s, one finger's touch-slide-lift cycle
};

SubjectHabits draw_habits(Random& random);

// Where one side's cells lie on the map.
struct SideArea {
  std::string id;               // layout group id: "front" or "back"
  std::vector<int> cells;       // indices into layout.taxels
  std::vector<Point2> centres;  // of those cells, same order
  Point2 centre, low, high;     // mean of the cell centres and bounding box of their outlines
  double pitch = 0.0;           // smallest distance between two cell centres (mm)
};

// One gesture of one class on one side: the hand parts and the ground truth.
struct Gesture {
  int class_index = 0;
  int side = 0;  // index into the sides
  std::vector<HandPart> parts;
  double contact_start = 0.0;  // s, first instant of physical contact
  double contact_end = 0.0;    // s, last instant of physical contact
  int64_t last_sample() const;
};

// Builds the hand motion of `class_name` (one of the layout's nao classes) whose approach starts
// at `start` seconds; throws tactile::Error for a class this simulator does not know.
Gesture build_gesture(const std::string& class_name, const SideArea& side,
                      const SubjectHabits& habits, Random& random, double start, double rate_hz);

// Delays a gesture by `samples`, contact times included.
void shift_gesture(Gesture& gesture, int64_t samples, double rate_hz);

//---- Skin -------------------------------------------------------------------------------------

// The robot's motion under the skin, in the torso frame (x: robot's left, y: down, z: forward),
// as the specific force an accelerometer fixed to the torso would read (g), plus the vibration
// of the joints' gears that every cell feels (g, along the cell normal before mounting tilt).
struct BodyMotion {
  Eigen::MatrixXd specific_force;   // samples x 3
  Eigen::VectorXd joint_vibration;  // samples
  std::string motion;               // "none", "walking" or "sit-stand"
};

BodyMotion simulate_body_motion(const std::string& motion, int64_t samples, double rate_hz,
                                Random& random);

// Writes all channels of the layout into `samples` (rows: samples, columns: layout channels)
// from the hand gestures and the body motion. `hardware` draws the fixed properties of the
// cells (resonances, mounting, offsets); `noise` the sensor noise and drift of this trial.
void render_skin(const SkinLayout& layout, const std::vector<SideArea>& sides,
                 const std::vector<Gesture>& gestures, const BodyMotion& body, double rate_hz,
                 Random& hardware, Random& noise, Eigen::Ref<Eigen::MatrixXf> samples);

}  // namespace tactile::sim::nao

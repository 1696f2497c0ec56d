#pragma once
// The Robovie-IIF piezo skin (paper 003) simulated from its physics. A person's hands
// press contact patches onto the skin (positions on the layout's unwrapped map), the
// robot's own joints bend the skin under the films, and every PVDF film answers the
// CHANGE of the load it carries: a charge amplifier turns it into a first-order high-pass
// of the load, so a constant press decays to zero. A 16-bit signed ADC samples at 100 Hz.
//
// These building blocks are what simulate_robovie_trial (simulator.h) is made of; they
// are public so tests and live sources can drive the same sensor with their own touches.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile::sim::robovie {

constexpr double kSampleRate = 100.0;  // Hz (paper 003, Sec. IV-A)
constexpr double kAdcLow = -32768.0;   // counts, 16-bit signed A/D
constexpr double kAdcHigh = 32767.0;
constexpr int kAdcBits = 16;

// Which half of the unwrapped map a film is drawn on (the layout's "side" groups).
enum class View { kFront, kBack };

// An axis-aligned rectangle on the map (mm).
struct MapArea {
  Point2 low;
  Point2 high;
  Point2 center() const { return {(low.x + high.x) * 0.5, (low.y + high.y) * 0.5}; }
  // The point at fractions (u, v) of the width and height; (0.5, 0.5) is the centre.
  Point2 at(double u, double v) const {
    return {low.x + u * (high.x - low.x), low.y + v * (high.y - low.y)};
  }
};

// The films of a layout in channel order: where each one sits and what it belongs to.
struct Films {
  std::vector<Point2> center;     // mm on the map
  std::vector<Point2> half_size;  // mm
  std::vector<View> view;
  std::vector<int> body_part;           // index into body_parts
  std::vector<std::string> body_parts;  // ids of the layout's "body-part" groups
  int64_t count() const { return static_cast<int64_t>(center.size()); }
};

// Reads the films from a layout with one "piezo" channel per taxel and "front"/"back"
// side groups. Throws tactile::Error naming the layout and what is missing.
Films films_of(const SkinLayout& layout);

// The map rectangle spanned by the films of body part `group` drawn in `view`. Throws
// tactile::Error when that body part has no film there.
MapArea body_area(const Films& films, const std::string& group, View view);

// One hand part (palm, finger pad, forearm, the person's torso) pressing on the skin.
struct Contact {
  double onset = 0.0;            // s, first instant of physical contact
  double duration = 0.0;         // s, contact lasts [onset, onset + duration]
  double rise = 0.05;            // s, raised-cosine ramp of the force at onset
  double fall = 0.05;            // s, and at release
  double force = 0.0;            // N, normal force of the whole patch
  Point2 center;                 // mm on the map at onset
  Point2 half_size{40.0, 45.0};  // mm; the patch is a rectangle (a palm by default)
  Point2 velocity;               // mm/s: a stroke slides the patch
  Point2 sway;                   // mm: amplitude of a back-and-forth rub along this vector
  double sway_hz = 0.0;
  double pulse_depth = 0.0;  // 0..1: share of the force that comes and goes (pumping, lifting)
  double pulse_hz = 0.0;
  double phase = 0.0;  // rad, of sway and pulse

  double end() const { return onset + duration; }
};

// Adds the force (N) each film carries from `contact` into `load` (samples x films, sample
// n at time n / rate_hz). The patch's pressure is spread evenly over its rectangle, blurred
// a few mm by the silicone, and each film takes the share over its own area.
void add_contact_load(const Films& films, const Contact& contact, double rate_hz,
                      SampleMatrix& load);

// The soft silicone the films are embedded in carries each film's contact load to the films
// around it on the same side of the map (front or back), falling with distance: load becomes
// load x S, S = I + 0.5 exp(-distance / 40 mm) between two films of one side.
void spread_through_skin(const Films& films, SampleMatrix& load);

// The robot's joints whose motion bends the skin.
enum class Joint { kHead, kRightArm, kLeftArm, kWaist };
constexpr int kJointCount = 4;

// One movement of a joint. kBump goes out by `amplitude` and back (a gesture), kRamp goes
// there and stays (a turn), kOscillation swings +-amplitude at `frequency_hz` (a hand shake
// pumping the arm) with short ramps in and out.
struct JointMove {
  enum class Shape { kBump, kRamp, kOscillation };
  Joint joint = Joint::kHead;
  Shape shape = Shape::kBump;
  double onset = 0.0;      // s
  double duration = 0.0;   // s
  double amplitude = 0.0;  // rad
  double frequency_hz = 0.0;
};

// Joint angles (samples x kJointCount, rad) from a list of movements.
Eigen::MatrixXf joint_angles(const std::vector<JointMove>& moves, double rate_hz, int64_t samples);

// One robot's skin: drawn once per seed, the same for every subject and trial.
struct Robot {
  Eigen::VectorXd gain;           // counts per N, per film (film and silicone spread)
  Eigen::VectorXd time_constant;  // s, of each film's charge amplifier high-pass
  Eigen::VectorXd offset;         // counts, amplifier offset
  Eigen::VectorXd noise;          // counts RMS, electronic noise
  Eigen::MatrixXf coupling;       // films x joints: load (N) per rad of joint angle
  Eigen::MatrixXf vibration;      // films x joints: counts RMS per rad/s of joint speed
};

// A robot for these films. Joint couplings are strongest on the films over the moving
// parts (shoulders, arms; neck for the head; hips for the waist) and weak elsewhere.
Robot make_robot(const Films& films, uint64_t seed);

// Adds the load the joints' bending puts on each film: load += angles x coupling^T.
void add_joint_load(const Robot& robot, const Eigen::MatrixXf& angles, SampleMatrix& load);

// The films' output in ADC counts, in place: `load` (samples x films, N, from contacts and
// joint bending) becomes the high-passed, noisy, quantised signal. `angles` are the joint
// angles the load was bent with; their speed drives the motors' vibration noise.
void piezo_output(const Robot& robot, const Eigen::MatrixXf& angles, double rate_hz, Random& noise,
                  SampleMatrix& load);

}  // namespace tactile::sim::robovie

namespace tactile {
// The whole trial (simulator.h's generator for "robovie"): a 15-stage session of one subject,
// stream "skin" (274 films, counts) and stream "commands" (one "stage" sample per start
// command, irregular time stamps), one ground-truth label per stage. options.repetitions is
// ignored: one session per trial.
SimulatedTrial simulate_robovie_trial(const SkinLayout& layout, const SimulationOptions& options,
                                      int subject, int trial);
}  // namespace tactile

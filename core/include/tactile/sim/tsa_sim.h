#pragma once
// The `tsa` skin simulator (paper 001, spec §2): capacitive 4x4 sheets read by front-end
// modules at 8 Hz, touched by a finger, a fingertip or a palm that taps, pokes or slides.
//
// The generator works in two stages: a touch plan (who touches which sheet, where, how long
// and along which path; tsa_sim.cpp) and the front end (footprint over pads -> capacitance
// -> 12-bit counts with drift and noise; tsa_front_end.cpp). Both are declared here so that
// tests can check each stage alone.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile {

// One trial of one subject on the `tsa` layout (registered as the "tsa" generator). Throws
// tactile::Error when the layout lacks the sheet/location/module groups or the six classes,
// or when options.repetitions, subject or trial is negative.
SimulatedTrial simulate_tsa_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial);

namespace sim::tsa {

// The paper collected ~1000 events over six classes (about 167 per class, two groups); one
// simulated trial holds 5 of each by default, so a handful of subjects gives a data set.
constexpr int kDefaultRepetitions = 5;
constexpr double kFramePeriod = 0.125;  // 8 Hz frames (paper Sec. II-D)
constexpr double kCountMax = 4095.0;    // 12-bit words

enum class Hand { kFinger, kFingertip, kPalm };
const char* hand_name(Hand hand);  // "finger", "fingertip", "palm"

// Movement directions of the paper's Fig. 8 with the codes of spec §2.10 (0 = stationary).
// Map and sheet coordinates have x to the right and y downwards.
enum class Direction : int {
  kNone = 0,
  kClockwise = 1,
  kCounterClockwise = 2,
  kLeftToRight = 3,
  kRightToLeft = 4,
  kUpToDown = 5,
  kDownToUp = 6,
  kUpperLeftToLowerRight = 7,
  kLowerRightToUpperLeft = 8,
  kLowerLeftToUpperRight = 9,
  kUpperRightToLowerLeft = 10,
};
// "none", "clockwise", "counter-clockwise", "left->right", ... (the label note's vocabulary).
const char* direction_name(Direction direction);
// Unit vector of a straight direction on the map (x right, y down); {0, 0} for the others.
Point2 direction_vector(Direction direction);

// One sheet of 4x4 pads, from the layout's groups and taxel positions.
struct Sheet {
  std::string id;                    // sheet group id, e.g. "m03.s2"
  std::string location;              // id of the "location" group holding it, e.g. "arm-left"
  std::vector<int> taxels;           // indices into layout.taxels
  std::vector<int> columns;          // stream column of each taxel
  std::vector<Point2> pad_centres;   // map position of each taxel (mm)
  std::vector<double> scan_offsets;  // s after the frame start at which each pad is converted
  Point2 centre;                     // mean pad position (mm)
  double pitch = 7.0;                // nearest pad spacing (mm)
  double pad_radius = 2.5;           // mm
};
// Throws tactile::Error(layout.id, ...) when a sheet, location or module group is missing.
std::vector<Sheet> layout_sheets(const SkinLayout& layout);

// An elliptical contact patch on the map.
struct Footprint {
  Point2 centre;
  double half_length = 6.0;  // mm, along `angle`
  double half_width = 5.0;   // mm
  double angle = 0.0;        // rad, long axis from +x towards +y
};

// Share (0..1) of a round pad's sensing area, widened by the field's fringe, that lies under
// the footprint: the footprint's edge is taken as straight across the pad, so a pad goes from
// off to on over one pad diameter as an edge crosses it.
double pad_coverage(const Point2& pad, double sensing_radius, const Footprint& footprint);

// One planned touch: a contact from `contact_start` to `contact_end` (the label's t0, t1),
// with the hand approaching and leaving over `approach` s on either side.
struct Touch {
  int class_index = 0;
  Hand hand = Hand::kFinger;
  Direction direction = Direction::kNone;
  int sheet = 0;  // index into layout_sheets()
  double contact_start = 0.0;
  double contact_end = 0.0;
  double approach = 0.03;
  // Path of the footprint centre: a straight line from `start` to `end`, bowed sideways by
  // `bow` mm at its middle, or (for circular directions) an arc around `start` of `radius`
  // from `start_angle` sweeping `sweep` rad (positive = clockwise on the y-down map).
  Point2 start;
  Point2 end;
  double bow = 0.0;
  double radius = 0.0;
  double start_angle = 0.0;
  double sweep = 0.0;
  Footprint shape;  // size and orientation; its centre is set along the path
};
// The footprint at time t (held at the path's ends before and after the contact), and how
// strongly the hand couples to the pads at t: 0 far away, rising through the approach to 1
// once the skin is pressed flat, falling again as it lifts.
Footprint footprint_at(const Touch& touch, double t);
double coupling_at(const Touch& touch, double t);

// Fixed properties of the built skin: one value per stream column (pad) or per sheet.
struct Device {
  std::vector<double> offset_counts;            // pad capacitance above the converter's reference
  std::vector<double> gain;                     // pad-to-pad sensitivity spread (about 1)
  std::vector<double> temperature_coefficient;  // counts per kelvin of the module's board
  std::vector<double> noise_counts;             // rms conversion noise
  std::vector<int> module_of_column;            // module index per column
  std::vector<double> full_cover_counts;        // per sheet: count rise of a fully covered pad
  std::vector<double> sensing_radius;  // per sheet: pad radius widened by the fringe field (mm)
  int module_count = 0;
};
// Drawn from derive_engine(seed, "tsa-device") only: the same robot for every subject.
Device make_device(const SkinLayout& layout, const std::vector<Sheet>& sheets, uint64_t seed);

// Renders the touches into `samples` (frames x columns, 12-bit counts): baseline, board
// temperature drift, conversion noise and the capacitance the touches add, quantised.
// `coupling_scale` is the subject's body coupling (about 1); `noise` draws the trial's drift
// and noise.
void render_front_end(const std::vector<Sheet>& sheets, const Device& device,
                      const std::vector<Touch>& touches, double coupling_scale, Random& noise,
                      SampleMatrix& samples);

}  // namespace sim::tsa
}  // namespace tactile

#pragma once
// A large uncalibrated pressure grid (any grid:RxC layout): 10-bit counts with a different
// rest level per taxel, noise, slow drift, crosstalk along the row lines and a few stuck or
// dead taxels, touched with seven social gestures of the kind an inflatable robot's skin
// records (tap, pat, push, stroke, slap, tickle, squeeze), each at a random place, size and
// force. `tactile simulate --skin grid:RxC` (docs/SIMULATION.md, "Pressure grid").

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/sim/simulator.h"

namespace tactile {

// The gestures in display order; a label's class is one of these.
const std::vector<std::string>& grid_gesture_classes();

// The sample rate of the simulated grid, Hz.
inline constexpr double kGridRateHz = 25.0;

// One labelled touch as planned: a contact (patches overlapping in time; a release between
// two patches of a gesture, as between a pat's pats, makes two touches of that gesture), when,
// and where its first patch is centred when the touch starts, in taxel units (row, column; 0
// is the first taxel's centre).
struct GridTouch {
  int gesture = 0;  // index into grid_gesture_classes()
  double t0 = 0.0, t1 = 0.0;
  double row = 0.0, column = 0.0;
  double radius = 0.0;  // the patch's larger semi-axis, taxels
  double force = 0.0;   // peak pressure, in units of the sensor's half-scale pressure
};

// The touches of one subject's trial on a rows x columns grid, in time order, with the
// recording's length (seconds) in `seconds`. Deterministic by (options.seed, subject, trial).
std::vector<GridTouch> plan_grid_touches(int64_t rows, int64_t columns,
                                         const SimulationOptions& options, int subject, int trial,
                                         double& seconds);

// The generator of grid:RxC recordings (TrialGenerator). Throws tactile::Error for a layout
// that is not a generic grid.
SimulatedTrial simulate_grid_trial(const SkinLayout& layout, const SimulationOptions& options,
                                   int subject, int trial);

// "grid-19x27-s01-t01" for layout grid:19x27: the recording id (a file name, so no ':').
std::string grid_recording_id(const std::string& layout_id, int subject, int trial);

}  // namespace tactile

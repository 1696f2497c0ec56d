#pragma once
// Physics of the silicone tactile flux sensor (paper 004): two orthogonal layers of
// piezo-resistive serpentines under a soft silicone cover, driven at constant current and read
// by a 10-bit ADC. Used by the flux simulator; kept apart so a live simulated source can share it.

#include <cstdint>
#include <vector>

#include "tactile/layout/skin_layout.h"

namespace tactile::sim {

//---- Geometry

// One serpentine in the sensor's physical frame: u across the first layer's stripes (the zone
// axis), v along them, both in mm from the sensor's corner.
struct Serpentine {
  int64_t taxel_id = 0;
  int layout_channel = -1;                        // index into SkinLayout::channels
  int layer = 0;                                  // 0 = nearest the touched surface
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;  // covered rectangle (mm)
  double depth = 0.0;                             // below the touched surface (mm)
};

struct FluxGeometry {
  double width = 0.0;                   // extent along u (mm)
  double height = 0.0;                  // extent along v (mm)
  std::vector<Serpentine> serpentines;  // layer by layer, in the layout's taxel order
};

// Places the layout's serpentines in one physical frame. The layout draws its layers side by
// side on the map; physically they are stacked, so each layer (a group of kind "layer", the
// first one nearest the surface) is mapped from its own bounding box onto the first layer's.
// Throws tactile::Error naming the layout when it has no layer groups or a taxel without a
// channel.
FluxGeometry flux_geometry(const SkinLayout& layout);

//---- Mechanics

// A fingertip on the surface: an elliptical Gaussian pressure footprint.
struct FingerContact {
  double u = 0.0, v = 0.0;     // centre (mm)
  double force = 0.0;          // normal force (N)
  double spread_along = 4.0;   // footprint standard deviation along its long axis (mm)
  double spread_across = 3.0;  // ... across it (mm)
  double angle = 0.0;          // long axis from the u axis (rad)
};

// Effective pressure (kPa, the unit of the paper's calibration) that the contact puts on each
// serpentine of `geometry`, written to pressures[0..serpentines-1]. Two paths: the load carried
// straight down through the cover (the footprint widened by the depth, integrated over the
// serpentine's rectangle) and the lateral stretch of the silicone around the indentation, which
// decays with the distance to the serpentine and is what the paper measures as crosstalk.
void serpentine_pressures(const FluxGeometry& geometry, const FingerContact& contact,
                          double* pressures);

// Visco-elastic response of one serpentine to its pressure: an elastic part that follows the
// load within milliseconds, and a viscous part that creeps up under load and relaxes slowly
// after release (paper 004 §5.2: relaxation of almost 7 s, like a slow-adapting receptor).
class ViscoelasticSerpentine {
 public:
  ViscoelasticSerpentine(double rate_hz, double relaxation_s);
  // Advances one sample under `pressure` (kPa) and returns the pressure the resistance follows.
  double step(double pressure) {
    elastic_ += elastic_rate_ * (pressure - elastic_);
    viscous_ += (pressure > viscous_ ? creep_rate_ : relax_rate_) * (pressure - viscous_);
    return kElasticShare * elastic_ + (1.0 - kElasticShare) * viscous_;
  }
  static constexpr double kElasticShare = 0.45;
  static constexpr double kElasticTime = 0.015;  // s
  static constexpr double kCreepTime = 0.30;     // s

 private:
  double elastic_rate_, creep_rate_, relax_rate_;
  double elastic_ = 0.0, viscous_ = 0.0;
};

//---- Electronics and temperature

// Paper 004 §5.2 Fig 5: baseline 519.6 Ohm at 10 degC rising 1.03 Ohm/degC (560.9 at 50 degC).
double flux_baseline_ohm(double temperature_c);
// Paper 004 §5.2 Fig 5: gain 4.67 Ohm/kPa at 10 degC to 15.99 at 50 degC, linear in temperature.
double flux_gain_ohm_per_kpa(double temperature_c);
// ADC counts per Ohm of serpentine resistance: constant drive current through the serpentine,
// a non-inverting amplifier, and a 10-bit ADC on a 5 V reference.
double flux_counts_per_ohm();
constexpr int kFluxAdcBits = 10;
constexpr double kFluxAdcMax = 1023.0;

}  // namespace tactile::sim

#pragma once
// Second-order Butterworth high-pass (bilinear transform, cut-off pre-warped), used to take a
// moving robot's own motion out of its skin's accelerometers before the Kaboli descriptors
// (gravity turning with the torso and the gait lie below a few Hz; a touch shakes the cell's
// plate at tens of Hz). Applied once it falls 40 dB per decade below the cut-off.

#include <Eigen/Core>

namespace tactile::dsp {

struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;  // a0 = 1
};

// Throws tactile::Error naming the cut-off or the rate when either is not positive or the
// cut-off is not below half the rate.
Biquad butterworth_high_pass(double cutoff_hz, double rate_hz);

// Direct form II transposed, started at rest on the first sample (a constant input gives
// zeros from the first sample on). Non-finite samples are not allowed here: the caller checks.
Eigen::VectorXd filter(const Biquad& section, const Eigen::Ref<const Eigen::VectorXd>& values);

}  // namespace tactile::dsp

#pragma once
// Butterworth high-pass of even order as a cascade of second-order sections (bilinear
// transform, cut-off pre-warped), used to take a moving robot's own motion out of its skin's
// accelerometers before the Kaboli descriptors (the gait and gravity turning with the torso lie
// below about 2 Hz; a touch shakes the torso at 3-9 Hz and a cell's plate at tens of Hz).
// Below the cut-off the gain falls 20 dB per decade per order.

#include <Eigen/Core>
#include <vector>

namespace tactile::dsp {

struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;  // a0 = 1
};

// The orders butterworth_high_pass builds.
constexpr bool is_butterworth_order(int order) {
  return order == 2 || order == 4 || order == 6 || order == 8;
}

// The sections of an `order`-th order high-pass (order 2, 4, 6 or 8). Throws tactile::Error
// naming the cut-off, the rate or the order when the cut-off or rate is not positive, the
// cut-off is not below half the rate, or the order is not one of those.
std::vector<Biquad> butterworth_high_pass(double cutoff_hz, double rate_hz, int order = 2);

// Direct form II transposed, started at rest on the first sample (a constant input gives
// zeros from the first sample on). Non-finite samples are not allowed here: the caller checks.
Eigen::VectorXd filter(const Biquad& section, const Eigen::Ref<const Eigen::VectorXd>& values);
// The sections one after the other, each started at rest.
Eigen::VectorXd filter(const std::vector<Biquad>& sections,
                       const Eigen::Ref<const Eigen::VectorXd>& values);

}  // namespace tactile::dsp

#pragma once
// First-order discrete RC high-pass (smart fur, paper 002 Sec. 3, spec §3.2) and the
// per-cell calibration that maps its output onto [0, 1] (spec §3.3).

#include <Eigen/Core>
#include <span>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile::dsp {

// α = RC / (RC + Δt), RC = 1 / (2π f_c), Δt = 1 / f_s. Throws tactile::Error naming the
// cut-off or the rate when either is not positive.
double high_pass_coefficient(double cutoff_hz, double rate_hz);

// y[t] = α (y[t-1] + u[t] - u[t-1]), y[-1] = 0, u[-1] = u[0]. A non-finite sample gives NaN
// and is skipped: the next finite sample continues from the last finite one.
Eigen::VectorXd high_pass(const Eigen::Ref<const Eigen::VectorXd>& values, double cutoff_hz,
                          double rate_hz);
// The same filter per column.
SampleMatrix high_pass_columns(const SampleMatrix& samples, double cutoff_hz, double rate_hz);

// v_c(t) = clamp(y_c(t) / r_c, 0, 1) with r_c the cell's calibration peak; a dead cell
// (r_c <= 0 or not finite) reads 0 throughout; NaN stays NaN. One peak per column, else
// tactile::Error.
SampleMatrix normalise_to_calibration(const SampleMatrix& filtered, std::span<const double> peaks);

}  // namespace tactile::dsp

#pragma once
// The TSA front end's IIR smoothing (paper 001 eq. 3, spec §2.2), in floating point and
// in the embedded integer form the module firmware uses.

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile::dsp {

// True for 1, 2, 4, 8, ...: eq. (3) divides by N with a shift, so N is a power of two.
bool is_power_of_two(int64_t value);

// TSA eq. (3): Avg[i] = Avg[i-1] + (val[i] - Avg[i-1]) / N, Avg[0] = val[0].
// A non-finite sample gives a NaN output and leaves the state as it was, so a missing
// frame is visible downstream and does not poison every later frame; the state starts at
// the first finite sample. Throws tactile::Error when N is not a power of two >= 1.
Eigen::VectorXd iir_average(const Eigen::Ref<const Eigen::VectorXd>& values, int64_t window);
// The same filter per column of a sample matrix (each channel smoothed on its own).
SampleMatrix iir_average_columns(const SampleMatrix& samples, int64_t window);
// TSA eq. (3), firmware form: Avg = (Avg·(N-1) + val) >> log2(N), truncating.
std::vector<int64_t> iir_average_integer(std::span<const int64_t> values, int64_t window);

}  // namespace tactile::dsp

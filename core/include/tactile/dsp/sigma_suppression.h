#pragma once
// Robovie preprocessing (spec §4.2): per sensor and per segment, a sample survives only
// when it stands out of the sensor's own noise; everything else becomes the mean.

#include <Eigen/Core>

namespace tactile::dsp {

// Robovie eq. (13): S'[t] = S[t] if |S[t] - mean(S)| > sigma(S) else mean(S), applied in
// place to every column (one column per sensor, one row per sample). sigma is the
// population standard deviation; a zero-variance column (spec §0 test) becomes its mean.
void suppress_within_sigma(Eigen::Ref<Eigen::MatrixXd> samples);

}  // namespace tactile::dsp

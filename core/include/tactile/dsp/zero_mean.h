#pragma once
// Zero-mean preprocessing (Kaboli et al. Sec 5.2, spec §1.3): each accelerometer and force
// signal of an action window has its mean removed before the descriptors are computed.

#include <Eigen/Core>

namespace tactile {

// Kaboli et al. Sec 5.2: x̃[t] = x[t] - mean(x). An empty signal stays empty.
Eigen::VectorXd zero_mean(const Eigen::Ref<const Eigen::VectorXd>& signal);

// The same for every column of `signals` (one signal per column), in place.
void zero_mean_columns(Eigen::Ref<Eigen::MatrixXd> signals);

}  // namespace tactile

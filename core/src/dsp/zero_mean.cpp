#include "tactile/dsp/zero_mean.h"

namespace tactile {

Eigen::VectorXd zero_mean(const Eigen::Ref<const Eigen::VectorXd>& signal) {
  if (signal.size() == 0) return Eigen::VectorXd();
  return signal.array() - signal.mean();
}

void zero_mean_columns(Eigen::Ref<Eigen::MatrixXd> signals) {
  if (signals.rows() == 0) return;
  // Column-major: each column is contiguous, so this is one pass per signal.
  signals.rowwise() -= signals.colwise().mean();
}

}  // namespace tactile

#include "tactile/dsp/sigma_suppression.h"

#include <cmath>
#include <span>

#include "tactile/stats/statistics.h"

namespace tactile::dsp {

void suppress_within_sigma(Eigen::Ref<Eigen::MatrixXd> samples) {
  const Eigen::Index count = samples.rows();
  if (count == 0) return;
  for (Eigen::Index sensor = 0; sensor < samples.cols(); ++sensor) {
    auto column = samples.col(sensor);
    const double average = column.mean();
    const double variance = (column.array() - average).square().mean();
    // Column-major storage: one sensor's samples are contiguous.
    const std::span<const double> values(column.data(), static_cast<size_t>(count));
    if (stats::is_zero_variance(variance, values)) {
      column.setConstant(average);
      continue;
    }
    const double sigma = std::sqrt(variance);
    // Robovie eq. (13): keep |S - mean| > sigma, replace the rest by the mean.
    column = ((column.array() - average).abs() > sigma).select(column, average);
  }
}

}  // namespace tactile::dsp

#include "tactile/dsp/high_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "tactile/error.h"

namespace tactile::dsp {

namespace {

template <typename In, typename Out>
void filter(const In* values, Out* filtered, int64_t count, double alpha) {
  double output = 0.0;
  double previous = 0.0;
  bool started = false;
  for (int64_t t = 0; t < count; ++t) {
    const double value = values[t];
    if (!std::isfinite(value)) {
      filtered[t] = std::numeric_limits<Out>::quiet_NaN();
      continue;
    }
    if (!started) previous = value;  // u[-1] = u[0]
    started = true;
    // Müller et al. (spec §3.2): y[t] = α (y[t-1] + u[t] - u[t-1]).
    output = alpha * (output + value - previous);
    previous = value;
    filtered[t] = static_cast<Out>(output);
  }
}

}  // namespace

double high_pass_coefficient(double cutoff_hz, double rate_hz) {
  if (!(cutoff_hz > 0.0) || !std::isfinite(cutoff_hz))
    throw Error("cutoff_hz", "the high-pass cut-off must be a positive frequency");
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz))
    throw Error("rate", "the high-pass needs a positive sample rate");
  const double resistance_capacitance = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
  return resistance_capacitance / (resistance_capacitance + 1.0 / rate_hz);
}

Eigen::VectorXd high_pass(const Eigen::Ref<const Eigen::VectorXd>& values, double cutoff_hz,
                          double rate_hz) {
  const double alpha = high_pass_coefficient(cutoff_hz, rate_hz);
  const Eigen::VectorXd contiguous = values;
  Eigen::VectorXd filtered(contiguous.size());
  filter(contiguous.data(), filtered.data(), contiguous.size(), alpha);
  return filtered;
}

SampleMatrix high_pass_columns(const SampleMatrix& samples, double cutoff_hz, double rate_hz) {
  const double alpha = high_pass_coefficient(cutoff_hz, rate_hz);
  SampleMatrix filtered(samples.rows(), samples.cols());
  for (Eigen::Index column = 0; column < samples.cols(); ++column)
    filter(samples.col(column).data(), filtered.col(column).data(), samples.rows(), alpha);
  return filtered;
}

SampleMatrix normalise_to_calibration(const SampleMatrix& filtered, std::span<const double> peaks) {
  if (static_cast<Eigen::Index>(peaks.size()) != filtered.cols())
    throw Error("calibration_peak", std::to_string(peaks.size()) + " calibration peaks for " +
                                        std::to_string(filtered.cols()) + " channels");
  SampleMatrix normalised(filtered.rows(), filtered.cols());
  for (Eigen::Index column = 0; column < filtered.cols(); ++column) {
    const double peak = peaks[column];
    const bool dead = !(peak > 0.0) || !std::isfinite(peak);
    // A missing sample stays NaN so that whoever reads the segment can name it.
    const auto normalise = [peak, dead](float value) -> float {
      if (std::isnan(value)) return value;
      if (dead) return 0.0f;
      return static_cast<float>(std::clamp(value / peak, 0.0, 1.0));
    };
    normalised.col(column) = filtered.col(column).unaryExpr(normalise);
  }
  return normalised;
}

}  // namespace tactile::dsp

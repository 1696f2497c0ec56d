#include "tactile/dsp/iir_average.h"

#include <cmath>
#include <limits>
#include <string>

#include "tactile/error.h"

namespace tactile::dsp {

namespace {

void check_window(int64_t window) {
  if (!is_power_of_two(window))
    throw Error("iir_n",
                "the IIR average's N must be a power of two >= 1, not " + std::to_string(window));
}

// One channel, contiguous in and out; the loop carries the filter state, so it stays plain.
template <typename In, typename Out>
void smooth(const In* values, Out* smoothed, int64_t count, double window) {
  double average = 0.0;
  bool started = false;
  for (int64_t i = 0; i < count; ++i) {
    const double value = values[i];
    if (!std::isfinite(value)) {
      smoothed[i] = std::numeric_limits<Out>::quiet_NaN();
      continue;
    }
    // TSA eq. (3): Avg[i] = Avg[i-1] + (val[i] - Avg[i-1]) / N.
    average = started ? average + (value - average) / window : value;
    started = true;
    smoothed[i] = static_cast<Out>(average);
  }
}

}  // namespace

bool is_power_of_two(int64_t value) { return value >= 1 && (value & (value - 1)) == 0; }

Eigen::VectorXd iir_average(const Eigen::Ref<const Eigen::VectorXd>& values, int64_t window) {
  check_window(window);
  const Eigen::VectorXd contiguous = values;
  Eigen::VectorXd smoothed(contiguous.size());
  smooth(contiguous.data(), smoothed.data(), contiguous.size(), static_cast<double>(window));
  return smoothed;
}

SampleMatrix iir_average_columns(const SampleMatrix& samples, int64_t window) {
  check_window(window);
  SampleMatrix smoothed(samples.rows(), samples.cols());
  for (Eigen::Index column = 0; column < samples.cols(); ++column)
    smooth(samples.col(column).data(), smoothed.col(column).data(), samples.rows(),
           static_cast<double>(window));
  return smoothed;
}

std::vector<int64_t> iir_average_integer(std::span<const int64_t> values, int64_t window) {
  check_window(window);
  int shift = 0;
  while ((int64_t{1} << shift) < window) ++shift;
  std::vector<int64_t> smoothed(values.size());
  int64_t average = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    // TSA eq. (3), firmware form: Avg = (Avg·(N-1) + val) >> log2(N).
    average = i == 0 ? values[0] : (average * (window - 1) + values[i]) >> shift;
    smoothed[i] = average;
  }
  return smoothed;
}

}  // namespace tactile::dsp

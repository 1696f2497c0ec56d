#include "tactile/dsp/butterworth.h"

#include <cmath>
#include <numbers>

#include "tactile/error.h"

namespace tactile::dsp {

std::vector<Biquad> butterworth_high_pass(double cutoff_hz, double rate_hz, int order) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz))
    throw Error("rate", "the high-pass needs a positive sample rate");
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * rate_hz))
    throw Error("cutoff_hz", "the high-pass cut-off must lie between 0 and half the rate (" +
                                 std::to_string(0.5 * rate_hz) + " Hz)");
  if (!is_butterworth_order(order))
    throw Error("order", std::to_string(order) + ": the high-pass order must be 2, 4, 6 or 8");
  // The analogue prototype's poles in conjugate pairs at angles theta_k = pi (2k + 1) / (2n)
  // from the negative real axis: H_k(s) = s^2 / (s^2 + 2 cos(theta_k) s + 1), each section
  // mapped by s = K (1 - z^-1) / (1 + z^-1), K = 1 / tan(pi fc / fs).
  const double k = 1.0 / std::tan(std::numbers::pi * cutoff_hz / rate_hz);
  std::vector<Biquad> sections;
  for (int pair = 0; pair < order / 2; ++pair) {
    const double theta = std::numbers::pi * (2.0 * pair + 1.0) / (2.0 * order);
    const double damping = 2.0 * std::cos(theta);  // sqrt(2) for order 2
    const double norm = 1.0 / (k * k + damping * k + 1.0);
    Biquad section;
    section.b0 = k * k * norm;
    section.b1 = -2.0 * section.b0;
    section.b2 = section.b0;
    section.a1 = 2.0 * (1.0 - k * k) * norm;
    section.a2 = (k * k - damping * k + 1.0) * norm;
    sections.push_back(section);
  }
  return sections;
}

Eigen::VectorXd filter(const Biquad& s, const Eigen::Ref<const Eigen::VectorXd>& values) {
  Eigen::VectorXd out(values.size());
  if (values.size() == 0) return out;
  // At rest on x[0]: with y = 0 (no DC gain) the delay states hold what x[0] feeds them.
  const double x0 = values[0];
  double z2 = s.b2 * x0;
  double z1 = s.b1 * x0 + z2;
  for (Eigen::Index t = 0; t < values.size(); ++t) {
    const double x = values[t];
    const double y = s.b0 * x + z1;
    z1 = s.b1 * x - s.a1 * y + z2;
    z2 = s.b2 * x - s.a2 * y;
    out[t] = y;
  }
  return out;
}

Eigen::VectorXd filter(const std::vector<Biquad>& sections,
                       const Eigen::Ref<const Eigen::VectorXd>& values) {
  Eigen::VectorXd out = values;
  for (const Biquad& section : sections) out = filter(section, out);
  return out;
}

}  // namespace tactile::dsp

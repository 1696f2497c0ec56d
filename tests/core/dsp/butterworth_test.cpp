// The Butterworth high-pass that takes a moving robot's own motion out of the NAO
// accelerometers: its gain at, above and below the cut-off for orders 2 and 4, its start at
// rest, and bad input.
#include "tactile/dsp/butterworth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tactile/error.h"

namespace tactile {
namespace {

// Steady-state gain for a sine at `hz` (the second half of 20 periods, after the start).
double gain_at(double hz, double cutoff_hz, double rate_hz, int order = 2) {
  const int64_t count = static_cast<int64_t>(std::ceil(20.0 * rate_hz / hz));
  Eigen::VectorXd input(count);
  for (int64_t s = 0; s < count; ++s)
    input[s] = std::sin(2.0 * std::numbers::pi * hz * static_cast<double>(s) / rate_hz);
  const Eigen::VectorXd output =
      dsp::filter(dsp::butterworth_high_pass(cutoff_hz, rate_hz, order), input);
  const Eigen::Index half = count / 2;
  const double in = input.tail(count - half).norm(), out = output.tail(count - half).norm();
  return out / in;
}

TEST(ButterworthHighPass, HalfPowerAtTheCutOffFortyDecibelsPerDecadeBelow) {
  EXPECT_NEAR(gain_at(5.0, 5.0, 250.0), 1.0 / std::numbers::sqrt2, 0.01);
  EXPECT_NEAR(gain_at(50.0, 5.0, 250.0), 1.0, 0.01);
  EXPECT_NEAR(gain_at(0.5, 5.0, 250.0), 0.01, 0.002);  // (0.5 / 5)^2
}

TEST(ButterworthHighPass, FourthOrderHalfPowerAtTheCutOffEightyDecibelsPerDecadeBelow) {
  EXPECT_EQ(dsp::butterworth_high_pass(7.0, 250.0, 4).size(), 2u);
  EXPECT_NEAR(gain_at(7.0, 7.0, 250.0, 4), 1.0 / std::numbers::sqrt2, 0.01);
  EXPECT_NEAR(gain_at(70.0, 7.0, 250.0, 4), 1.0, 0.01);
  EXPECT_NEAR(gain_at(0.7, 7.0, 250.0, 4), 1e-4, 2e-5);  // (0.7 / 7)^4
  // Maximally flat: no peak above the cut-off.
  for (const double hz : {8.0, 10.0, 14.0, 20.0, 40.0})
    EXPECT_LT(gain_at(hz, 7.0, 250.0, 4), 1.0 + 1e-3) << hz;
}

TEST(ButterworthHighPass, StartsAtRestOnTheFirstSample) {
  Eigen::VectorXd constant = Eigen::VectorXd::Constant(50, -0.98);
  const Eigen::VectorXd output = dsp::filter(dsp::butterworth_high_pass(5.0, 250.0), constant);
  EXPECT_LT(output.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(dsp::filter(dsp::butterworth_high_pass(5.0, 250.0), Eigen::VectorXd()).size(), 0);
  const Eigen::VectorXd fourth = dsp::filter(dsp::butterworth_high_pass(7.0, 250.0, 4), constant);
  EXPECT_LT(fourth.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ButterworthHighPass, CutOffOutsideZeroToNyquistNamesIt) {
  EXPECT_THROW(dsp::butterworth_high_pass(0.0, 250.0), Error);
  EXPECT_THROW(dsp::butterworth_high_pass(125.0, 250.0), Error);
  EXPECT_THROW(dsp::butterworth_high_pass(5.0, 0.0), Error);
  try {
    dsp::butterworth_high_pass(200.0, 250.0);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cutoff_hz"), std::string::npos) << error.what();
  }
  for (const int order : {0, 1, 3, 10}) {
    try {
      dsp::butterworth_high_pass(5.0, 250.0, order);
      FAIL() << order;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("order"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace tactile

// Flux sensor preprocessing (spec §5.2-5.4): moving average, ratiometric deviation with a
// re-sampled baseline, virtual sums. Expected numbers from TEST_VECTORS.md X1.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/dsp/flux.h"
#include "tactile/error.h"

namespace tactile::dsp {
namespace {

Eigen::VectorXd x1_raw() {
  Eigen::VectorXd raw(15);
  raw << 100, 100, 100, 100, 100, 100, 100, 100, 100, 100, 120, 140, 160, 160, 160;
  return raw;
}

TEST(FluxMovingAverage, IsCausalWithAShorterWindowAtStartUp) {
  const Eigen::VectorXd averaged = causal_moving_average(x1_raw(), 10);
  const double expected[15] = {100, 100, 100, 100, 100, 100, 100, 100,
                               100, 100, 102, 106, 112, 118, 124};
  for (int n = 0; n < 15; ++n) EXPECT_NEAR(averaged[n], expected[n], 1e-9) << n;
  Eigen::VectorXd ramp(4);
  ramp << 1, 2, 3, 4;
  const Eigen::VectorXd started = causal_moving_average(ramp, 10);
  EXPECT_DOUBLE_EQ(started[0], 1.0);
  EXPECT_DOUBLE_EQ(started[1], 1.5);
  EXPECT_DOUBLE_EQ(started[3], 2.5);
}

TEST(FluxMovingAverage, NaNSpoilsOnlyTheWindowsThatHoldIt) {
  Eigen::VectorXd raw = Eigen::VectorXd::Constant(20, 5.0);
  raw[4] = std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd averaged = causal_moving_average(raw, 3);
  EXPECT_DOUBLE_EQ(averaged[3], 5.0);
  EXPECT_TRUE(std::isnan(averaged[4]));
  EXPECT_TRUE(std::isnan(averaged[6]));
  EXPECT_DOUBLE_EQ(averaged[7], 5.0);
}

TEST(FluxRatiometric, MatchesTheSpecVectorAndItsSecondChannel) {
  Eigen::MatrixXd raw(15, 2);
  raw.col(0) = x1_raw();
  raw.col(1) = 0.5 * x1_raw().array() + 50.0;
  Eigen::MatrixXd averaged(15, 2);
  for (int column = 0; column < 2; ++column)
    averaged.col(column) = causal_moving_average(raw.col(column), 10);
  const RatiometricResult result = ratiometric_deviation(averaged, 1000.0, 2, FluxOptions{});
  ASSERT_EQ(result.baseline_samples, (std::vector<int64_t>{9}));
  const double e[15] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.02, 0.06, 0.12, 0.18, 0.24};
  const double e2[15] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.01, 0.03, 0.06, 0.09, 0.12};
  const double sum[15] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.03, 0.09, 0.18, 0.27, 0.36};
  for (int n = 0; n < 15; ++n) {
    EXPECT_NEAR(result.deviation(n, 0), e[n], 1e-12) << n;
    EXPECT_NEAR(result.deviation(n, 1), e2[n], 1e-12) << n;
    EXPECT_NEAR(result.deviation.row(n).sum(), sum[n], 1e-12) << n;
  }
}

// 100 Hz, so a minute is 6000 samples; the baseline creeps up 4 % per minute.
Eigen::MatrixXd drifting_baseline(int64_t count) {
  Eigen::MatrixXd averaged(count, 1);
  for (int64_t n = 0; n < count; ++n) averaged(n, 0) = 100.0 * (1.0 + 0.04 * n / 6000.0);
  return averaged;
}

TEST(FluxRatiometric, BaselineIsResampledEachMinuteWhenQuiet) {
  const RatiometricResult result =
      ratiometric_deviation(drifting_baseline(13000), 100.0, 1, FluxOptions{});
  EXPECT_EQ(result.baseline_samples, (std::vector<int64_t>{9, 6009, 12009}));
  // Just before the re-sample the drift shows; from it on it starts again from 0.
  EXPECT_NEAR(result.deviation(6008, 0), 0.04 * 5999 / 6000 / 1.00006, 1e-9);
  // V0 is the mean of the first half of the settled second before it: y at sample 5934.5.
  EXPECT_NEAR(result.deviation(6009, 0), (1 + 0.04 * 6009 / 6000) / (1 + 0.04 * 5934.5 / 6000) - 1,
              1e-12);
  EXPECT_LT(result.deviation(12008, 0), 0.04);
}

TEST(FluxRatiometric, ResampleWaitsForTheExcitationToEnd) {
  Eigen::VectorXd raw = Eigen::VectorXd::Constant(8000, 100.0);
  raw.segment(5950, 100).setConstant(130.0);  // a press across the one-minute mark
  Eigen::MatrixXd averaged(8000, 1);
  averaged.col(0) = causal_moving_average(raw, 10);
  const RatiometricResult result = ratiometric_deviation(averaged, 100.0, 1, FluxOptions{});
  ASSERT_EQ(result.baseline_samples.size(), 2u);
  // Onset at 5951 (y = 106): the 5 s window ends at 6451; the re-sample comes right then.
  EXPECT_GE(result.baseline_samples[1], 6451);
  EXPECT_LE(result.baseline_samples[1], 6452);
}

TEST(FluxRatiometric, ResampleWaitsForEveryChannelToBeQuietForOneSecond) {
  Eigen::MatrixXd averaged = Eigen::MatrixXd::Constant(8000, 2, 100.0);
  // The second (unwatched) channel is off baseline until 6300: no onset, but not quiet.
  averaged.col(1).segment(5000, 1300).setConstant(110.0);
  const RatiometricResult result = ratiometric_deviation(averaged, 100.0, 1, FluxOptions{});
  ASSERT_EQ(result.baseline_samples.size(), 2u);
  EXPECT_EQ(result.baseline_samples[1], 6300 + 100 - 1);
}

// 100 Hz: a press from 58 s, then the sensor's slow relaxation (τ = 7 s) from 4.8 % above rest.
Eigen::MatrixXd press_then_relaxation() {
  Eigen::MatrixXd averaged = Eigen::MatrixXd::Constant(9000, 1, 100.0);
  averaged.col(0).segment(5800, 100).setConstant(130.0);
  for (int64_t n = 5900; n < 9000; ++n)
    averaged(n, 0) = 100.0 + 4.8 * std::exp(-(n - 5900) / 700.0);
  return averaged;
}

TEST(FluxRatiometric, ResampleWaitsForTheRelaxationTailToSettle) {
  const RatiometricResult result =
      ratiometric_deviation(press_then_relaxation(), 100.0, 1, FluxOptions{});
  ASSERT_EQ(result.baseline_samples.size(), 2u);
  // The tail falls under 5 % at once, but still moves more than 0.1 % per half second
  // until it is about 1.4 % above rest (~8.6 s after the release).
  EXPECT_GT(result.baseline_samples[1], 6700);
  // At rest again the deviation stays close to 0 rather than a tail's worth below it.
  EXPECT_GT(result.deviation(8999, 0), -0.016);
}

TEST(FluxRatiometric, WithoutTheSettleTestTheTailBecomesTheBaseline) {
  FluxOptions spec_only;
  spec_only.baseline_settle = 1.0;  // any change passes: the spec's rule alone
  const RatiometricResult result =
      ratiometric_deviation(press_then_relaxation(), 100.0, 1, spec_only);
  ASSERT_EQ(result.baseline_samples.size(), 2u);
  // Window 5800..6299, re-armed after 0.5 s under θ_on: the re-sample lands in the tail.
  EXPECT_LT(result.baseline_samples[1], 6360);
  EXPECT_LT(result.deviation(8999, 0), -0.02);
}

TEST(FluxRatiometric, NonPositiveBaselineMarksTheChannelInvalidWithZeroDeviation) {
  Eigen::MatrixXd averaged(50, 2);
  averaged.col(0).setConstant(0.0);
  averaged.col(1).setLinSpaced(50, 100.0, 150.0);
  const RatiometricResult result = ratiometric_deviation(averaged, 100.0, 2, FluxOptions{});
  EXPECT_TRUE(result.invalid[0]);
  EXPECT_FALSE(result.invalid[1]);
  EXPECT_TRUE((result.deviation.col(0).array() == 0.0).all());
  EXPECT_GT(result.deviation(49, 1), 0.3);
}

TEST(FluxRatiometric, EmptyAndShortInputsAreDefined) {
  EXPECT_EQ(ratiometric_deviation(Eigen::MatrixXd(0, 3), 100.0, 3, FluxOptions{}).deviation.rows(),
            0);
  // Three samples: V0 comes from the last one, the only "full" window there is.
  Eigen::MatrixXd averaged(3, 1);
  averaged << 100, 100, 200;
  const RatiometricResult result = ratiometric_deviation(averaged, 100.0, 1, FluxOptions{});
  EXPECT_EQ(result.baseline_samples, (std::vector<int64_t>{2}));
  EXPECT_DOUBLE_EQ(result.deviation(0, 0), -0.5);
}

TEST(ExcitationDetector, DisarmsForTheWindowAndTheQuietTime) {
  ExcitationDetector detector(5, 2, 0.05);
  //                        0    1    2    3    4    5    6    7    8    9    10   11
  const double samples[] = {0.0, 0.1, 0.0, 0.2, 0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 0.3, 0.0};
  std::vector<int> onsets;
  for (int n = 0; n < 12; ++n)
    if (detector.step(samples[n])) onsets.push_back(n);
  // 3 and 6: inside the window or the refractory quiet; 10: quiet since 7, window over at 6.
  EXPECT_EQ(onsets, (std::vector<int>{1, 10}));
}

TEST(FluxChannels, FollowTheLayoutOrderOfTheSpec) {
  const FluxChannels channels = flux_channels(load_layout("flux"));
  EXPECT_EQ(channels.top, (std::vector<std::string>{"x1", "x2", "x3", "x4"}));
  EXPECT_EQ(channels.top_sum, "x_sum");
  EXPECT_EQ(channels.bottom, (std::vector<std::string>{"y1", "y2", "y3", "y4"}));
  EXPECT_EQ(channels.bottom_sum, "y_sum");
  EXPECT_THROW(flux_channels(make_grid_layout(2, 5)), Error);
}

TEST(FluxOptions, RejectBadValuesNamingTheKey) {
  try {
    flux_options(Parameters::parse("window_s=-1", "--params"));
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("window_s=-1"), std::string::npos) << error.what();
  }
  EXPECT_THROW(flux_options(Parameters::parse("average_window=0", "--params")), Error);
  EXPECT_EQ(flux_options(Parameters::parse("average_window=4", "--params")).average_window, 4);
}

//---- The whole chain on a recording

// The simulator's stream: the 8 real channels x1..x4, y1..y4 in ADC counts at 1 kHz.
Recording raw_flux_recording(int64_t count) {
  Recording recording;
  recording.id = "flux-test";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 1000.0;
  skin.channels = {"x1", "x2", "x3", "x4", "y1", "y2", "y3", "y4"};
  skin.units.assign(8, "counts");
  skin.samples = SampleMatrix::Constant(count, 8, 500.0f);
  for (int channel = 0; channel < 8; ++channel)
    skin.samples.col(channel).setConstant(400.0f + 20.0f * channel);
  recording.streams.push_back(skin);
  return recording;
}

TEST(FluxPreprocess, WritesTheTenLayoutChannelsWithTheVirtualSums) {
  const SkinLayout layout = load_layout("flux");
  Recording raw = raw_flux_recording(2000);
  raw.streams[0].samples.col(1).segment(1000, 500).array() += 84.0f;  // x2: +20 %
  raw.streams[0].samples.col(6).segment(1000, 500).array() += 52.0f;  // y3: +10 %
  const Recording processed = preprocess_flux(raw, layout, FluxOptions{});
  ASSERT_TRUE(is_flux_preprocessed(processed));
  const Stream& stream = processed.streams[0];
  ASSERT_EQ(stream.channels, (std::vector<std::string>{"x1", "x2", "x3", "x4", "x_sum", "y1", "y2",
                                                       "y3", "y4", "y_sum"}));
  EXPECT_NEAR(stream.samples(1400, 1), 0.2, 1e-6);
  EXPECT_NEAR(stream.samples(1400, 4), 0.2, 1e-6);  // x_sum
  EXPECT_NEAR(stream.samples(1400, 7), 0.1, 1e-6);  // y3
  EXPECT_NEAR(stream.samples(1400, 9), 0.1, 1e-6);  // y_sum
  EXPECT_NEAR(stream.samples(1004, 4), 0.2 * 5 / 10, 1e-6);
  EXPECT_EQ(stream.samples(500, 0), 0.0f);
  EXPECT_EQ(processed.metadata.at("flux.baseline_samples"), "1");
}

TEST(FluxPreprocess, MissingRealChannelNamesIt) {
  Recording raw = raw_flux_recording(100);
  raw.streams[0].channels[6] = "z3";
  try {
    preprocess_flux(raw, load_layout("flux"), FluxOptions{});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "flux-test stream skin");
    EXPECT_NE(error.message().find("y3"), std::string::npos) << error.message();
  }
}

TEST(FluxPreprocess, DeadChannelIsFlaggedInTheMetadata) {
  Recording raw = raw_flux_recording(100);
  raw.streams[0].samples.col(2).setZero();
  const Recording processed = preprocess_flux(raw, load_layout("flux"), FluxOptions{});
  EXPECT_EQ(processed.metadata.at("flux.invalid_channels"), "x3");
  EXPECT_TRUE(processed.streams[0].samples.allFinite());
}

}  // namespace
}  // namespace tactile::dsp

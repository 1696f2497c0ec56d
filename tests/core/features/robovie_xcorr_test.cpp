// Robovie-IIF (spec §4.1-4.3): sigma suppression, all-pairs cross-correlation, the
// scenario segmenter. Expected numbers from TEST_VECTORS.md R1.
#include "tactile/features/robovie_xcorr.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/dsp/sigma_suppression.h"
#include "tactile/error.h"
#include "tactile/segment/scenario.h"

namespace tactile {
namespace {

// TV R1: three sensors over eight samples, one column per sensor.
Eigen::MatrixXd r1_samples() {
  Eigen::MatrixXd samples(8, 3);
  samples.col(0) << 0, 0.1, 3, 2.5, 0.2, -0.1, 0, 0.1;
  samples.col(1) << 1, 1.2, 2.8, 3, 1.1, 0.9, 1, 1;
  samples.col(2) << 0, 2, 0, -2, 0, 2, 0, -2;
  return samples;
}

void expect_near_relative(double actual, double expected, double relative = 1e-5) {
  EXPECT_NEAR(actual, expected, relative * std::max(1.0, std::abs(expected)));
}

TEST(SigmaSuppression, KeepsOnlySamplesBeyondOneSigmaAndSetsTheRestToTheMean) {
  Eigen::MatrixXd samples = r1_samples();
  dsp::suppress_within_sigma(samples);
  Eigen::MatrixXd expected(8, 3);
  expected.col(0) << 0.725, 0.725, 3, 2.5, 0.725, 0.725, 0.725, 0.725;
  expected.col(1) << 1.5, 1.5, 2.8, 3, 1.5, 1.5, 1.5, 1.5;
  expected.col(2) << 0, 2, 0, -2, 0, 2, 0, -2;
  for (int t = 0; t < 8; ++t)
    for (int sensor = 0; sensor < 3; ++sensor)
      expect_near_relative(samples(t, sensor), expected(t, sensor));
}

TEST(SigmaSuppression, LeavesAConstantSensorConstant) {
  Eigen::MatrixXd samples = Eigen::MatrixXd::Constant(5, 1, 0.1);
  dsp::suppress_within_sigma(samples);
  for (int t = 0; t < 5; ++t) EXPECT_DOUBLE_EQ(samples(t, 0), 0.1);
}

TEST(RobovieCorrelation, MatchesTheSpecMatrixAfterSuppression) {
  Eigen::MatrixXd samples = r1_samples();
  dsp::suppress_within_sigma(samples);
  const Eigen::MatrixXd r = robovie_correlation_matrix(samples);
  const double expected[3][3] = {
      {1, 0.97504, -0.354266}, {0.97504, 1, -0.435929}, {-0.354266, -0.435929, 1}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) expect_near_relative(r(i, j), expected[i][j]);
}

TEST(RobovieCorrelation, FeatureVectorIsTheRowMajorUpperTriangle) {
  const Eigen::VectorXd suppressed = robovie_xcorr_vector(r1_samples(), true);
  ASSERT_EQ(suppressed.size(), 3);
  expect_near_relative(suppressed[0], 0.97504);
  expect_near_relative(suppressed[1], -0.354266);
  expect_near_relative(suppressed[2], -0.435929);
  const Eigen::VectorXd raw = robovie_xcorr_vector(r1_samples(), false);
  expect_near_relative(raw[0], 0.983681);
  expect_near_relative(raw[1], -0.389932);
  expect_near_relative(raw[2], -0.412654);
}

TEST(RobovieCorrelation, PairIndexFollowsTheSpecFormula) {
  EXPECT_EQ(robovie_pair_index(0, 1, 3), 0);
  EXPECT_EQ(robovie_pair_index(0, 2, 3), 1);
  EXPECT_EQ(robovie_pair_index(1, 2, 3), 2);
  EXPECT_EQ(robovie_pair_index(272, 273, 274), 37400);
  EXPECT_EQ(robovie_pair_count(274), 37401);
}

TEST(RobovieCorrelation, ProductEqualsThePairwisePearsonOfEveryPair) {
  // Many sensors, so the GEMM takes its blocked path; compare with pair loops.
  const int sensors = 40;
  const int samples_count = 300;
  Eigen::MatrixXd samples(samples_count, sensors);
  for (int t = 0; t < samples_count; ++t)
    for (int sensor = 0; sensor < sensors; ++sensor)
      samples(t, sensor) =
          std::sin(0.013 * (sensor + 1) * t + sensor) + 0.01 * ((t * 7919 + sensor * 104729) % 97);
  const Eigen::VectorXd features = robovie_xcorr_vector(samples, false);
  for (int i = 0; i < sensors; ++i)
    for (int j = i + 1; j < sensors; ++j) {
      const Eigen::ArrayXd x = samples.col(i).array() - samples.col(i).mean();
      const Eigen::ArrayXd y = samples.col(j).array() - samples.col(j).mean();
      const double pearson = (x * y).sum() / std::sqrt(x.square().sum() * y.square().sum());
      EXPECT_NEAR(features[robovie_pair_index(i, j, sensors)], pearson, 1e-12);
    }
}

TEST(RobovieCorrelation, ConstantSensorCorrelatesZeroWithEveryoneAndItself) {
  Eigen::MatrixXd samples = r1_samples();
  samples.col(1).setConstant(0.3);
  dsp::suppress_within_sigma(samples);
  const Eigen::MatrixXd r = robovie_correlation_matrix(samples);
  EXPECT_EQ(r(1, 1), 0.0);
  EXPECT_EQ(r(0, 1), 0.0);
  EXPECT_EQ(r(1, 2), 0.0);
  EXPECT_DOUBLE_EQ(r(0, 0), 1.0);
  EXPECT_TRUE(r.allFinite());
}

//---- Extractor over a recording

SkinLayout three_film_layout() {
  SkinLayout layout = make_strip_layout(3, "strip:3");
  return layout;
}

Recording r1_recording(const SkinLayout& layout) {
  Recording recording;
  recording.id = "r1";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 100.0;
  for (const Channel& channel : layout.channels) {
    skin.channels.push_back(channel.name);
    skin.units.push_back(channel.unit);
  }
  // Two seconds of silence, then the R1 samples at 1.00 s .. 1.07 s, then silence.
  skin.samples = SampleMatrix::Zero(200, 3);
  skin.samples.middleRows(100, 8) = r1_samples().cast<float>();
  recording.streams.push_back(skin);
  return recording;
}

TEST(RobovieXcorrExtractor, ExtractsTheSpecVectorFromALabelledSpan) {
  const SkinLayout layout = three_film_layout();
  const Recording recording = r1_recording(layout);
  const auto extractor = make_robovie_xcorr_extractor({});
  const auto columns = extractor->columns(layout);
  ASSERT_EQ(columns.size(), 3u);
  EXPECT_EQ(columns[1].name, "xcorr." + layout.channels[0].name + "." + layout.channels[2].name);
  Label segment;
  segment.t0 = 0.995;
  segment.t1 = 1.075;  // samples 100..107
  const FeatureResult result = extractor->extract({recording, layout, segment});
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  ASSERT_EQ(result.values.size(), 3u);
  // The samples went through float: compare to the spec to float precision.
  EXPECT_NEAR(result.values[0], 0.97504, 1e-5);
  EXPECT_NEAR(result.values[1], -0.354266, 1e-5);
  EXPECT_NEAR(result.values[2], -0.435929, 1e-5);
}

TEST(RobovieXcorrExtractor, SkipsASegmentOfOneSample) {
  const SkinLayout layout = three_film_layout();
  const Recording recording = r1_recording(layout);
  Label segment;
  segment.t0 = 1.0;
  segment.t1 = 1.005;
  const FeatureResult result =
      make_robovie_xcorr_extractor({})->extract({recording, layout, segment});
  EXPECT_TRUE(result.values.empty());
  EXPECT_NE(result.skip_reason.find("1 sample"), std::string::npos) << result.skip_reason;
}

TEST(RobovieXcorrExtractor, SkipsANaNSampleNamingTheFilmAndTime) {
  const SkinLayout layout = three_film_layout();
  Recording recording = r1_recording(layout);
  recording.streams[0].samples(103, 2) = std::numeric_limits<float>::quiet_NaN();
  Label segment;
  segment.t0 = 0.995;
  segment.t1 = 1.075;
  const FeatureResult result =
      make_robovie_xcorr_extractor({})->extract({recording, layout, segment});
  EXPECT_TRUE(result.values.empty());
  EXPECT_NE(result.skip_reason.find(layout.channels[2].name), std::string::npos)
      << result.skip_reason;
  EXPECT_NE(result.skip_reason.find("1.03"), std::string::npos) << result.skip_reason;
}

TEST(RobovieXcorrExtractor, SilentSegmentGivesZerosNotNaN) {
  const SkinLayout layout = three_film_layout();
  const Recording recording = r1_recording(layout);
  Label segment;
  segment.t0 = 0.0;
  segment.t1 = 0.5;
  const FeatureResult result =
      make_robovie_xcorr_extractor({})->extract({recording, layout, segment});
  ASSERT_EQ(result.values.size(), 3u);
  for (double value : result.values) EXPECT_EQ(value, 0.0);
}

TEST(RobovieXcorrExtractor, RawOptionSkipsTheSuppression) {
  const SkinLayout layout = three_film_layout();
  const Recording recording = r1_recording(layout);
  Label segment;
  segment.t0 = 0.995;
  segment.t1 = 1.075;
  const FeatureResult result =
      make_robovie_xcorr_extractor(Parameters::parse("sigma_suppression=false", "--params"))
          ->extract({recording, layout, segment});
  ASSERT_EQ(result.values.size(), 3u);
  EXPECT_NEAR(result.values[0], 0.983681, 1e-5);
}

TEST(RobovieXcorrExtractor, MissingFilmChannelNamesIt) {
  const SkinLayout layout = three_film_layout();
  Recording recording = r1_recording(layout);
  recording.streams[0].channels[1] = "other";
  Label segment;
  segment.t1 = 1.0;
  try {
    make_robovie_xcorr_extractor({})->extract({recording, layout, segment});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(layout.channels[1].name), std::string::npos)
        << error.what();
  }
}

TEST(RobovieXcorrExtractor, UnknownParameterIsRejected) {
  EXPECT_THROW(make_robovie_xcorr_extractor(Parameters::parse("sigma=1", "--params")), Error);
}

}  // namespace
}  // namespace tactile

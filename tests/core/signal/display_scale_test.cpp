#include "tactile/signal/display_scale.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tactile {
namespace {

TEST(RestScale, RestIsTheMedianAndTheScaleIgnoresOneSpike) {
  // Noise-free columns: the noise band is zero and changes show whole.
  Stream stream;
  stream.rate_hz = 10;
  stream.samples = SampleMatrix::Constant(1000, 2, 500.0f);
  // Column 1 is pressed down by 40 counts for 100 samples and spikes once.
  stream.samples.col(1).segment(300, 100).setConstant(460.0f);
  stream.samples(700, 1) = 5000.0f;
  const RestScale scale = rest_scale(stream, {0, 1, -1});
  EXPECT_FLOAT_EQ(scale.rest[0], 500.0f);
  EXPECT_FLOAT_EQ(scale.rest[1], 500.0f);
  EXPECT_TRUE(std::isnan(scale.rest[2]));
  EXPECT_NEAR(scale.max_change, 40.0, 1e-6);
  const std::vector<float> change = change_from_rest({500.0f, 460.0f, 3.0f}, scale);
  EXPECT_FLOAT_EQ(change[0], 0.0f);
  EXPECT_FLOAT_EQ(change[1], 40.0f);
  EXPECT_TRUE(std::isnan(change[2]));
}

TEST(RestScale, NoiseStaysDarkAndATouchShowsAboveIt) {
  Stream stream;
  stream.rate_hz = 10;
  stream.samples = SampleMatrix::Zero(2000, 1);
  // -1, 0, +1 cycling noise on a rest level of 100 (MAD 1), and a touch of +30 for 20 samples.
  for (int k = 0; k < 2000; ++k) stream.samples(k, 0) = 100.0f + static_cast<float>(k % 3 - 1);
  stream.samples.col(0).segment(1000, 20).setConstant(130.0f);
  const RestScale scale = rest_scale(stream, {0});
  EXPECT_NEAR(scale.noise_band[0], 3.0 * 1.4826, 1e-4);
  EXPECT_FLOAT_EQ(change_from_rest({101.0f}, scale)[0], 0.0f);
  EXPECT_GT(change_from_rest({130.0f}, scale)[0], 0.8 * scale.max_change);
}

TEST(RestScale, ALiveScaleOfQuietNoiseTopsAtTenNoiseBandsAndNeverFalls) {
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 10;
  stream.channels = {"a"};
  stream.samples = SampleMatrix::Zero(200, 1);
  for (int k = 0; k < 200; ++k) stream.samples(k, 0) = 100.0f + static_cast<float>(k % 3 - 1);
  const MemorySampleSource source(stream, "strip:1", "r");
  const RestScale quiet = live_rest_scale(source, {0}, 0.0);
  EXPECT_NEAR(quiet.max_change, kQuietTopBands * quiet.noise_band[0], 1e-4);
  // A noise sample just beyond the band stays near the bottom of the scale.
  EXPECT_LT(change_from_rest({100.0f + quiet.noise_band[0] + 1.0f}, quiet)[0],
            0.1 * quiet.max_change);
  EXPECT_DOUBLE_EQ(live_rest_scale(source, {0}, 500.0).max_change, 500.0);
}

TEST(RestScale, FlatRecordingKeepsAPositiveScale) {
  Stream stream;
  stream.rate_hz = 10;
  stream.samples = SampleMatrix::Constant(10, 1, 7.0f);
  EXPECT_GT(rest_scale(stream, {0}).max_change, 0.0);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// A touch from 5 s to 6 s on one of two channels: the edges near 5.5 s are where it starts
// and ends, to a column's width; a quiet stretch has none.
// Ten seconds of two channels at 100 Hz, at rest at 0 with a noise band of 1.
Stream two_quiet_channels() {
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.channels = {"a", "b"};
  stream.samples = SampleMatrix::Zero(1000, 2);
  return stream;
}
const RestScale kQuiet{{0.0f, 0.0f}, {1.0f, 1.0f}};

TEST(ActivityEdges, AreWhereSomeChannelLeavesAndReentersItsNoiseBand) {
  Stream stream = two_quiet_channels();
  for (int row = 500; row < 600; ++row) stream.samples(row, 1) = 10.0f;
  const MemorySampleSource source(stream, "strip:2", "r");
  const RestScale& scale = kQuiet;
  const std::vector<double> edges = activity_edges(source, {0, 1}, scale, 5.5, 1.0);
  ASSERT_EQ(edges.size(), 2u);
  EXPECT_NEAR(edges[0], 5.0, 2.0 / 24);
  EXPECT_NEAR(edges[1], 6.0, 2.0 / 24);
  EXPECT_TRUE(activity_edges(source, {0, 1}, scale, 8.0, 1.0).empty());
  EXPECT_TRUE(activity_edges(source, {0, -1}, scale, 5.5, 1.0).empty());  // the moving one absent
}

TEST(PeakChangeTime, IsWhereTheChannelsDifferMostFromRest) {
  Stream stream = two_quiet_channels();
  stream.samples(520, 0) = 3.0f;
  stream.samples(540, 1) = -5.0f;  // the larger change, on the other channel
  const MemorySampleSource source(stream, "strip:2", "r");
  const RestScale& scale = kQuiet;
  EXPECT_DOUBLE_EQ(peak_change_time(source, {0, 1}, scale, 5.0, 6.0, 20000), 5.4);
  EXPECT_DOUBLE_EQ(peak_change_time(source, {0, -1}, scale, 5.0, 6.0, 20000), 5.2);
  EXPECT_DOUBLE_EQ(peak_change_time(source, {0, 1}, scale, 5.0, 6.0, 30), 5.2);  // read no further
}

}  // namespace
}  // namespace tactile

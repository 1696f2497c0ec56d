// Segmenter "adaptive": no calibration, each channel's own noise band.
#include <gtest/gtest.h>

#include <random>

#include "tactile/error.h"
#include "tactile/segment/segmenter.h"

namespace tactile {
namespace {

TEST(AdaptiveSegmenter, FindsTouchesOnAnUncalibratedGridWithChannelsOfDifferentNoise) {
  // grid:2x2 at 100 Hz, 20 s; channels at different levels and noise; touches on
  // channel 1 from 3 s to 4 s and on channel 3 from 12 s to 13.5 s.
  Recording recording;
  recording.id = "grid";
  recording.layout_id = "grid:2x2";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.channels = {"ch0", "ch1", "ch2", "ch3"};
  stream.samples.resize(2000, 4);
  std::mt19937 random(5);
  const float level[] = {0.0f, 500.0f, -3.0f, 1e4f};
  const float noise[] = {0.01f, 2.0f, 0.001f, 30.0f};
  for (int t = 0; t < 2000; ++t)
    for (int c = 0; c < 4; ++c) {
      std::normal_distribution<float> gaussian(0.0f, noise[c]);
      float value = level[c] + gaussian(random);
      if (c == 1 && t >= 300 && t < 400) value += 40.0f;   // 20 sigma
      if (c == 3 && t >= 1200 && t < 1350) value -= 600.0f;  // 20 sigma, downwards
      stream.samples(t, c) = value;
    }
  recording.streams = {stream};
  const SkinLayout layout = load_layout("grid:2x2");
  const std::vector<Label> labels = segment_recording("adaptive", recording, layout);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NEAR(labels[0].t0, 3.0, 0.02);
  EXPECT_NEAR(labels[0].t1, 4.0, 0.02);
  EXPECT_NEAR(labels[1].t0, 12.0, 0.02);
  EXPECT_NEAR(labels[1].t1, 13.5, 0.02);
  EXPECT_EQ(labels[0].annotator, "segmenter:adaptive");
  EXPECT_EQ(labels[0].class_name, kUnknownClass);
  EXPECT_THROW(segment_recording("adaptive", recording, layout, Parameters::parse("margin=0", "test")), Error);
}

}  // namespace
}  // namespace tactile

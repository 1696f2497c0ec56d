// Segmenter "adaptive": no calibration, each channel's own noise band.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/segment/segmenter.h"

namespace tactile {
namespace {

TEST(AdaptiveSegmenter, FindsTouchesOnAnUncalibratedGridWithChannelsOfDifferentNoise) {
  // grid:2x2 at 100 Hz, 20 s; channels at different levels and noise (one kind: one scale of
  // presses); touches on channel 1 from 3 s to 4 s and on channel 3 from 12 s to 13.5 s.
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
      if (c == 1 && t >= 300 && t < 400) value += 600.0f;    // 300 sigma
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
  EXPECT_THROW(
      segment_recording("adaptive", recording, layout, Parameters::parse("margin=0", "test")),
      Error);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// A 4 x 4 grid at 20 Hz with an uncalibrated rest per taxel and unit noise; touches press a
// 2 x 2 patch by 60 counts.
struct GridScene {
  static constexpr int kRows = 4;
  static constexpr double kRate = 20.0;
  Eigen::MatrixXf values;

  explicit GridScene(int64_t frames, uint64_t seed = 3) : values(frames, kRows * kRows) {
    std::mt19937 random(static_cast<unsigned>(seed));
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (int c = 0; c < kRows * kRows; ++c)
      for (int64_t t = 0; t < frames; ++t)
        values(t, c) = 100.0f * static_cast<float>(c) + noise(random);
  }
  // Frames [first, last] on the patch whose top-left taxel is (row, column).
  void press(int64_t first, int64_t last, int row = 1, int column = 1, float by = 60.0f) {
    for (int r = row; r < row + 2; ++r)
      for (int k = column; k < column + 2; ++k)
        for (int64_t t = first; t <= last; ++t) values(t, r * kRows + k) += by;
  }
  Recording recording() const {
    Recording recording;
    recording.id = "grid";
    recording.layout_id = "grid:4x4";
    Stream stream;
    stream.name = "skin";
    stream.rate_hz = kRate;
    for (int c = 0; c < kRows * kRows; ++c) stream.channels.push_back("ch" + std::to_string(c));
    stream.samples = values;
    recording.streams = {stream};
    return recording;
  }
  std::vector<Label> segments(const std::string& parameters = "") const {
    return segment_recording("adaptive", recording(), load_layout("grid:4x4"),
                             Parameters::parse(parameters, "test"));
  }
};

TEST(AdaptiveSegmenter, TwoContactsOneFrameApartAreOneTouchUnlessJoinIsZero) {
  GridScene scene(1200);
  scene.press(200, 209);
  scene.press(211, 220);  // frame 210 is the release: a lift inside one gesture
  const std::vector<Label> joined = scene.segments();
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR(joined[0].t0, 200 / GridScene::kRate, 1e-9);
  EXPECT_NEAR(joined[0].t1, 221 / GridScene::kRate, 1e-9);
  // join_seconds=0: every contact is its own touch.
  const std::vector<Label> labels = scene.segments("join_seconds=0");
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NEAR(labels[0].t0, 200 / GridScene::kRate, 1e-9);
  EXPECT_NEAR(labels[0].t1, 210 / GridScene::kRate, 1e-9);
  EXPECT_NEAR(labels[1].t0, 211 / GridScene::kRate, 1e-9);
  EXPECT_NEAR(labels[1].t1, 221 / GridScene::kRate, 1e-9);
}

// From a file read a channel at a time (the workbench's G), the labels of the whole recording
// read into memory; a step that throws (a cancelled job) stops the reading.
TEST(AdaptiveSegmenter, AFileReadAChannelAtATimeGivesTheSameTouches) {
  GridScene scene(1200);
  scene.press(200, 240);
  scene.press(500, 530, 0, 2);
  scene.press(800, 900, 2, 0, 30.0f);
  const testing::TemporaryDirectory folder;
  const std::string path = folder.file("grid.h5");
  write_recording(path, scene.recording());
  FileSourceOptions options;
  options.cache_bytes = 1 << 16;  // less than one channel: nothing held between reads
  const FileSampleSource source(path, options);
  const Parameters none;
  const std::vector<Label> whole =
      segment_recording("adaptive", scene.recording(), load_layout("grid:4x4"));
  std::vector<double> shares;
  const std::vector<Label> read = segment_source("adaptive", source, load_layout("grid:4x4"), none,
                                                 [&](double share) { shares.push_back(share); });
  ASSERT_EQ(whole.size(), 3u);
  ASSERT_EQ(read.size(), whole.size());
  for (size_t k = 0; k < whole.size(); ++k) {
    EXPECT_EQ(read[k].t0, whole[k].t0);
    EXPECT_EQ(read[k].t1, whole[k].t1);
    EXPECT_EQ(read[k].region, whole[k].region);
    EXPECT_EQ(read[k].note, whole[k].note);
    EXPECT_EQ(read[k].annotator, "segmenter:adaptive");
    EXPECT_EQ(read[k].recording, "grid");
  }
  ASSERT_FALSE(shares.empty());
  EXPECT_TRUE(std::is_sorted(shares.begin(), shares.end()));
  EXPECT_DOUBLE_EQ(shares.back(), 1.0);
  EXPECT_THROW(segment_source("adaptive", source, load_layout("grid:4x4"), none,
                              [](double share) {
                                if (share > 0.3) throw Error("job", "cancelled");
                              }),
               Error);
  EXPECT_THROW(segment_source("no-such-method", source, load_layout("grid:4x4")), Error);
}

TEST(AdaptiveSegmenter, ABurstOfFiveTapsGivesFiveSegments) {
  GridScene scene(1200);
  for (int tap = 0; tap < 5; ++tap) scene.press(400 + 6 * tap, 403 + 6 * tap, 0, 2);
  EXPECT_EQ(scene.segments().size(), 5u);
}

TEST(AdaptiveSegmenter, AStuckTaxelMakesNoTouch) {
  GridScene scene(1200);
  scene.press(100, 115);
  // Taxel 6 sticks far above its rest from frame 300 to the end: 45 s.
  scene.values.col(6).tail(900).setConstant(scene.values(300, 6) + 80.0f);
  // A dead taxel reads 0 throughout.
  scene.values.col(9).setZero();
  const std::vector<Label> labels = scene.segments();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0].t0, 100 / GridScene::kRate, 1e-9);
}

TEST(AdaptiveSegmenter, DriftOfTheRestMakesNoTouch) {
  GridScene scene(2400);
  // Every taxel's rest wanders by up to 40 counts over two minutes, each its own way.
  for (int c = 0; c < 16; ++c)
    for (int64_t t = 0; t < 2400; ++t)
      scene.values(t, c) += (c % 2 ? 40.0f : -40.0f) * static_cast<float>(t) / 2400.0f;
  for (int touch = 0; touch < 4; ++touch) scene.press(300 + 500 * touch, 315 + 500 * touch);
  EXPECT_EQ(scene.segments().size(), 4u);
}

TEST(AdaptiveSegmenter, ATaxelStuckUnderADriftingOffsetMakesNoTouch) {
  GridScene scene(1200);
  scene.press(600, 615);
  // Taxel 5 is stuck, but an offset that drifts is laid over it: it changes every frame,
  // smoothly, without noise of its own (0.01 counts where the others have 1).
  for (int64_t t = 0; t < 1200; ++t)
    scene.values(t, 5) = 900.0f + 0.05f * static_cast<float>(t) + 0.01f * static_cast<float>(t % 3);
  const std::vector<Label> labels = scene.segments();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0].t0, 600 / GridScene::kRate, 1e-9);
}

TEST(AdaptiveSegmenter, DriftThatBendsNearTheEndsMakesNoTouchThere) {
  GridScene scene(1600);
  // Every taxel's rest swings by 30 counts (30 noise sigmas) on a wave about as long as the
  // recording, each with its own phase, so it is steep or bending where the recording starts
  // and ends; touches press in the middle, on one patch only (the other taxels never move but
  // for the drift).
  for (int c = 0; c < 16; ++c)
    for (int64_t t = 0; t < 1600; ++t)
      scene.values(t, c) +=
          30.0f * static_cast<float>(std::sin(2.0 * 3.14159265 * static_cast<double>(t) / 1400.0 +
                                              0.4 * static_cast<double>(c)));
  for (int touch = 0; touch < 4; ++touch) scene.press(500 + 150 * touch, 515 + 150 * touch);
  const std::vector<Label> labels = scene.segments();
  ASSERT_EQ(labels.size(), 4u);
  for (int touch = 0; touch < 4; ++touch)
    EXPECT_NEAR(labels[static_cast<size_t>(touch)].t0, (500 + 150 * touch) / GridScene::kRate,
                0.11);
  // A rest that is a running quantile over 20 s (opening_seconds=0) lags behind the drift
  // near the ends and finds touches there.
  EXPECT_GT(scene.segments("opening_seconds=0").size(), 4u);
}

TEST(AdaptiveSegmenter, AHandRestingBetweenTouchesIsNoTouch) {
  GridScene scene(2400);
  for (int touch = 0; touch < 6; ++touch)
    scene.press(200 + 300 * touch, 215 + 300 * touch, touch % 3, 1);
  // A hand rests on 12 taxels for 6 s between two touches: 8 noise sigmas, past each
  // taxel's noise band but less than a seventh of a touch's press; rising and falling over a
  // second.
  for (int64_t t = 560; t < 680; ++t) {
    const float envelope =
        std::min({1.0f, static_cast<float>(t - 560) / 20.0f, static_cast<float>(680 - t) / 20.0f});
    for (int c = 0; c < 12; ++c) scene.values(t, c) += 8.0f * envelope;
  }
  EXPECT_EQ(scene.segments().size(), 6u);
  // Without the touch amplitude's share (share=0) the resting hand makes touches of its own.
  EXPECT_GT(scene.segments("share=0,opening_seconds=0").size(), 6u);
}

}  // namespace
}  // namespace tactile

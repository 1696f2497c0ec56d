// Proximity segmenter (spec §1.1, §1.9) on hand-built NAO recordings at 250 Hz.
#include <gtest/gtest.h>

#include <cmath>

#include "nao_test_recording.h"
#include "tactile/error.h"
#include "tactile/segment/proximity.h"

namespace tactile {
namespace {

using testing::set_range;

constexpr double kSample = 1.0 / 250.0;

struct Fixture {
  SkinLayout layout = load_layout("nao");
  Recording recording = testing::nao_recording(layout, 1000);  // 4 s
};

std::vector<Label> segment(const Fixture& fixture, const Parameters& parameters = {}) {
  return segment_proximity(fixture.recording, fixture.layout, parameters);
}

TEST(ProximitySegmenter, OneTouchIsItsContactSpanPaddedByATenthOfASecond) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 5, "prox", 250, 500, 20.0f);  // 1.0 s to 2.0 s
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0].t0, 0.9, 1e-9);
  EXPECT_NEAR(labels[0].t1, 2.1, 1e-9);  // last contact sample 499 at 1.996 s, + 1 sample + 0.1 s
  EXPECT_EQ(labels[0].region, "front");
  EXPECT_EQ(labels[0].class_name, "");
  EXPECT_EQ(labels[0].recording, "r");
  EXPECT_EQ(labels[0].source, LabelSource::kSegmenter);
  EXPECT_EQ(labels[0].annotator, "segmenter:proximity");
}

TEST(ProximitySegmenter, FiftyMillimetresIsNotContact) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 5, "prox", 250, 500, 50.0f);
  EXPECT_TRUE(segment(fixture).empty());
  Parameters wider;
  wider.set("threshold_mm", "60");
  EXPECT_EQ(segment(fixture, wider).size(), 1u);
}

TEST(ProximitySegmenter, MergesShortGapsAndSplitsLongOnes) {
  Fixture fixture;
  // Taps of a pat on two cells of the back: 0.1 s apart merge into one action ...
  set_range(fixture.recording, fixture.layout, 20, "prox", 100, 150, 15.0f);
  set_range(fixture.recording, fixture.layout, 21, "prox", 175, 225, 15.0f);
  // ... and 0.4 s later a new one starts.
  set_range(fixture.recording, fixture.layout, 20, "prox", 325, 400, 15.0f);
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NEAR(labels[0].t0, 100 * kSample - 0.1, 1e-9);
  EXPECT_NEAR(labels[0].t1, 225 * kSample + 0.1, 1e-9);
  EXPECT_NEAR(labels[1].t0, 325 * kSample - 0.1, 1e-9);
  EXPECT_EQ(labels[0].region, "back");
  // With no merging the taps are two actions.
  Parameters separate;
  separate.set("merge_gap_s", "0");
  EXPECT_EQ(segment(fixture, separate).size(), 3u);
}

TEST(ProximitySegmenter, MultiTouchGivesOverlappingLabelsPerBodyPart) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 3, "prox", 300, 600, 10.0f);
  set_range(fixture.recording, fixture.layout, 30, "prox", 350, 700, 10.0f);
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].region, "front");
  EXPECT_EQ(labels[1].region, "back");
  EXPECT_LT(labels[1].t0, labels[0].t1);  // they overlap in time
  EXPECT_NEAR(labels[1].t1, 700 * kSample + 0.1, 1e-9);
}

TEST(ProximitySegmenter, DropsBlipsShorterThanTheMinimumDuration) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 7, "prox", 100, 110, 30.0f);  // 0.04 s
  set_range(fixture.recording, fixture.layout, 7, "prox", 500, 513, 30.0f);  // 0.052 s
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0].t0, 500 * kSample - 0.1, 1e-9);
  Parameters strict;
  strict.set("min_duration_s", "0.1");
  EXPECT_TRUE(segment(fixture, strict).empty());
}

TEST(ProximitySegmenter, PaddingIsClippedToTheRecording) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 1, "prox", 0, 50, 5.0f);
  set_range(fixture.recording, fixture.layout, 17, "prox", 980, 1000, 5.0f);
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].t0, 0.0);
  EXPECT_NEAR(labels[1].t1, 4.0, 1e-9);
}

TEST(ProximitySegmenter, NonFiniteReadingIsNoContact) {
  Fixture fixture;
  set_range(fixture.recording, fixture.layout, 5, "prox", 250, 500, 20.0f);
  // A gap of missing readings in the middle of the touch longer than the merge gap splits it.
  set_range(fixture.recording, fixture.layout, 5, "prox", 300, 400, NAN);
  const std::vector<Label> labels = segment(fixture);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NEAR(labels[0].t1, 300 * kSample + 0.1, 1e-9);
  EXPECT_NEAR(labels[1].t0, 400 * kSample - 0.1, 1e-9);
}

TEST(ProximitySegmenter, BadParametersNameTheKey) {
  Fixture fixture;
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"pad_s", "-0.1"},
                                                        {"threshold_mm", "0"},
                                                        {"merge_gap_s", "soon"},
                                                        {"threshold", "50"}}) {
    Parameters parameters;
    parameters.set(key, value);
    try {
      segment(fixture, parameters);
      FAIL() << key;
    } catch (const Error& error) {
      EXPECT_NE(error.message().find(key), std::string::npos) << error.what();
    }
  }
}

TEST(ProximitySegmenter, LayoutWithoutProximityIsAnError) {
  const SkinLayout grid = make_grid_layout(2, 2);
  Recording recording;
  recording.id = "g";
  EXPECT_THROW(segment_proximity(recording, grid, {}), Error);
  Fixture fixture;
  fixture.recording.streams[0].channels[6] = "other";  // c01.prox
  EXPECT_THROW(segment(fixture), Error);
}

}  // namespace
}  // namespace tactile

// Scores of a segmentation against ground truth (segment/scoring.h).
#include <gtest/gtest.h>

#include "tactile/segment/scoring.h"

namespace tactile {
namespace {

Label span(double t0, double t1) {
  Label label;
  label.t0 = t0;
  label.t1 = t1;
  return label;
}

TEST(SegmentScoring, ASegmentSpanningTwoTouchesIsOneHitAndOneMiss) {
  const DetectionScore score = score_events({span(1.0, 4.0)}, {span(1.0, 2.0), span(2.5, 4.0)});
  EXPECT_EQ(score.hits, 1);
  EXPECT_EQ(score.misses, 1);
  EXPECT_EQ(score.false_alarms, 0);
  EXPECT_DOUBLE_EQ(score.f1(), 2.0 / 3.0);
}

TEST(SegmentScoring, ATouchSplitInTwoIsOneHitAndOneFalseAlarm) {
  const DetectionScore score = score_events({span(1.0, 1.4), span(1.6, 3.0)}, {span(1.0, 3.0)});
  EXPECT_EQ(score.hits, 1);
  EXPECT_EQ(score.false_alarms, 1);
  EXPECT_EQ(score.misses, 0);
}

TEST(SegmentScoring, EachTouchTakesTheSegmentItOverlapsMost) {
  // The long segment overlaps both touches; the short one only the second: both match.
  const DetectionScore score =
      score_events({span(0.0, 3.0), span(2.9, 4.0)}, {span(0.0, 2.0), span(2.8, 4.0)});
  EXPECT_EQ(score.hits, 2);
  EXPECT_EQ(score.false_alarms, 0);
  EXPECT_EQ(score.misses, 0);
  // Touching ends do not overlap; a minimum IoU leaves small overlaps unmatched.
  EXPECT_EQ(score_events({span(2.0, 3.0)}, {span(1.0, 2.0)}).hits, 0);
  EXPECT_EQ(score_events({span(1.9, 3.0)}, {span(1.0, 2.0)}, 0.5).hits, 0);
}

TEST(SegmentScoring, FramesCountFromTheLabelsTimes) {
  // 10 Hz, 20 frames from t = 1 s: truth holds frames 5..9, the segment frames 8..11.
  const DetectionScore score = score_frames({span(1.8, 2.2)}, {span(1.5, 2.0)}, 1.0, 10.0, 20);
  EXPECT_EQ(score.hits, 2);
  EXPECT_EQ(score.false_alarms, 2);
  EXPECT_EQ(score.misses, 3);
  EXPECT_DOUBLE_EQ(score.precision(), 0.5);
  EXPECT_DOUBLE_EQ(score.recall(), 0.4);
  // Nothing to find and nothing found is perfect.
  EXPECT_DOUBLE_EQ(score_frames({}, {}, 0.0, 10.0, 20).f1(), 1.0);
  DetectionScore total = score;
  total += score;
  EXPECT_EQ(total.misses, 6);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// shared/data/inflatable-grid-dev/README.md: each labelled touch in time order takes the
// unused segment that overlaps it most; splits and merges are counted.
TEST(SegmentScoring, TouchesTakeTheirSegmentsInTimeOrder) {
  // Touch A [0, 2) overlaps segment X [1, 5) by 1; touch B [2, 5) overlaps X by 3. A comes first
  // and takes X (largest-IoU-first would give X to B and leave A missed): B is missed instead.
  const TouchScore score =
      score_touches({span(1.0, 5.0)}, {span(0.0, 2.0), span(2.0, 5.0)}, 0.0, 1.0, 6);
  EXPECT_EQ(score.events.hits, 1);
  EXPECT_EQ(score.events.misses, 1);
  EXPECT_EQ(score.events.false_alarms, 0);
  EXPECT_EQ(score.merged, 2);
  EXPECT_EQ(score.split, 0);
  // Frames 0..5: the segment holds 1-4, the touches 0-4: 4 hits, 1 miss.
  EXPECT_EQ(score.frames.hits, 4);
  EXPECT_EQ(score.frames.misses, 1);
  EXPECT_EQ(score.frames.false_alarms, 0);
}

TEST(SegmentScoring, ATouchCutInThreeIsSplitWithTwoFalseAlarms) {
  const TouchScore score = score_touches({span(0.0, 1.0), span(1.5, 2.0), span(2.5, 4.0)},
                                         {span(0.0, 4.0)}, 0.0, 2.0, 10);
  EXPECT_EQ(score.events.hits, 1);
  EXPECT_EQ(score.events.false_alarms, 2);
  EXPECT_EQ(score.split, 1);
  EXPECT_EQ(score.merged, 0);
  EXPECT_NEAR(score.events.f1(), 2.0 / 4.0, 1e-12);
  EXPECT_EQ(score.touches, 1);
  EXPECT_EQ(score.segments, 3);
}

TEST(SegmentScoring, NothingToFindAndNothingFoundScoresOne) {
  const TouchScore score = score_touches({}, {}, 0.0, 10.0, 100);
  EXPECT_DOUBLE_EQ(score.events.f1(), 1.0);
  EXPECT_DOUBLE_EQ(score.frames.f1(), 1.0);
}

}  // namespace
}  // namespace tactile

// Lanes of labels: grouping into tiers, time lookups, and per-pixel spans whose
// number is bounded by the pixel columns however many labels a lane holds.
#include <gtest/gtest.h>

#include "tactile/labels/lanes.h"

namespace tactile {
namespace {

Label make(double t0, double t1, LabelSource source, const std::string& annotator, int64_t id = 0,
           const std::string& class_name = "pat") {
  Label label;
  label.id = id;
  label.t0 = t0;
  label.t1 = t1;
  label.source = source;
  label.annotator = annotator;
  label.class_name = class_name;
  return label;
}

TEST(Lanes, LabelsGroupByTierInAStableOrder) {
  const Lanes lanes = group_into_lanes(
      {make(0, 1, LabelSource::kSegmenter, "segmenter:threshold"),
       make(0, 1, LabelSource::kManual, "zoe"), make(0, 1, LabelSource::kGroundTruth, "simulator"),
       make(2, 3, LabelSource::kManual, "ana"), make(4, 5, LabelSource::kManual, "ana"),
       make(0, 1, LabelSource::kModel, "svm")});
  std::vector<std::string> titles;
  for (const LaneKey& key : lanes.keys) titles.push_back(key.title());
  EXPECT_EQ(titles,
            (std::vector<std::string>{"ground truth", "ana", "zoe", "threshold", "model svm"}));
  EXPECT_EQ(lanes.lanes[1].size(), 2u);
  EXPECT_EQ(lanes.find({LabelSource::kManual, "zoe"}), 2);
  EXPECT_EQ(lanes.find({LabelSource::kManual, "nobody"}), -1);
  EXPECT_EQ(lanes.keys[0].id(), "ground-truth");
  EXPECT_EQ(lanes.keys[1].id(), "manual:ana");
}

TEST(LaneIndex, FindsWhatMeetsARangeIncludingALongEarlierLabel) {
  // A long label from 0 to 10 and short ones inside and after it.
  const LaneIndex lane(
      {make(0, 10, LabelSource::kManual, "a", 1), make(1, 2, LabelSource::kManual, "a", 2),
       make(3, 4, LabelSource::kManual, "a", 3), make(11, 12, LabelSource::kManual, "a", 4)});
  auto ids = [&](double t0, double t1) {
    std::vector<int64_t> found;
    for (size_t k : lane.meeting(t0, t1)) found.push_back(lane.labels()[k].id);
    return found;
  };
  EXPECT_EQ(ids(5, 6), (std::vector<int64_t>{1}));
  EXPECT_EQ(ids(1.5, 3.5), (std::vector<int64_t>{1, 2, 3}));
  EXPECT_EQ(ids(10, 11), (std::vector<int64_t>{}));  // [t0, t1) ends are exclusive
  EXPECT_EQ(ids(9, 11.5), (std::vector<int64_t>{1, 4}));
  EXPECT_EQ(lane.labels()[static_cast<size_t>(lane.at(3.5))].id, 3);
  EXPECT_EQ(lane.labels()[static_cast<size_t>(lane.at(5))].id, 1);
  EXPECT_EQ(lane.at(10.5), -1);
  EXPECT_EQ(lane.labels()[static_cast<size_t>(lane.next_after(1))].id, 3);
  EXPECT_EQ(lane.labels()[static_cast<size_t>(lane.previous_before(3))].id, 2);
  EXPECT_EQ(lane.next_after(11), -1);
  EXPECT_EQ(lane.previous_before(0), -1);
  EXPECT_EQ(lane.labels()[static_cast<size_t>(lane.any_meeting(5, 6))].id, 1);
}

TEST(LaneSpans, SparseLabelsAreOneSpanEachAtTheirColumns) {
  const LaneIndex lane(
      {make(1, 2, LabelSource::kManual, "a", 1), make(5, 7, LabelSource::kManual, "a", 2)});
  const auto spans = lane_spans(lane, 0, 10, 100);
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_EQ(spans[0].first, 10);
  EXPECT_EQ(spans[0].last, 20);
  EXPECT_EQ(spans[1].first, 50);
  EXPECT_EQ(spans[1].last, 70);
}

TEST(LaneSpans, ADenseLaneCostsItsColumnsNotItsLabels) {
  std::vector<Label> labels;
  for (int k = 0; k < 100000; ++k)
    labels.push_back(make(k * 0.1, k * 0.1 + 0.05, LabelSource::kManual, "a", k + 1));
  const LaneIndex lane(std::move(labels));
  const auto spans = lane_spans(lane, 0, 10000, 800);
  EXPECT_LE(spans.size(), 800u);
  EXPECT_GE(spans.size(), 700u);  // every column is covered by some label
  // Zoomed in to 10 labels: one span each.
  EXPECT_EQ(lane_spans(lane, 100, 101, 800).size(), 10u);
}

}  // namespace
}  // namespace tactile

#include "tactile/labels/region.h"

namespace tactile {
namespace {

TEST(LabelRegion, ASelectionIsAllAGroupOrItsTaxels) {
  const SkinLayout layout = load_layout("grid:3x3");
  ASSERT_FALSE(layout.groups.empty());
  const Group& group = layout.groups.front();
  EXPECT_EQ(region_of_taxels(layout, {}), "all");
  std::vector<int64_t> every;
  for (const Taxel& taxel : layout.taxels) every.push_back(taxel.id);
  EXPECT_EQ(region_of_taxels(layout, every), "all");
  EXPECT_EQ(region_of_taxels(layout, group.taxels), group.id);
  EXPECT_EQ(region_of_taxels(layout, {5, 3, 5}), "taxels:3,5");
  EXPECT_EQ(taxels_of_region(layout, "taxels:3,5"), (std::vector<int64_t>{3, 5}));
  EXPECT_EQ(taxels_of_region(layout, group.id).size(), group.taxels.size());
  EXPECT_EQ(taxels_of_region(layout, "all").size(), layout.taxels.size());
  EXPECT_TRUE(taxels_of_region(layout, "taxels:3,x").empty());
  EXPECT_TRUE(taxels_of_region(layout, "nowhere").empty());
}

}  // namespace
}  // namespace tactile

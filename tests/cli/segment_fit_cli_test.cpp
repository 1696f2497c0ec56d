// `tactile segment --fit-to LANE`, `--preset NAME` and `--score LANE` end to end: a strip of
// binary sensors whose operator labels double taps as one touch; the fit learns it from the
// labelled touches, prints its held-out score, saves the preset and segments with it; the
// labels are never changed; too few touches and labels outside the recording are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "touch_scenes.h"

namespace tactile {
namespace {

using test::run_program;

using test::double_tap_recording;

Label pair_label(const std::string& recording, int pair, const std::string& annotator) {
  return test::double_tap_touches(recording, pair + 1, annotator).back();
}

class SegmentFitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* id : {"a", "b"})
      write_recording(folder.file(std::string(id) + ".h5"), double_tap_recording(id, 8));
    LabelStore store(folder.file("labels.db"));
    for (int pair = 0; pair < 4; ++pair) store.add(pair_label("a", pair, "ana"));
    for (int pair = 0; pair < 3; ++pair) store.add(pair_label("b", pair, "ana"));
  }
  test::CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder);
  }
  std::vector<Label> lane(const std::string& annotator) {
    LabelStore store(folder.file("labels.db"));
    LabelFilter filter;
    filter.annotator = annotator;
    return store.list(filter);
  }
  std::string recordings() { return folder.file("a.h5") + " " + folder.file("b.h5"); }
  test::TempFolder folder{"tactile-segment-fit"};
};

TEST_F(SegmentFitCli, FitsToTheLabelledTouchesSavesAPresetAndSegmentsWithIt) {
  const std::vector<Label> before = lane("ana");
  // Adaptive's defaults cut each double tap in two.
  const auto plain = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                             " --method adaptive --score manual:ana");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("32 segments from 2 recordings"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("7 touches split"), std::string::npos) << plain.out;

  const auto fit = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                           " --fit-to ana --preset taps --replace");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("fitted adaptive to 7 labelled touches"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("held out, by recording (2 folds): frame F1 1.000"), std::string::npos)
      << fit.out;
  EXPECT_NE(fit.out.find("event F1 1.000 (7 of 7 touches found, 0 false alarms"), std::string::npos)
      << fit.out;
  EXPECT_NE(fit.out.find("saved as preset 'taps'"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("16 segments from 2 recordings"), std::string::npos) << fit.out;
  EXPECT_EQ(lane("segmenter:adaptive").size(), 16u);
  EXPECT_TRUE(std::filesystem::exists(folder.file("segmenter-presets.json")));

  // The preset again, scored against the operator's lane on the labelled stretch and beyond.
  const auto again = tactile("segment " + folder.file("a.h5") + " --labels " +
                             folder.file("labels.db") + " --preset taps --replace --score ana");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("a: 8 segments (adaptive)"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("event F1 0.667 (4 of 4 touches found, 4 false alarms; 8 segments), "
                           "0 touches split, 0 merged"),
            std::string::npos)
      << again.out;

  // Fitting never changes a label of the lane it read.
  const std::vector<Label> after = lane("ana");
  ASSERT_EQ(after.size(), before.size());
  for (size_t k = 0; k < after.size(); ++k) {
    EXPECT_EQ(after[k].id, before[k].id);
    EXPECT_EQ(after[k].t0, before[k].t0);
    EXPECT_EQ(after[k].t1, before[k].t1);
    EXPECT_EQ(after[k].revision, before[k].revision);
  }
}

TEST_F(SegmentFitCli, RefusesTooFewTouchesLabelsOutsideTheRecordingAndUnknownPresets) {
  {
    LabelStore store(folder.file("labels.db"));
    store.add(pair_label("a", 0, "bo"));
    store.add(pair_label("a", 1, "bo"));
  }
  const auto few =
      tactile("segment " + recordings() + " --labels " + folder.file("labels.db") + " --fit-to bo");
  EXPECT_EQ(few.exit_code, 1);
  EXPECT_NE(few.err.find("needs at least three labelled touches, has 2"), std::string::npos)
      << few.err;
  {
    LabelStore store(folder.file("labels.db"));
    Label late = pair_label("a", 2, "bo");
    late.t0 = 40.0;
    late.t1 = 41.0;  // a.h5 lasts 34 s
    store.add(late);
  }
  const auto outside =
      tactile("segment " + recordings() + " --labels " + folder.file("labels.db") + " --fit-to bo");
  EXPECT_EQ(outside.exit_code, 1);
  EXPECT_NE(
      outside.err.find("a: label 40.000-41.000 s lies outside the recording (0.000-34.000 s)"),
      std::string::npos)
      << outside.err;
  EXPECT_EQ(lane("segmenter:adaptive").size(), 0u) << "nothing is segmented after a refusal";
  EXPECT_FALSE(std::filesystem::exists(folder.file("segmenter-presets.json")));

  const auto empty_lane = tactile("segment " + recordings() + " --labels " +
                                  folder.file("labels.db") + " --method adaptive --score nobody");
  EXPECT_EQ(empty_lane.exit_code, 1);
  EXPECT_NE(empty_lane.err.find("--score nobody: no labels in this lane"), std::string::npos)
      << empty_lane.err;
  EXPECT_NE(empty_lane.err.find("manual:ana"), std::string::npos) << empty_lane.err;
  EXPECT_EQ(lane("segmenter:adaptive").size(), 0u) << "nothing is stored after a refusal";
  const auto unknown = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                               " --preset nope");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("--preset nope: no such preset"), std::string::npos) << unknown.err;
  // A damaged presets file is named, and a fit does not overwrite it.
  { std::ofstream(folder.file("segmenter-presets.json")) << "{\"taps\": {\"method\": "; }
  const auto damaged = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                               " --preset taps");
  EXPECT_EQ(damaged.exit_code, 1);
  EXPECT_NE(damaged.err.find("segmenter-presets.json: damaged segmenter presets"),
            std::string::npos)
      << damaged.err;
  const auto over = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                            " --fit-to ana");
  EXPECT_EQ(over.exit_code, 1);
  EXPECT_EQ(test::read_text(folder.file("segmenter-presets.json")), "{\"taps\": {\"method\": ");
  const auto other = tactile("segment " + recordings() + " --labels " + folder.file("labels.db") +
                             " --fit-to ana --method threshold");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_NE(other.err.find("fits the adaptive segmenter's parameters, not threshold"),
            std::string::npos)
      << other.err;
}

}  // namespace
}  // namespace tactile

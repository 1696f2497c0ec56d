// Labels > Fit segmenter to my labels, through the workbench's real input path: an operator
// labels three double taps with the keys ([ ] 1 Enter), fits, presses G, and the suggestions
// follow the way they label (one per double tap, where adaptive's defaults give two), and
// the Quality tab scores them against the operator's touches; the operator's labels are
// unchanged; with two labels the fit is refused with what is needed.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "touch_scenes.h"

namespace tactile {
namespace {

class WorkbenchSegmentFit : public ::testing::Test {
 protected:
  void SetUp() override {
    // Eight double taps on sensor 3 of strip:8, 4 s apart (touch_scenes.h).
    const Recording recording = test::double_tap_recording("taps", 8);
    write_recording(folder.file("taps.h5"), recording);
    LabelStore store(folder.file("labels.db"));
    store.set_classes("strip:8", {"double-tap", "stroke"});
  }
  // The keys that label double tap `pair` (2 + 4 pair s to 3.1 + 4 pair s) as class 1.
  static std::string label_pair(int pair) {
    const double t0 = 2.0 + 4.0 * pair, t1 = t0 + 1.1;
    return "time " + std::to_string(t0) + "\nkey [\ntime " + std::to_string(t1) +
           "\nkey ]\nkey 1\nkey Enter\nwait 1\n";
  }
  test::CommandResult workbench(const std::string& script_text) {
    return test::run_program("tactile-workbench-headless",
                             folder.file("taps.h5") + " --labels " + folder.file("labels.db") +
                                 " --annotator ana --size 1200x760 --settings " +
                                 folder.file("settings.json") + " --script " +
                                 test::write_script(folder, script_text),
                             folder);
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }
  std::vector<Label> lane(const std::string& annotator) {
    LabelStore store(folder.file("labels.db"));
    LabelFilter filter;
    filter.annotator = annotator;
    return store.list(filter);
  }
  test::TempFolder folder{"tactile-workbench-fit"};
};

TEST_F(WorkbenchSegmentFit, FittedToThreeLabelledTouchesGSuggestsTheWayTheOperatorLabels) {
  const auto result = workbench(
      "wait 2\nkey G\nwait jobs\nstate @default.json\n" + label_pair(0) + label_pair(1) +
      label_pair(2) + "menu Labels/Fit segmenter to my labels\nwait jobs\nstate @fitted.json\n" +
      "key G\nwait jobs\nstate @suggested.json\nclick item tab:quality\nwait 2\n"
      "state @quality.json\nscreenshot @quality.png\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(state("default.json")["segmenter"]["method"], "adaptive");
  const std::vector<Label> mine = lane("ana");
  ASSERT_EQ(mine.size(), 3u);
  for (size_t k = 0; k < mine.size(); ++k) {
    EXPECT_NEAR(mine[k].t0, 2.0 + 4.0 * static_cast<double>(k), 1e-3);
    EXPECT_EQ(mine[k].class_name, "double-tap");
  }
  const nlohmann::json fitted = state("fitted.json");
  EXPECT_EQ(fitted["error"], "");
  const std::string notice = fitted["notice"];
  EXPECT_NE(notice.find("segmenter fitted to 3 touches"), std::string::npos) << notice;
  EXPECT_NE(notice.find("held out by time blocks (3 folds): event F1 1.00"), std::string::npos)
      << notice;
  EXPECT_EQ(fitted["segmenter"]["method"], "adaptive");
  const std::string params = fitted["segmenter"]["params"];
  EXPECT_NE(params.find("join_seconds="), std::string::npos) << params;
  // G with the fitted parameters: one suggestion per double tap, 8 in all; those over the
  // operator's three touches match them.
  const std::vector<Label> suggestions = lane("segmenter:adaptive");
  ASSERT_EQ(suggestions.size(), 8u) << params;
  for (size_t k = 0; k < suggestions.size(); ++k) {
    EXPECT_NEAR(suggestions[k].t0, 2.0 + 4.0 * static_cast<double>(k), 1e-6) << params;
    EXPECT_NEAR(suggestions[k].t1, 3.1 + 4.0 * static_cast<double>(k), 1e-6) << params;
  }
  // Fitting changed none of the operator's labels.
  const std::vector<Label> after = lane("ana");
  ASSERT_EQ(after.size(), mine.size());
  for (size_t k = 0; k < after.size(); ++k) EXPECT_EQ(after[k].revision, mine[k].revision);
  EXPECT_TRUE(std::filesystem::exists(folder.file("segmenter-presets.json")));
  // The Quality tab scores the suggestions (lane B) against the operator's touches (lane A):
  // each of the three found whole, the five beyond them false alarms, none split or merged.
  const nlohmann::json quality = state("quality.json")["quality"];
  EXPECT_EQ(quality["touches"], 3);
  EXPECT_EQ(quality["touches_found"], 3);
  EXPECT_EQ(quality["touch_false_alarms"], 5);
  EXPECT_EQ(quality["touches_split"], 0);
  EXPECT_EQ(quality["touches_merged"], 0);
  EXPECT_NEAR(quality["touch_event_f1"].get<double>(), 6.0 / 11.0, 1e-9);
}

TEST_F(WorkbenchSegmentFit, FewerThanThreeLabelledTouchesAreRefusedWithWhatIsNeeded) {
  const auto result =
      workbench("wait 2\n" + label_pair(0) + label_pair(1) +
                "menu Labels/Fit segmenter to my labels\nwait jobs\nstate @refused.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string error = state("refused.json")["error"];
  EXPECT_NE(error.find("Fit needs at least three touches labelled in your lane (ana); it has 2"),
            std::string::npos)
      << error;
  EXPECT_EQ(lane("ana").size(), 2u);
}

}  // namespace
}  // namespace tactile

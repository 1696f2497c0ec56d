// Labelling in the workbench, driven by scripts through ImGui's real input path and
// checked in the label database: keys make a label, undo and redo across restarts,
// Tab walks and Delete removes, a label over selected taxels records that region,
// marks made while playing are moved back by the reaction time, and a label
// committed just before the process is killed is in the database.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli_test_support.h"
#include "test_paths.h"

extern char** environ;

namespace tactile {
namespace {

class WorkbenchLabelling : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto made = test::run_program(
        "tactile",
        "simulate --skin fur --subjects 1 --repetitions 1 --seed 3 --out " + folder.file("ws"),
        folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const auto classes =
        test::run_program("tactile", "labels classes " + database() + " fur", folder);
    ASSERT_EQ(classes.exit_code, 0) << classes.err;
    std::istringstream lines(classes.out);
    for (std::string line; std::getline(lines, line);) vocabulary.push_back(line);
    ASSERT_GE(vocabulary.size(), 3u);
  }
  std::string recording() const { return folder.file("ws/fur-s01-t01.h5"); }
  std::string database() const { return folder.file("ws/labels.db"); }
  std::string script(const std::string& text) { return test::write_script(folder, text); }
  std::string arguments(const std::string& script_path) const {
    return recording() + " --annotator ana --size 1200x760 --settings " +
           folder.file("settings.json") + " --script " + script_path;
  }
  test::CommandResult workbench(const std::string& script_text) {
    return test::run_program("tactile-workbench-headless", arguments(script(script_text)), folder);
  }
  // The manual labels in the database, as `tactile labels list --json` gives them.
  nlohmann::json manual_labels() {
    const auto listed = test::run_program(
        "tactile", "labels list " + database() + " --source manual --json", folder);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    return nlohmann::json::parse(listed.out)["labels"];
  }
  // Every label in the database, ids and times aside, in a fixed order.
  nlohmann::json all_labels() {
    const auto listed =
        test::run_program("tactile", "labels list " + database() + " --json", folder);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    nlohmann::json labels = nlohmann::json::parse(listed.out)["labels"];
    for (nlohmann::json& label : labels)
      for (const char* field : {"id", "created", "modified"}) label.erase(field);
    std::sort(labels.begin(), labels.end(),
              [](const nlohmann::json& a, const nlohmann::json& b) { return a.dump() < b.dump(); });
    return labels;
  }
  // One command, run by `command` (a script), undone by Ctrl+Z in a new process and redone by
  // Ctrl+Shift+Z: the whole label table is as before the command, then as after it, and the
  // store's check finds no overlap.
  void expect_one_undo(const std::string& command) {
    const nlohmann::json before = all_labels();
    const auto done = workbench(command + "state @done.json\n");
    ASSERT_EQ(done.exit_code, 0) << done.err;
    ASSERT_EQ(state("done.json")["error"], "") << command;
    const nlohmann::json after = all_labels();
    ASSERT_NE(after, before) << "the command changed nothing: " << command;
    ASSERT_EQ(workbench("wait 2\nkey Ctrl+Z\nwait 1\nstate @undone.json\n").exit_code, 0);
    EXPECT_TRUE(state("undone.json")["notice"].get<std::string>().starts_with("undone: "))
        << state("undone.json")["notice"];
    EXPECT_EQ(all_labels(), before) << command;
    const auto check = test::run_program("tactile", "labels check " + database(), folder);
    EXPECT_EQ(check.out.find("overlap"), std::string::npos) << check.out;
    ASSERT_EQ(workbench("wait 2\nkey Ctrl+Shift+Z\nwait 1\n").exit_code, 0);
    EXPECT_EQ(all_labels(), after) << command;
  }
  // The middle of the first suggestion of a segmenter's lane in the database.
  double first_suggestion(const std::string& method) {
    const auto listed = test::run_program(
        "tactile", "labels list " + database() + " --source segmenter --json", folder);
    const nlohmann::json labels = nlohmann::json::parse(listed.out)["labels"];
    for (const nlohmann::json& label : labels)
      if (label["annotator"] == "segmenter:" + method)
        return 0.5 * (label["t0"].get<double>() + label["t1"].get<double>());
    ADD_FAILURE() << "no suggestion of " << method;
    return 0.0;
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  test::TempFolder folder{"tactile-workbench-labelling"};
  std::vector<std::string> vocabulary;
};

TEST_F(WorkbenchLabelling, KeysMakeALabelThatIsInTheDatabaseAtOnce) {
  const auto result = workbench(
      "wait 2\ntime 3\nkey [\ntime 4.5\nkey ]\nkey 2\nstate @marked.json\nkey Enter\n"
      "wait 1\nstate @made.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json marked = state("marked.json");
  EXPECT_DOUBLE_EQ(marked["marks"]["start"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(marked["marks"]["end"].get<double>(), 4.5);
  EXPECT_EQ(marked["marks"]["class"], vocabulary[1]);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["class"], vocabulary[1]);
  EXPECT_DOUBLE_EQ(labels[0]["t0"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(labels[0]["t1"].get<double>(), 4.5);
  EXPECT_EQ(labels[0]["annotator"], "ana");
  EXPECT_EQ(labels[0]["region"], "all");
  const nlohmann::json made = state("made.json");
  EXPECT_TRUE(made["marks"]["start"].is_null());
  EXPECT_EQ(made["selection"]["labels"][0], labels[0]["id"]);
}

TEST_F(WorkbenchLabelling, UndoAndRedoWorkAcrossRestarts) {
  ASSERT_EQ(workbench("wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 1\nkey Enter\nwait 1\n").exit_code,
            0);
  ASSERT_EQ(manual_labels().size(), 1u);
  // A new process: the journal in the database knows what to undo.
  ASSERT_EQ(workbench("wait 2\nkey Ctrl+Z\nwait 1\nstate @undone.json\n").exit_code, 0);
  EXPECT_EQ(manual_labels().size(), 0u);
  EXPECT_TRUE(state("undone.json")["notice"].get<std::string>().starts_with("undone: "))
      << state("undone.json")["notice"];
  ASSERT_EQ(workbench("wait 2\nkey Ctrl+Shift+Z\nwait 1\n").exit_code, 0);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["class"], vocabulary[0]);
}

TEST_F(WorkbenchLabelling, TabWalksTheOwnLaneAndDeleteRemoves) {
  const auto result = workbench(
      "wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 1\nkey Enter\ntime 5\nkey [\ntime 6\nkey ]\n"
      "key 3\nkey Enter\ntime 0\nkey Escape\nkey Tab\nstate @first.json\nkey Tab\n"
      "state @second.json\nkey Shift+Tab\nkey Delete\nwait 1\nstate @deleted.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_DOUBLE_EQ(state("first.json")["time"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(state("second.json")["time"].get<double>(), 5.0);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);  // the first was removed
  EXPECT_DOUBLE_EQ(labels[0]["t0"].get<double>(), 5.0);
  EXPECT_EQ(labels[0]["class"], vocabulary[2]);
}

TEST_F(WorkbenchLabelling, ALabelOverSelectedTaxelsRecordsThatRegion) {
  const auto result = workbench(
      "wait 2\nclick taxel 10\nwait 1\ntime 7\nkey [\ntime 8\nkey ]\nkey 1\n"
      "key Enter\nwait 1\nstate @region.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["region"], "taxels:10");
}

TEST_F(WorkbenchLabelling, LanesShowEachTierAndAClickInOneSelectsItsLabel) {
  const auto result = workbench(
      "wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 1\nkey Enter\nwait 1\n"
      "click time 5 in lane:ground-truth\nstate @clicked.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json clicked = state("clicked.json");
  ASSERT_EQ(clicked["lanes"].size(), 2u);
  EXPECT_EQ(clicked["lanes"][0]["id"], "ground-truth");
  EXPECT_EQ(clicked["lanes"][1]["id"], "manual:ana");
  EXPECT_EQ(clicked["lanes"][1]["labels"], 1);
  // The simulator's first touch runs from 2.2 s to 7.6 s: label 1.
  EXPECT_EQ(clicked["selection"]["labels"], nlohmann::json::array({1}));
}

TEST_F(WorkbenchLabelling, SuggestionsAreAcceptedAndRejectedAndARerunLeavesTheRejectedOut) {
  const auto result = workbench(
      "wait 2\nmenu Labels/Run segmenter/threshold\nwait jobs\nstate @suggested.json\n"
      "key 2\nkey A\nwait 1\nstate @accepted.json\nkey R\nwait 1\nstate @rejected.json\n"
      "menu Labels/Run segmenter/threshold\nwait jobs\nstate @rerun.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  auto lane_size = [](const nlohmann::json& state, const std::string& id) {
    for (const auto& lane : state["lanes"])
      if (lane["id"] == id) return lane["labels"].get<int>();
    return 0;
  };
  const std::string lane = "segmenter:threshold";
  const nlohmann::json suggested = state("suggested.json");
  const int suggestions = lane_size(suggested, lane);
  ASSERT_GE(suggestions, 3) << suggested.dump(2);
  EXPECT_EQ(suggested["selection"]["labels"].size(), 1u);
  const double first = suggested["time"].get<double>();
  // A: the first suggestion, with class 2, in ana's lane; the cursor moves on.
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["class"], vocabulary[1]);
  EXPECT_DOUBLE_EQ(labels[0]["t0"].get<double>(), first);
  const double second = state("accepted.json")["time"].get<double>();
  EXPECT_GT(second, first);
  // R: the second is gone, and stays gone when the segmenter runs again.
  EXPECT_EQ(lane_size(state("rejected.json"), lane), suggestions - 1);
  EXPECT_EQ(lane_size(state("rerun.json"), lane), suggestions - 1);
  EXPECT_NE(state("rerun.json")["notice"].get<std::string>().find("(1 rejected before)"),
            std::string::npos);
}

// G, accept one suggestion and reject the next, G again, Ctrl+Z: the database is as it was
// before the second run (a run was two journal batches, and undo left both runs stacked).
TEST_F(WorkbenchLabelling, CtrlZAfterASegmenterRerunRestoresTheLabelsBeforeIt) {
  ASSERT_EQ(workbench("wait 2\nkey G\nwait jobs\nkey 6\nkey A\nwait 1\nkey R\nwait 1\n").exit_code,
            0);
  const nlohmann::json before = all_labels();
  ASSERT_GE(before.size(), 3u);
  const auto result = workbench(
      "wait 2\nkey G\nwait jobs\nstate @rerun.json\nkey Ctrl+Z\nwait 1\nstate @undone.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(state("rerun.json")["notice"].get<std::string>().find("(1 rejected before)"),
            std::string::npos);
  EXPECT_TRUE(state("undone.json")["notice"].get<std::string>().starts_with("undone: "))
      << state("undone.json")["notice"];
  EXPECT_EQ(all_labels(), before);
  const auto check = test::run_program("tactile", "labels check " + database(), folder);
  EXPECT_EQ(check.out.find("overlap"), std::string::npos) << check.out;
}

// An operator's label, G, Ctrl+Z: the run goes and the label stays (undo took the label).
TEST_F(WorkbenchLabelling, CtrlZAfterASegmenterRunTakesBackTheRunNotTheLabelBeforeIt) {
  const auto result = workbench(
      "wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 2\nkey Enter\nwait 1\nstate @labelled.json\n"
      "key G\nwait jobs\nstate @run.json\nkey Ctrl+Z\nwait 1\nstate @undone.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // Lane id -> labels, for the lanes that hold any.
  auto lanes = [](const nlohmann::json& state) {
    std::map<std::string, int> sizes;
    for (const auto& lane : state["lanes"])
      if (lane["labels"].get<int>() > 0) sizes[lane["id"]] = lane["labels"].get<int>();
    return sizes;
  };
  const std::map<std::string, int> labelled = lanes(state("labelled.json"));
  EXPECT_GT(lanes(state("run.json")).size(), labelled.size());
  EXPECT_EQ(lanes(state("undone.json")), labelled);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["class"], vocabulary[1]);
}

// One of every command kind of the labelling keys, each undone exactly (after a restart) and
// redone.
constexpr const char* kCommitOne =
    "wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 2\nkey Enter\nwait 1\n";

TEST_F(WorkbenchLabelling, CommittingALabelUndoesAsOneCommand) { expect_one_undo(kCommitOne); }

TEST_F(WorkbenchLabelling, AClassChangeUndoesAsOneCommand) {
  ASSERT_EQ(workbench(kCommitOne).exit_code, 0);
  expect_one_undo("wait 2\ntime 0\nkey Tab\nkey 3\nkey Enter\nwait 1\n");
  EXPECT_EQ(manual_labels()[0]["class"], vocabulary[2]);  // redone
}

TEST_F(WorkbenchLabelling, ADeleteUndoesAsOneCommand) {
  ASSERT_EQ(workbench(kCommitOne).exit_code, 0);
  expect_one_undo("wait 2\ntime 0\nkey Tab\nkey Delete\nwait 1\n");
  EXPECT_EQ(manual_labels().size(), 0u);
}

TEST_F(WorkbenchLabelling, ADraggedEdgeUndoesAsOneCommand) {
  ASSERT_EQ(
      workbench("wait 2\nkey S\ndrag time 13 15 in timeline\nkey 1\nkey Enter\nwait 1\n").exit_code,
      0);
  expect_one_undo("wait 2\nkey S\ndrag time 15 17 in timeline\nwait 2\n");
}

TEST_F(WorkbenchLabelling, AnAcceptedSuggestionUndoesAsOneCommand) {
  ASSERT_EQ(workbench("wait 2\nkey G\nwait jobs\n").exit_code, 0);
  const double t = first_suggestion("threshold");
  expect_one_undo("wait 2\nclick time " + std::to_string(t) +
                  " in lane:segmenter:threshold\nkey 2\nkey A\nwait 1\n");
  EXPECT_EQ(manual_labels().size(), 1u);
}

// A reject's undo also forgets the rejection: a rerun of the segmenter suggests it again.
TEST_F(WorkbenchLabelling, ARejectedSuggestionUndoesAsOneCommandAndComesBackInARerun) {
  ASSERT_EQ(workbench("wait 2\nkey G\nwait jobs\nstate @first.json\n").exit_code, 0);
  const double t = first_suggestion("threshold");
  expect_one_undo("wait 2\nclick time " + std::to_string(t) +
                  " in lane:segmenter:threshold\nkey R\nwait 1\n");
  // Redone: rejected again. Undone once more, then a rerun: nothing left out.
  ASSERT_EQ(
      workbench("wait 2\nkey Ctrl+Z\nwait 1\nkey G\nwait jobs\nstate @rerun.json\n").exit_code, 0);
  EXPECT_EQ(state("rerun.json")["notice"].get<std::string>().find("rejected before"),
            std::string::npos)
      << state("rerun.json")["notice"];
  EXPECT_EQ(state("rerun.json")["notice"], state("first.json")["notice"]);
}

// The run is a job: applied frames after G, while the window went on drawing.
TEST_F(WorkbenchLabelling, ASegmenterRunUndoesAsOneCommand) {
  expect_one_undo("wait 2\nkey G\nwait jobs\n");
  const nlohmann::json job = state("done.json")["jobs"].back();
  EXPECT_EQ(job["name"], "segmenter threshold");
  EXPECT_EQ(job["status"], "done");
  EXPECT_GT(job["finished_frame"].get<int>(), job["started_frame"].get<int>());
}

TEST_F(WorkbenchLabelling, TheQualityViewListsIssuesAndAgreementAndAClickGoesThere) {
  // Two overlapping labels in ana's lane: an issue. Ground truth against ana: agreement.
  const auto result = workbench(
      "wait 2\ntime 10\nkey [\ntime 12\nkey ]\nkey 1\nkey Enter\ntime 11\nkey [\ntime 12.5\n"
      "key ]\nkey 1\nkey Enter\ntime 0\nclick item tab:quality\nwait 2\nclick item "
      "quality:issue:0\n"
      "wait 1\nstate @quality.json\nscreenshot @quality.png\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json quality = state("quality.json");
  EXPECT_DOUBLE_EQ(quality["time"].get<double>(), 11.0);  // the later of the overlapping two
  EXPECT_GT(quality["quality"]["disagreements"].get<int>(), 0);
  EXPECT_GE(quality["quality"]["f1"].get<double>(), 0.0);
}

TEST_F(WorkbenchLabelling, DraggingInTheOwnLaneMarksAndDraggingAnEdgeMovesIt) {
  // Snapping off (S): the ground truth's boundaries would otherwise catch the drags.
  const auto result = workbench(
      "wait 2\nkey S\ndrag time 13 15 in timeline\nstate @dragged.json\nkey 1\nkey Enter\n"
      "wait 1\ndrag time 15 17 in timeline\nwait 2\nstate @moved.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json dragged = state("dragged.json");
  const double pixel = 31.4 / dragged["views"]["signals"]["width"].get<double>();
  EXPECT_NEAR(dragged["marks"]["start"].get<double>(), 13.0, 2 * pixel);
  EXPECT_NEAR(dragged["marks"]["end"].get<double>(), 15.0, 2 * pixel);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0]["t0"].get<double>(), 13.0, 2 * pixel);
  EXPECT_NEAR(labels[0]["t1"].get<double>(), 17.0, 2 * pixel);  // the end edge, dragged
}

TEST_F(WorkbenchLabelling, DraggedTimesSnapToTheBoundariesOfOtherLanes) {
  // A drag released a few pixels short of the simulator's first touch's end ends there.
  const auto truth = nlohmann::json::parse(
      test::run_program("tactile", "labels list " + database() + " --source ground-truth --json",
                        folder)
          .out)["labels"];
  const double end = truth[0]["t1"].get<double>();
  const auto result = workbench("wait 2\ndrag time " + std::to_string(end - 2.5) + " " +
                                std::to_string(end - 0.08) + " in timeline\nstate @snapped.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_DOUBLE_EQ(state("snapped.json")["marks"]["end"].get<double>(),
                   truth[0]["t1"].get<double>());
}

TEST_F(WorkbenchLabelling, TheTypeAheadPickerAndTheRegionMenuNeedNoTaxelClicks) {
  const std::string last = vocabulary.back();  // any class, by typing part of it
  const auto result = workbench(
      "wait 2\nclick item region\nwait 2\nclick item region:middle\nwait 1\ntime 20\nkey [\n"
      "time 21\nkey ]\nkey C\nwait 2\ntype " +
      last.substr(1, 3) +
      "\nkey Enter\nwait 1\n"
      "state @picked.json\nkey Enter\nwait 1\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(state("picked.json")["marks"]["class"], last);
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["class"], last);
  EXPECT_EQ(labels[0]["region"], "middle");
}

TEST_F(WorkbenchLabelling, ARectangleDraggedOverTheSkinSelectsTheRegionOfTheNextLabel) {
  // Taxels 0, 1 and 2 are the first three of the fur's top row.
  const auto result = workbench(
      "wait 2\ndrag taxel 0 2\nwait 1\nstate @rectangle.json\ntime 20\nkey [\ntime 21\nkey ]\n"
      "key 1\nkey Enter\nwait 1\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(state("rectangle.json")["selection"]["taxels"], nlohmann::json::array({0, 1, 2}));
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0]["region"], "taxels:0,1,2");
}

TEST_F(WorkbenchLabelling, MarksMadeWhilePlayingAreMovedBackByTheReactionTime) {
  const auto result = workbench("wait 2\ntime 2\nkey Space\nwait 20\nkey [\nstate @playing.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json playing = state("playing.json");
  ASSERT_TRUE(playing["playing"].get<bool>());
  const double mark = playing["marks"]["start"].get<double>();
  const double now = playing["time"].get<double>();
  // The mark was made a frame or two before the state was written, 0.25 s back.
  EXPECT_LT(mark, now - 0.25 + 1e-9);
  EXPECT_GT(mark, now - 0.25 - 0.2);
}

TEST_F(WorkbenchLabelling, ALabelCommittedJustBeforeAKillIsInTheDatabase) {
  const std::string script_path =
      script("wait 2\ntime 3\nkey [\ntime 4\nkey ]\nkey 1\nkey Enter\nsleep 60\n");
  const std::string program = tactile::test::bin_dir() + "/tactile-workbench-headless";
  const std::string command = program + " " + arguments(script_path) + " >/dev/null 2>&1";
  pid_t child = 0;
  const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
  // exec, so that the pid is the workbench's own and SIGKILL reaches it.
  const std::string exec_command = "exec " + command;
  argv[2] = exec_command.c_str();
  ASSERT_EQ(posix_spawn(&child, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  // Wait until the label is committed (the script sleeps after it), then kill -9.
  bool found = false;
  for (int attempt = 0; attempt < 200 && !found; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto listed = test::run_program(
        "tactile", "labels list " + database() + " --source manual --json", folder);
    found = listed.exit_code == 0 && !nlohmann::json::parse(listed.out)["labels"].empty();
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(found) << "the label never reached the database";
  EXPECT_TRUE(WIFSIGNALED(status)) << "the workbench had ended before the kill";
  const nlohmann::json labels = manual_labels();
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_DOUBLE_EQ(labels[0]["t0"].get<double>(), 3.0);
  const auto verified = test::run_program("tactile", "verify " + database(), folder);
  EXPECT_EQ(verified.exit_code, 0) << verified.out;
}

}  // namespace
}  // namespace tactile

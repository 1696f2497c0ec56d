// Two writers of one label store with a workbench among them, through the real UI path: the
// labels another process commits (another annotator's LabelStore, `tactile segment --labels`)
// appear in the open workbench without reopening, the status line naming who did what; and an
// undo of a label another annotator changed since is refused naming the label and them, the
// other's change kept.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli_test_support.h"
#include "tactile/labels/commands.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

extern char** environ;

namespace tactile {
namespace {

class WorkbenchWriters : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto made = test::run_program(
        "tactile",
        "simulate --skin fur --subjects 1 --repetitions 1 --seed 3 --out " + folder.file("ws"),
        folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
    LabelStore store(database(), LabelStore::OpenMode::kExisting);
    const std::vector<Label> labels = store.list();
    ASSERT_FALSE(labels.empty());
    recording_id = labels.front().recording;
    class_name = labels.front().class_name;
  }
  std::string recording() const { return folder.file("ws/fur-s01-t01.h5"); }
  std::string database() const { return folder.file("ws/labels.db"); }
  std::string arguments(const std::string& script_text) const {
    return recording() + " --annotator ana --size 1200x760 --settings " +
           folder.file("settings.json") + " --script " + test::write_script(folder, script_text);
  }
  int64_t shown_labels() const {
    LabelStore store(database(), LabelStore::OpenMode::kExisting);
    return store.count(recording_id);
  }
  nlohmann::json state(const std::string& name) const {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }
  // Starts the workbench on `script_text`, runs `other_writer` once the script has written
  // `ready` (a state file), and returns the workbench's exit code.
  int run_alongside(const std::string& script_text, const std::string& ready,
                    const std::function<void()>& other_writer) {
    const std::string command = "exec " + tactile::test::bin_dir() +
                                "/tactile-workbench-headless " + arguments(script_text) + " >" +
                                folder.file("wb.out") + " 2>&1";
    const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
    pid_t child = 0;
    if (posix_spawn(&child, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) != 0)
      return -1;
    bool started = false;
    for (int attempt = 0; attempt < 1200 && !started; ++attempt) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      started = std::filesystem::exists(folder.file(ready));
    }
    if (started) other_writer();
    if (!started) kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    if (!started) ADD_FAILURE() << "the workbench never wrote " << ready;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  Label bobs_label(double t0, double t1) const {
    Label label;
    label.recording = recording_id;
    label.t0 = t0;
    label.t1 = t1;
    label.class_name = class_name;
    label.annotator = "bob";
    return label;
  }

  test::TempFolder folder{"tactile-workbench-writers"};
  std::string recording_id, class_name;
};

TEST_F(WorkbenchWriters, AnotherAnnotatorsLabelsAppearWithoutReopeningAndAreNamed) {
  const int64_t before = shown_labels();
  const std::string script = "wait 2\nstate @before.json\nwait labels " +
                             std::to_string(before + 2) + "\nwait 1\nstate @after.json\n";
  const int code = run_alongside(script, "before.json", [&] {
    LabelStore bob(database(), LabelStore::OpenMode::kExisting);
    LabelEdit edit;
    edit.add = {bobs_label(1.0, 1.5), bobs_label(2.0, 2.5)};
    bob.apply(edit, "bob");
  });
  ASSERT_EQ(code, 0) << test::read_text(folder.file("wb.out"));
  EXPECT_EQ(state("before.json")["labels"], before);
  const nlohmann::json after = state("after.json");
  EXPECT_EQ(after["labels"], before + 2);
  EXPECT_EQ(after["notice"], "bob added 2 labels");
  EXPECT_EQ(after["error"], "");
}

TEST_F(WorkbenchWriters, ASegmenterRunOfTheCommandLineAppearsInTheOpenWorkbench) {
  // The same run on a copy first, to know how many suggestions it stores.
  const std::string copy = folder.file("ws/copy.db");
  std::filesystem::copy_file(database(), copy);
  const std::string segment = "segment " + recording() + " --labels ";
  ASSERT_EQ(test::run_program("tactile", segment + copy, folder).exit_code, 0);
  int64_t expected = 0;
  {
    LabelStore store(copy, LabelStore::OpenMode::kExisting);
    expected = store.count(recording_id);
  }
  ASSERT_GT(expected, shown_labels());
  const std::string script = "wait 2\nstate @before.json\nwait labels " + std::to_string(expected) +
                             "\nwait 1\nstate @after.json\n";
  const int code = run_alongside(script, "before.json", [&] {
    const auto run = test::run_program("tactile", segment + database(), folder);
    EXPECT_EQ(run.exit_code, 0) << run.err;
  });
  ASSERT_EQ(code, 0) << test::read_text(folder.file("wb.out"));
  const nlohmann::json after = state("after.json");
  EXPECT_EQ(after["labels"], expected);
  EXPECT_NE(after["notice"].get<std::string>().find("segmenter:"), std::string::npos)
      << after["notice"];
  EXPECT_NE(after["notice"].get<std::string>().find(" added "), std::string::npos)
      << after["notice"];
}

TEST_F(WorkbenchWriters, AnUndoOfALabelAnotherAnnotatorChangedIsRefusedNamingThem) {
  const auto made = test::run_program(
      "tactile-workbench-headless",
      arguments("wait 2\ntime 1\nkey [\ntime 2\nkey ]\nkey 1\nkey Enter\nwait 1\n"), folder);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  Label changed;
  {
    LabelStore bob(database(), LabelStore::OpenMode::kExisting);
    LabelFilter anas;
    anas.annotator = "ana";
    const std::vector<Label> labels = bob.list(anas);
    ASSERT_EQ(labels.size(), 1u);
    bob.apply(bounds_edit(labels[0], 0.5, 2.5), "bob");
    changed = *bob.get(labels[0].id);
  }
  const auto undone =
      test::run_program("tactile-workbench-headless",
                        arguments("wait 2\nkey Ctrl+Z\nwait 1\nstate @undo.json\n"), folder);
  ASSERT_EQ(undone.exit_code, 0) << undone.err;
  const std::string error = state("undo.json")["error"];
  EXPECT_NE(error.find("label " + std::to_string(changed.id) + " ("), std::string::npos) << error;
  EXPECT_NE(error.find("0.50-2.50 s) was changed by bob meanwhile"), std::string::npos) << error;
  EXPECT_NE(error.find("nothing was undone"), std::string::npos) << error;
  // Bob's change stands, and the store verifies.
  LabelStore store(database(), LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.get(changed.id)->t0, 0.5);
  EXPECT_EQ(store.get(changed.id)->revision, changed.revision);
  EXPECT_EQ(test::run_program("tactile", "verify " + database(), folder).exit_code, 0);
}

}  // namespace
}  // namespace tactile

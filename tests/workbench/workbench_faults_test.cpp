// The workbench when the world fails it (issue 27): a recording whose disk stops answering or
// fails its reads (injected through `fault read`, where a dying disk would fail) keeps a frame
// under a second, shows what it holds and says why, and reads again when the disk is back; a
// recording in a read-only folder is viewed, labels are refused before anything is written
// there, and another store (the user's own) takes them.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"

namespace tactile {
namespace {

class WorkbenchFaults : public ::testing::Test {
 protected:
  // grid:2x2, 80 s at 1 kHz: many chunks, so a new time reads the file.
  void make_recording(const std::string& folder_path) {
    std::ofstream csv(folder.file("long.csv"));
    csv << "t,ch0,ch1,ch2,ch3\n";
    for (int k = 0; k < 80000; ++k)
      csv << k / 1000.0 << "," << k % 97 << ",1,2," << (k / 1000) % 7 << "\n";
    csv.close();
    const auto imported =
        test::run_program("tactile",
                          "import " + folder.file("long.csv") +
                              " --layout grid:2x2 --rate 1000 --out " + folder_path + "/long.h5",
                          folder);
    ASSERT_EQ(imported.exit_code, 0) << imported.err;
  }
  test::CommandResult run(const std::string& arguments, const std::string& environment = "") {
    return test::run_program("tactile-workbench-headless",
                             arguments + " --settings " + folder.file("settings.json"), folder,
                             environment);
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }
  test::TempFolder folder{"tactile-workbench-faults"};
};

TEST_F(WorkbenchFaults, ADiskThatHangsOrFailsIsSaidAndTheWindowDrawsOnUntilTheFileReturns) {
  make_recording(folder.path().string());
  const std::string script =
      test::write_script(folder,
                         "time 1\nwait 3\n"
                         "fault read hang\ntime 40\nwait 4\ntime 60\nwait 4\nstate @hang.json\n"
                         "fault read off\nsleep 1.3\ntime 40\nwait 4\nstate @back.json\n"
                         "fault read fail\ntime 20\nwait 4\nstate @fail.json\n"
                         "fault read off\nsleep 1.3\nwait 3\nstate @again.json\n");
  const auto result = run(folder.file("long.h5") + " --size 900x600 --script " + script);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json hang = state("hang.json");
  EXPECT_NE(hang["unavailable"].get<std::string>().find("does not answer"), std::string::npos)
      << hang["unavailable"];
  EXPECT_EQ(state("back.json")["unavailable"], "");
  const nlohmann::json fail = state("fail.json");
  EXPECT_NE(fail["unavailable"].get<std::string>().find("Input/output error"), std::string::npos)
      << fail["unavailable"];
  const nlohmann::json again = state("again.json");
  EXPECT_EQ(again["unavailable"], "");
  // The window drew on through the hung and the failing disk: frames counted, not timed (the
  // longest frame during a fault is bench/file_faults_bench.sh's figure, docs/BENCHMARKS.md).
  EXPECT_GE(state("back.json")["frame"].get<int64_t>() - hang["frame"].get<int64_t>(), 4);
  EXPECT_GE(again["frame"].get<int64_t>() - fail["frame"].get<int64_t>(), 3);
}

// A folder this process cannot write: a read-only tmpfs for root (who writes anywhere else),
// a folder without write permission for anyone else. Empty when neither can be made.
std::string read_only_folder(const test::TempFolder& folder,
                             const std::function<void(const std::string&)>& fill) {
  const std::string path = folder.file("ro");
  std::filesystem::create_directories(path);
  if (geteuid() == 0) {
    if (::mount("tmpfs", path.c_str(), "tmpfs", 0, "size=8m") != 0) return "";
    fill(path);
    if (::mount("tmpfs", path.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=8m") != 0) {
      ::umount(path.c_str());
      return "";
    }
    return path;
  }
  fill(path);
  std::filesystem::permissions(path, std::filesystem::perms::owner_write,
                               std::filesystem::perm_options::remove);
  return path;
}

TEST_F(WorkbenchFaults, AReadOnlyRecordingIsViewedAndItsLabelsGoToTheUsersOwnStore) {
  // A skin with classes (keys 1-9 label), its simulator's labels.db beside it.
  const std::string ro = read_only_folder(folder, [&](const std::string& path) {
    const auto simulated = test::run_program(
        "tactile",
        "simulate --skin flux --subjects 1 --repetitions 1 --seed 4 --out '" + path + "'", folder);
    ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  });
  if (ro.empty()) GTEST_SKIP() << "cannot make a read-only folder here";
  const std::string script = test::write_script(
      folder,
      "wait 3\nstate @open.json\n"
      "time 3\nkey [\ntime 4\nkey ]\nkey 1\nkey Enter\nwait 3\nstate @refused.json\n"
      "menu Labels/Keep labels in my own store\nwait 3\n"
      "time 3\nkey [\ntime 4\nkey ]\nkey 1\nkey Enter\nwait 3\nstate @kept.json\n");
  const auto result = run(ro + "/flux-s01-t01.h5 --annotator ana --size 900x600 --script " + script,
                          "XDG_DATA_HOME='" + folder.file("data") + "'");
  const auto listed =
      std::distance(std::filesystem::directory_iterator(ro), std::filesystem::directory_iterator());
  if (geteuid() == 0)
    ::umount(ro.c_str());
  else
    std::filesystem::permissions(ro, std::filesystem::perms::owner_write,
                                 std::filesystem::perm_options::add);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(listed, 2);  // nothing was written beside the recording and its labels.db: no -wal
  const nlohmann::json open = state("open.json");
  EXPECT_NE(open["labels_read_only"].get<std::string>().find("read-only"), std::string::npos)
      << open;
  EXPECT_NE(open["notice"].get<std::string>().find("Keep labels in my own store"),
            std::string::npos)
      << open["notice"];
  const nlohmann::json refused = state("refused.json");
  EXPECT_NE(refused["error"].get<std::string>().find("labels cannot be saved here"),
            std::string::npos)
      << refused["error"];
  const int before = open["labels"].get<int>();
  EXPECT_GT(before, 0);  // the read-only store's labels are shown
  EXPECT_EQ(refused["labels"], before);
  const nlohmann::json kept = state("kept.json");
  EXPECT_EQ(kept["labels_read_only"], "");
  EXPECT_EQ(kept["labels"], before + 1);  // its labels came along, and the new one
  EXPECT_EQ(kept["labels_path"].get<std::string>().rfind(
                folder.file("data/tactile-workbench/labels/"), 0),
            0u)
      << kept["labels_path"];
  EXPECT_TRUE(std::filesystem::exists(kept["labels_path"].get<std::string>()));
}

}  // namespace
}  // namespace tactile

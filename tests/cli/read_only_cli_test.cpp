// Opening is read-only, and a command that fails changes nothing: every command below is
// given bad input next to files that already exist, fails, and leaves every one of those
// files byte for byte as it was (issue 13 §3).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"

namespace {

using tactile::test::CommandResult;
using tactile::test::read_text;

class ReadOnly : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(tactile("simulate --skin flux --subjects 1 --repetitions 1 --seed 4 --out '" +
                      file("work") + "'")
                  .exit_code,
              0);
    recording = file("work/flux-s01-t01.h5");
    labels = file("work/labels.db");
    // Files a careless program could overwrite or remove.
    write(file("existing.h5"), read_text(recording));
    write(file("existing.csv"), "time_s,a\n0,1\n");
    write(file("existing.json"), "{\"labels\": []}\n");
    // Damaged inputs.
    const std::string bytes = read_text(recording);
    write(file("truncated.h5"), bytes.substr(0, bytes.size() / 3));
    write(file("ragged.csv"), "time,a,b,c\n0,1,2,3\n0.01,4,5\n");
    write(file("notadb.db"), std::string("SQLite format 3\0 but not really", 31));
    write(file("bad-labels.csv"),
          "id,recording,t0,t1,region,class,annotator,source,confidence,note,created,modified\n"
          "1,flux-s01-t01,2.0,1.0,all,touch1,me,manual,1,,2026-01-01T00:00:00Z,"
          "2026-01-01T00:00:00Z\n");
    snapshot();
  }

  std::string file(const std::string& name) const { return folder.file(name); }
  CommandResult tactile(const std::string& arguments) const {
    return tactile::test::run_program("tactile", arguments, folder);
  }
  static void write(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  // Every file of the folder and its bytes.
  std::map<std::string, std::string> files() const {
    std::map<std::string, std::string> all;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder.path()))
      if (entry.is_regular_file()) all[entry.path().string()] = read_text(entry.path());
    return all;
  }
  void snapshot() { before = files(); }
  // The command fails and no file appeared, vanished or changed.
  void expect_failure_changing_nothing(const std::string& arguments) {
    const CommandResult run = tactile(arguments);
    EXPECT_NE(run.exit_code, 0) << arguments << "\n" << run.out;
    EXPECT_FALSE(run.err.empty()) << arguments;
    const auto after = files();
    for (const auto& [path, bytes] : before) {
      const auto found = after.find(path);
      ASSERT_NE(found, after.end()) << arguments << " removed " << path;
      EXPECT_TRUE(found->second == bytes) << arguments << " changed " << path;
    }
    for (const auto& [path, bytes] : after)
      EXPECT_TRUE(before.count(path)) << arguments << " left " << path;
  }

  tactile::test::TempFolder folder{"tactile-read-only"};
  std::string recording, labels;
  std::map<std::string, std::string> before;
};

TEST_F(ReadOnly, AFailedImportLeavesTheOutputThatWasThere) {
  expect_failure_changing_nothing("import '" + file("ragged.csv") + "' --layout strip:3 --out '" +
                                  file("existing.h5") + "'");
  expect_failure_changing_nothing("import '" + file("truncated.h5") +
                                  "' --dataset /streams/skin/samples --layout flux --rate 1000 "
                                  "--out '" +
                                  file("existing.h5") + "'");
}

TEST_F(ReadOnly, AFailedExportLeavesTheOutputAndTheRecording) {
  expect_failure_changing_nothing("export '" + file("truncated.h5") + "' --csv '" +
                                  file("existing.csv") + "'");
  expect_failure_changing_nothing("export '" + recording + "' --stream nonesuch --csv '" +
                                  file("existing.csv") + "'");
  expect_failure_changing_nothing("labels export '" + file("notadb.db") + "' --json '" +
                                  file("existing.json") + "'");
}

TEST_F(ReadOnly, OpeningADamagedFileNeverChangesIt) {
  expect_failure_changing_nothing("info '" + file("truncated.h5") + "'");
  expect_failure_changing_nothing("verify '" + file("truncated.h5") + "'");
  expect_failure_changing_nothing("upgrade '" + file("truncated.h5") + "'");
  expect_failure_changing_nothing("labels list '" + file("notadb.db") + "'");
}

TEST_F(ReadOnly, AFailedLabelImportLeavesTheStoreAsItWas) {
  expect_failure_changing_nothing("labels import '" + labels + "' '" + file("bad-labels.csv") +
                                  "'");
}

}  // namespace

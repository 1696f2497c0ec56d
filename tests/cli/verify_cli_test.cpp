// `tactile verify` and `tactile upgrade` end to end, and damaged label rows in
// `tactile labels export`.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "test_paths.h"

namespace tactile {
namespace {

class VerifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto made = test::run_program(
        "tactile", "simulate --skin fur --subjects 1 --repetitions 1 --out " + folder.file("ws"),
        folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
    for (const auto& entry : std::filesystem::directory_iterator(folder.file("ws")))
      if (entry.path().extension() == ".h5") recording = entry.path().string();
    ASSERT_FALSE(recording.empty());
  }
  test::CommandResult tactile(const std::string& arguments) {
    return test::run_program("tactile", arguments, folder);
  }
  void flip_byte(const std::string& path, std::streamoff offset) {
    std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
    file.seekg(offset);
    char byte = 0;
    file.get(byte);
    file.seekp(offset);
    file.put(static_cast<char>(byte ^ 0x01));
  }

  test::TempFolder folder{"tactile-verify-cli"};
  std::string recording;
};

TEST_F(VerifyCli, AnIntactWorkspaceVerifiesClean) {
  const auto result = tactile("verify " + folder.file("ws"));
  EXPECT_EQ(result.exit_code, 0) << result.out << result.err;
  EXPECT_EQ(result.out, "");
  EXPECT_NE(result.err.find("verified 1 recording(s) and 1 label store(s): no problems"),
            std::string::npos)
      << result.err;
}

TEST_F(VerifyCli, ADamagedByteIsOneLineNamingTheFileAndThePlace) {
  // Past the metadata, inside the compressed samples of some channel.
  const auto size = std::filesystem::file_size(recording);
  flip_byte(recording, static_cast<std::streamoff>(size / 2));
  const auto result = tactile("verify " + folder.file("ws"));
  EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
  ASSERT_FALSE(result.out.empty());
  EXPECT_EQ(result.out.rfind(recording + ":/streams/skin/", 0), 0u) << result.out;
  const auto json = tactile("verify --json " + recording);
  EXPECT_EQ(json.exit_code, 1);
  const nlohmann::json report = nlohmann::json::parse(json.out);
  EXPECT_FALSE(report["ok"].get<bool>());
  EXPECT_EQ(report["files"][0]["kind"], "recording");
  EXPECT_GE(report["problems"].size(), 1u);
  // Reading it is refused as well, not answered with other numbers.
  const auto exported = tactile("export " + recording + " --csv " + folder.file("out.csv"));
  EXPECT_EQ(exported.exit_code, 1);
  EXPECT_NE(exported.err.find(recording + ":/streams/skin/samples"), std::string::npos)
      << exported.err;
  EXPECT_FALSE(std::filesystem::exists(folder.file("out.csv")));
}

TEST_F(VerifyCli, ADamagedLabelRowIsNamedAndLeftOutOfTheExport) {
  const std::string store = folder.file("ws/labels.db");
  sqlite3* database = nullptr;
  ASSERT_EQ(sqlite3_open(store.c_str(), &database), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(database, "UPDATE labels SET region = 'mildle' WHERE id = 1", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(database);
  const auto verified = tactile("verify " + store);
  EXPECT_EQ(verified.exit_code, 1);
  EXPECT_NE(verified.out.find(store + ": labels row 1 field region: "), std::string::npos)
      << verified.out;
  const auto exported = tactile("labels export " + store + " --json " + folder.file("l.json"));
  EXPECT_EQ(exported.exit_code, 1);
  EXPECT_NE(exported.err.find("labels row 1 field region"), std::string::npos) << exported.err;
  const nlohmann::json labels =
      nlohmann::json::parse(test::read_text(folder.file("l.json")))["labels"];
  ASSERT_FALSE(labels.empty());
  for (const auto& label : labels) EXPECT_NE(label["id"], 1);
}

TEST_F(VerifyCli, UpgradeRewritesFilesOfTheEarlierFormat) {
  const std::string old_recording = folder.file("old.h5");
  const std::string old_store = folder.file("old.db");
  std::filesystem::copy_file(tactile::test::test_data_dir() + "/format_v1/fur-s01-t01.h5",
                             old_recording);
  std::filesystem::copy_file(tactile::test::test_data_dir() + "/format_v1/labels.db", old_store);
  EXPECT_EQ(tactile("verify " + old_recording + " " + old_store).exit_code, 1);
  const auto before = tactile("export " + old_recording + " --csv " + folder.file("before.csv"));
  ASSERT_EQ(before.exit_code, 0) << before.err;
  const auto upgraded = tactile("upgrade " + old_recording + " " + old_store);
  EXPECT_EQ(upgraded.exit_code, 0) << upgraded.err;
  EXPECT_EQ(upgraded.out, old_recording + ": format 1 -> 2\n" + old_store + ": schema 1 -> 4\n");
  const auto verified = tactile("verify " + old_recording + " " + old_store);
  EXPECT_EQ(verified.exit_code, 0) << verified.out;
  const auto after = tactile("export " + old_recording + " --csv " + folder.file("after.csv"));
  ASSERT_EQ(after.exit_code, 0) << after.err;
  EXPECT_EQ(test::read_text(folder.file("before.csv")), test::read_text(folder.file("after.csv")));
  EXPECT_EQ(tactile("upgrade " + old_recording).out, old_recording + ": already format 2\n");
}

TEST_F(VerifyCli, RepairMendsADamagedRecordingNamesWhatWasLostAndKeepsTheOriginal) {
  const auto whole = tactile("repair " + recording);
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.out, recording + ": whole, nothing to repair\n");
  const auto size = std::filesystem::file_size(recording);
  flip_byte(recording, static_cast<std::streamoff>(size / 2));
  const auto repaired = tactile("repair " + recording);
  EXPECT_EQ(repaired.exit_code, 0) << repaired.out << repaired.err;
  EXPECT_EQ(
      repaired.out.rfind(
          recording + ": repaired; the damaged original is kept as " + recording + ".damaged\n", 0),
      0u)
      << repaired.out;
  EXPECT_NE(repaired.out.find("  rebuilt: /streams/skin: the overview and the sample count"),
            std::string::npos)
      << repaired.out;
  EXPECT_NE(repaired.out.find("  lost: /streams/skin channel "), std::string::npos) << repaired.out;
  EXPECT_TRUE(std::filesystem::exists(recording + ".damaged"));
  EXPECT_EQ(tactile("verify " + recording).exit_code, 0);
  // A file that is no recording at all: refused, named, left as it was.
  std::ofstream(folder.file("junk.h5")) << "junk";
  const auto junk = tactile("repair " + folder.file("junk.h5"));
  EXPECT_EQ(junk.exit_code, 1);
  EXPECT_NE(junk.err.find(folder.file("junk.h5") + ": cannot be repaired"), std::string::npos)
      << junk.err;
  EXPECT_EQ(test::read_text(folder.file("junk.h5")), "junk");
}

}  // namespace
}  // namespace tactile

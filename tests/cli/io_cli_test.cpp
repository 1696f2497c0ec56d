// End-to-end tests of `tactile info|import|export`: run the built binary on the tiny
// CSVs of tests/data/io and on files made in a temporary directory.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"
#include "test_paths.h"

namespace {

using tactile::test::CommandResult;
using tactile::test::read_text;

const std::string kData = tactile::test::test_data_dir() + "/io";

class IoCommand : public ::testing::Test {
 protected:
  std::string file(const std::string& name) const { return folder.file(name); }
  tactile::test::CommandResult tactile(const std::string& arguments) const {
    return tactile::test::run_program("tactile", arguments, folder);
  }

  tactile::test::TempFolder folder{"tactile-io-cli"};
};

TEST_F(IoCommand, RaggedCsvFailsNamingFileAndLineAndWritesNothing) {
  const CommandResult run =
      tactile("import '" + kData + "/ragged_strip3.csv' --layout strip:3 --out '" +
              file("ragged.h5") + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("ragged_strip3.csv:4 column 4: row has 3 cells, header has 4"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(std::filesystem::exists(file("ragged.h5")));
}

TEST_F(IoCommand, ImportedRecordingIsDescribedByInfoJson) {
  const std::string h5 = file("session-1.h5");
  const CommandResult imported =
      tactile("import '" + kData + "/long_strip3.csv' --layout strip:3 --out '" + h5 + "'");
  ASSERT_EQ(imported.exit_code, 0) << imported.err;

  const CommandResult info = tactile("info '" + h5 + "' --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json json = nlohmann::json::parse(info.out);
  EXPECT_EQ(json.at("layout"), "strip:3");
  EXPECT_EQ(json.at("recording"), "session-1");  // the output file's stem
  EXPECT_EQ(json.at("metadata").at("imported_from"), "long_strip3.csv");
  EXPECT_TRUE(json.at("labels").is_null());
  ASSERT_EQ(json.at("streams").size(), 1u);
  const nlohmann::json& stream = json.at("streams")[0];
  EXPECT_EQ(stream.at("name"), "skin");
  EXPECT_DOUBLE_EQ(stream.at("rate_hz").get<double>(), 100.0);
  EXPECT_EQ(stream.at("channels").size(), 3u);
  EXPECT_EQ(stream.at("samples"), 4);
  EXPECT_DOUBLE_EQ(stream.at("duration_s").get<double>(), 0.04);

  const CommandResult text = tactile("info '" + h5 + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("labels:    (no database given, and no labels.db beside the recording)"),
            std::string::npos)
      << text.out;
}

TEST_F(IoCommand, InfoCountsTheLabelsInTheDatabaseBesideTheRecording) {
  ASSERT_EQ(tactile("simulate --skin flux --subjects 1 --repetitions 1 --out '" + file("sim") + "'")
                .exit_code,
            0);
  const CommandResult text = tactile("info '" + file("sim/flux-s01-t01.h5") + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("labels:    6 in " + file("sim/labels.db")), std::string::npos)
      << text.out;
  const nlohmann::json json =
      nlohmann::json::parse(tactile("info '" + file("sim/flux-s01-t01.h5") + "' --json").out);
  EXPECT_EQ(json.at("labels"), 6);
  EXPECT_EQ(json.at("labels_database"), file("sim/labels.db"));
}

TEST_F(IoCommand, ExportWritesTheSamplesBack) {
  const std::string h5 = file("rec.h5");
  ASSERT_EQ(tactile("import '" + kData + "/long_strip3.csv' --layout strip:3 --out '" + h5 +
                    "' --recording-id chosen")
                .exit_code,
            0);
  const CommandResult run = tactile("export '" + h5 + "' --csv '" + file("rec.csv") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string csv = read_text(file("rec.csv"));
  // The header names come from the layout; the rows are the fixture's numbers.
  EXPECT_EQ(csv.substr(csv.find('\n') + 1), "0,1,2,3\n0.01,4,5.5,6\n0.02,-7,8,9\n0.03,10,11,12\n");
  EXPECT_EQ(
      tactile("export '" + h5 + "' --csv '" + file("x.csv") + "' --stream pressure").exit_code, 1);
}

TEST_F(IoCommand, WideImportNeedsItsOptions) {
  const CommandResult run =
      tactile("import '" + kData + "/wide_strip2.csv' --layout strip:2 --wide --rate 10 --out '" +
              file("w.h5") + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--samples-per-capture: required with --wide"), std::string::npos)
      << run.err;
  const CommandResult stray = tactile(
      "import '" + kData + "/long_strip3.csv' --layout strip:3 --labels-file x.csv --out '" +
      file("l.h5") + "'");
  EXPECT_EQ(stray.exit_code, 1);
  EXPECT_NE(stray.err.find("--labels-file: only with --wide"), std::string::npos) << stray.err;
}

TEST_F(IoCommand, WideImportMakesOneLabelPerCapture) {
  const std::string h5 = file("wide.h5");
  const CommandResult run =
      tactile("import '" + kData +
              "/wide_strip2.csv' --layout strip:2 --wide --samples-per-capture 3 "
              "--rate 10 --labels-file '" +
              kData + "/wide_strip2_labels.csv' --class-names poke,pat,slap --out '" + h5 + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("9 samples x 2 channels at 10 Hz, 3 labels"), std::string::npos)
      << run.out;
  const nlohmann::json json = nlohmann::json::parse(tactile("info '" + h5 + "' --json").out);
  EXPECT_EQ(json.at("streams")[0].at("samples"), 9);
}

TEST_F(IoCommand, MissingRecordingIsAnError) {
  const CommandResult run = tactile("info '" + file("absent.h5") + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("absent.h5: no such file"), std::string::npos) << run.err;
}

TEST_F(IoCommand, EveryCommandHasHelp) {
  for (const char* command : {"info", "import", "export"}) {
    const CommandResult run = tactile(std::string(command) + " --help");
    EXPECT_EQ(run.exit_code, 0) << command;
    EXPECT_NE(run.out.find("--"), std::string::npos) << command;
  }
  EXPECT_NE(tactile("import --help").out.find("--samples-per-capture"), std::string::npos);
}

}  // namespace

// `tactile experiment` end to end: a quick run's tables and JSON, and an unknown name.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_test_support.h"

namespace tactile::test {
namespace {

TEST(ExperimentCli, QuickFluxSomPrintsTablesAndSimulatesIntoWorkFolder) {
  TempFolder folder;
  const std::string work = folder.file("work");
  const CommandResult text =
      run_program("tactile", "experiment flux-som --quick --seed 2 --work '" + work + "'", folder);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("flux-som"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Fig 8B: SOM class regions"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("ours"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(work + "/flux/labels.db"));

  const CommandResult json = run_program(
      "tactile", "experiment flux-som --quick --seed 2 --json --work '" + work + "'", folder);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json document = nlohmann::json::parse(json.out);
  EXPECT_EQ(document["name"], "flux-som");
  const double accuracy = document["accuracy"].get<double>();
  EXPECT_GT(accuracy, 1.0 / 3.0);  // six classes
  EXPECT_LE(accuracy, 1.0);
  EXPECT_EQ(document["tables"][0]["paper_components"], 8);
}

std::string work_folder_named_in(const std::string& err) {
  const std::string marker = "work folder: ";
  const size_t at = err.find(marker);
  if (at == std::string::npos) return {};
  const std::string line = err.substr(at + marker.size(), err.find('\n', at) - at - marker.size());
  return line.substr(0, line.find(" (removed"));
}

// Without --work a run simulates into a folder of its own under the temp dir, named on
// stderr, and removes it when done (hundreds of MB a run); --keep keeps it.
TEST(ExperimentCli, DefaultWorkFolderIsRemovedWhenDoneUnlessKept) {
  TempFolder folder;
  const CommandResult result =
      run_program("tactile", "experiment tsa-classifiers --quick --json", folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string work = work_folder_named_in(result.err);
  ASSERT_FALSE(work.empty()) << result.err;
  EXPECT_NE(result.err.find("removed when done"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(work)) << work;
  EXPECT_FALSE(nlohmann::json::parse(result.out).contains("work_dir"));

  const CommandResult kept =
      run_program("tactile", "experiment tsa-classifiers --quick --json --keep", folder);
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  const std::string kept_work = work_folder_named_in(kept.err);
  EXPECT_TRUE(std::filesystem::exists(kept_work + "/tsa/labels.db")) << kept_work;
  EXPECT_EQ(nlohmann::json::parse(kept.out)["work_dir"], kept_work);
  std::filesystem::remove_all(kept_work);
}

TEST(ExperimentCli, UnknownNameFailsListingKnownExperiments) {
  TempFolder folder;
  const CommandResult result =
      run_program("tactile", "experiment no-such-thing --work '" + folder.file("w") + "'", folder);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("no-such-thing"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("tsa-classifiers"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("robovie-clafic"), std::string::npos) << result.err;
  EXPECT_TRUE(result.out.empty());
  EXPECT_FALSE(std::filesystem::exists(folder.file("w")));  // nothing created for a bad name
}

}  // namespace
}  // namespace tactile::test

// `tactile experiment` end to end: a quick run's tables and JSON, and an unknown name;
// --repeats R over consecutive seeds and its shards merged by `tactile merge`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

//---- Repeats and shards ---------------------------------------------------------------------
// tsa-classifiers is the quickest experiment with --quick (about 0.5 s a run here; fur-ml
// 0.8 s, flux-som 1.6 s, kaboli-location 4 s, robovie-clafic 6 s).

const char* const kRepeats = "experiment tsa-classifiers --quick --repeats 3 --seed 5";

// What a run prints but the result line naming its --out.
std::string without_result_line(const std::string& out) {
  const size_t at = out.rfind("result      ");
  return at == std::string::npos ? out : out.substr(0, at);
}

TEST(ExperimentCli, RepeatsShardedThenMergedWriteTheOneProcessResult) {
  TempFolder folder;
  const CommandResult one = run_program(
      "tactile", std::string(kRepeats) + " --out '" + folder.file("one.json") + "'", folder);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::string merged = folder.file("merged.json");
  std::vector<std::string> parts;
  for (int shard = 1; shard <= 3; ++shard) {
    const CommandResult part = run_program(
        "tactile",
        std::string(kRepeats) + " --out '" + merged + "' --shard " + std::to_string(shard) + "/3",
        folder);
    ASSERT_EQ(part.exit_code, 0) << part.err;
    EXPECT_NE(part.out.find("1 of 3 items"), std::string::npos) << part.out;
    parts.push_back(merged + ".part-" + std::to_string(shard) + "-of-3");
  }
  EXPECT_FALSE(std::filesystem::exists(merged));  // a shard writes only its part
  // Shard 2 again alone (as after a kill): its part is replaced, the merge is the same.
  ASSERT_EQ(
      run_program("tactile", std::string(kRepeats) + " --out '" + merged + "' --shard 2/3", folder)
          .exit_code,
      0);
  const CommandResult merge = run_program(
      "tactile", "merge '" + parts[2] + "' '" + parts[0] + "' '" + parts[1] + "'", folder);
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  ASSERT_TRUE(std::filesystem::exists(merged));
  EXPECT_EQ(read_text(merged), read_text(folder.file("one.json")));  // byte for byte
  EXPECT_EQ(without_result_line(merge.out), without_result_line(one.out));
  EXPECT_NE(one.out.find("==== seed 7 ===="), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("Summary: headline"), std::string::npos) << one.out;
  EXPECT_NE(merge.out.find("result      " + merged), std::string::npos) << merge.out;
}

TEST(ExperimentCli, RepeatsMergeNamesTheMissingShard) {
  TempFolder folder;
  const std::string merged = folder.file("merged.json");
  ASSERT_EQ(
      run_program("tactile", std::string(kRepeats) + " --out '" + merged + "' --shard 1/3", folder)
          .exit_code,
      0);
  ASSERT_EQ(
      run_program("tactile", std::string(kRepeats) + " --out '" + merged + "' --shard 3/3", folder)
          .exit_code,
      0);
  const CommandResult merge = run_program(
      "tactile", "merge '" + merged + ".part-1-of-3' '" + merged + ".part-3-of-3'", folder);
  EXPECT_NE(merge.exit_code, 0);
  EXPECT_NE(merge.err.find("shard 2/3"), std::string::npos) << merge.err;
  EXPECT_NE(merge.err.find("missing"), std::string::npos) << merge.err;
  EXPECT_FALSE(std::filesystem::exists(merged));

  const CommandResult no_out =
      run_program("tactile", std::string(kRepeats) + " --shard 1/3", folder);
  EXPECT_NE(no_out.exit_code, 0);
  EXPECT_NE(no_out.err.find("--out"), std::string::npos) << no_out.err;
  const CommandResult no_runs =
      run_program("tactile", "experiment tsa-classifiers --quick --repeats 0", folder);
  EXPECT_NE(no_runs.exit_code, 0);
  EXPECT_NE(no_runs.err.find("--repeats"), std::string::npos) << no_runs.err;
}

// The document's summary is the runs' own figures' mean, sample sd and range, and it holds
// neither the work folder nor a time.
TEST(ExperimentCli, RepeatsSummaryIsMeanAndDeviationOfTheRunsFigures) {
  TempFolder folder;
  const std::string work = folder.file("work");
  const CommandResult result = run_program(
      "tactile",
      std::string(kRepeats) + " --work '" + work + "' --out '" + folder.file("r.json") + "'",
      folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(std::filesystem::exists(work + "/seed-6/tsa/labels.db"));  // --work keeps each run
  const std::string text = read_text(folder.file("r.json"));
  EXPECT_EQ(text.find(work), std::string::npos);
  const nlohmann::json document = nlohmann::json::parse(text);
  EXPECT_FALSE(document.contains("work_dir"));
  ASSERT_EQ(document["runs"].size(), 3u);
  std::vector<double> accuracies;
  for (size_t run = 0; run < 3; ++run) {
    EXPECT_EQ(document["runs"][run]["seed"], 5 + run);
    accuracies.push_back(document["runs"][run]["report"]["accuracy"].get<double>());
  }
  const nlohmann::json& headline = document["summary"][0];
  EXPECT_EQ(headline["table"], "headline");
  EXPECT_EQ(headline["runs"], 3);
  const double mean = (accuracies[0] + accuracies[1] + accuracies[2]) / 3;
  double squares = 0;
  for (const double accuracy : accuracies) squares += (accuracy - mean) * (accuracy - mean);
  EXPECT_NEAR(headline["mean"].get<double>(), mean, 1e-12);
  EXPECT_NEAR(headline["sd"].get<double>(), std::sqrt(squares / 2), 1e-12);
  EXPECT_GT(headline["sd"].get<double>(), 0.0);  // three seeds, three skins
  EXPECT_EQ(headline["min"].get<double>(), *std::min_element(accuracies.begin(), accuracies.end()));
  EXPECT_EQ(headline["max"].get<double>(), *std::max_element(accuracies.begin(), accuracies.end()));
  EXPECT_EQ(headline["paper_accuracy"], document["runs"][0]["report"]["paper_accuracy"]);
}

// One repeat prints what a run without --repeats prints, as text and as JSON.
TEST(ExperimentCli, OneRepeatPrintsAsBefore) {
  TempFolder folder;
  for (const std::string json : {"", " --json"}) {
    const CommandResult plain =
        run_program("tactile", "experiment tsa-classifiers --quick --seed 3" + json, folder);
    const CommandResult once = run_program(
        "tactile", "experiment tsa-classifiers --quick --seed 3 --repeats 1" + json, folder);
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    ASSERT_EQ(once.exit_code, 0) << once.err;
    EXPECT_FALSE(plain.out.empty());
    EXPECT_EQ(once.out, plain.out) << json;
  }
}

}  // namespace
}  // namespace tactile::test

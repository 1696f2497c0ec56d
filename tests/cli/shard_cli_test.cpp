// `--shard I/N` and `tactile merge` for features and evaluate: the merged files are the bytes
// one process writes; missing, repeated, damaged and mismatched parts are refused by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_test_support.h"

namespace tactile {
namespace {

using test::CommandResult;
using test::read_text;
using test::run_program;
using test::TempFolder;

// Six fur recordings and their feature table, made once for the suite.
class ShardCommands : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    corpus_ = new TempFolder("tactile-shard");
    const CommandResult simulated = run_program(
        "tactile", "simulate --skin fur --subjects 3 --trials 2 --out " + corpus_->file("sim"),
        *corpus_);
    ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
    const CommandResult table =
        run_program("tactile",
                    "features --pipeline fur --labels " + corpus_->file("sim/labels.db") +
                        " --out " + corpus_->file("table.csv"),
                    *corpus_);
    ASSERT_EQ(table.exit_code, 0) << table.err;
  }
  static void TearDownTestSuite() {
    delete corpus_;
    corpus_ = nullptr;
  }

  static std::string labels() { return corpus_->file("sim/labels.db"); }
  static std::string table() { return corpus_->file("table.csv"); }

  CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder_);
  }
  // Runs `arguments --shard I/N` for every I and returns the part files, as --part names them.
  std::vector<std::string> run_shards(const std::string& arguments, int count,
                                      const std::string& stem) {
    std::vector<std::string> parts;
    for (int index = 1; index <= count; ++index) {
      parts.push_back(folder_.file(stem + "-" + std::to_string(index)));
      const CommandResult shard = tactile(arguments + " --shard " + std::to_string(index) + "/" +
                                          std::to_string(count) + " --part " + parts.back());
      EXPECT_EQ(shard.exit_code, 0) << arguments << ": " << shard.err;
    }
    return parts;
  }
  static std::string joined(const std::vector<std::string>& parts) {
    std::string text;
    for (const std::string& part : parts) text += " " + part;
    return text;
  }

  static TempFolder* corpus_;
  TempFolder folder_;
};

TempFolder* ShardCommands::corpus_ = nullptr;

TEST_F(ShardCommands, FeaturesFromShardsAreTheOneProcessTableAndSkipLog) {
  const std::string one = folder_.file("one.csv");
  ASSERT_EQ(tactile("features --pipeline fur --labels " + labels() + " --out " + one).exit_code, 0);
  // Three shards of six recordings, and eight: two of them have none.
  for (int count : {3, 8}) {
    const std::string merged = folder_.file("merged-" + std::to_string(count) + ".csv");
    const std::vector<std::string> parts =
        run_shards("features --pipeline fur --labels " + labels() + " --out " + merged, count,
                   "features-" + std::to_string(count));
    EXPECT_FALSE(std::filesystem::exists(merged)) << "a shard writes only its part";
    const CommandResult merge = tactile("merge" + joined(parts));  // --out: the parts' result
    ASSERT_EQ(merge.exit_code, 0) << merge.err;
    EXPECT_NE(merge.out.find("180 rows x 15 features from 6 recordings"), std::string::npos)
        << merge.out;
    EXPECT_EQ(read_text(merged), read_text(one)) << count << " shards";
    EXPECT_EQ(read_text(merged + ".log"), read_text(one + ".log"));
  }
}

TEST_F(ShardCommands, TrainAllFromFourShardsIsByteIdenticalAndPrintsTheSameTable) {
  const std::string arguments =
      "evaluate --features " + table() + " --classifier all --protocol kfold:5 --no-timings";
  const CommandResult one = tactile(arguments + " --out " + folder_.file("one.json"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::vector<std::string> parts =
      run_shards(arguments + " --out " + folder_.file("merged.json"), 4, "all");
  const CommandResult merge =
      tactile("merge" + joined(parts) + " --out " + folder_.file("out.json"));
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  EXPECT_EQ(read_text(folder_.file("out.json")), read_text(folder_.file("one.json")));
  // The table as one process prints it, but for the file it names.
  const auto table_of = [](const std::string& out) { return out.substr(0, out.find("results")); };
  EXPECT_EQ(table_of(merge.out), table_of(one.out));
  EXPECT_NE(merge.out.find("results     " + folder_.file("out.json")), std::string::npos);
}

TEST_F(ShardCommands, OneClassifiersFoldsMergeIntoItsResultFile) {
  const std::string arguments = "evaluate --features " + table() +
                                " --classifier knn:k=3 --protocol kfold:4x2 --seed 7 --no-timings";
  const CommandResult one = tactile(arguments + " --out " + folder_.file("one.json"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::vector<std::string> parts =
      run_shards(arguments + " --out " + folder_.file("merged.json"), 3, "knn");
  const CommandResult merge = tactile("merge" + joined(parts));
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  EXPECT_EQ(read_text(folder_.file("merged.json")), read_text(folder_.file("one.json")));
  EXPECT_NE(merge.out.find("protocol    kfold:4x2 (8 folds, seed 7)"), std::string::npos)
      << merge.out;
}

TEST_F(ShardCommands, AMissingShardIsNamedAndARunOfItAloneThenMerges) {
  const std::string merged = folder_.file("merged.csv");
  const std::string arguments = "features --pipeline fur --labels " + labels() + " --out " + merged;
  for (int index : {1, 2, 4}) {  // shard 3 was killed before it wrote its part
    const CommandResult shard = tactile(arguments + " --shard " + std::to_string(index) + "/4");
    ASSERT_EQ(shard.exit_code, 0) << shard.err;
    EXPECT_NE(shard.out.find(merged + ".part-" + std::to_string(index) + "-of-4"),
              std::string::npos)
        << shard.out;
  }
  const std::string parts =
      " " + merged + ".part-1-of-4 " + merged + ".part-2-of-4 " + merged + ".part-4-of-4";
  CommandResult merge = tactile("merge" + parts);
  EXPECT_NE(merge.exit_code, 0);
  EXPECT_NE(merge.err.find("shard 3/4 (" + merged + ".part-3-of-4) is missing"), std::string::npos)
      << merge.err;
  EXPECT_FALSE(std::filesystem::exists(merged));
  ASSERT_EQ(tactile(arguments + " --shard 3/4").exit_code, 0);
  merge = tactile("merge" + parts + " " + merged + ".part-3-of-4");
  ASSERT_EQ(merge.exit_code, 0) << merge.err;
  ASSERT_EQ(
      tactile("features --pipeline fur --labels " + labels() + " --out " + folder_.file("one.csv"))
          .exit_code,
      0);
  EXPECT_EQ(read_text(merged), read_text(folder_.file("one.csv")));
}

TEST_F(ShardCommands, RepeatedDamagedAndMismatchedPartsAreRefusedByName) {
  const std::string base = "evaluate --features " + table() +
                           " --classifier knn --protocol kfold:3 --out " + folder_.file("r.json");
  const std::string a = folder_.file("a"), b = folder_.file("b"), c = folder_.file("c");
  ASSERT_EQ(tactile(base + " --shard 1/2 --part " + a).exit_code, 0);
  ASSERT_EQ(tactile(base + " --shard 1/2 --part " + b).exit_code, 0);
  ASSERT_EQ(tactile(base + " --seed 9 --shard 2/2 --part " + c).exit_code, 0);
  CommandResult merge = tactile("merge " + a + " " + b);
  EXPECT_NE(merge.err.find(b + ": shard 1/2 is given twice: also " + a), std::string::npos)
      << merge.err;
  merge = tactile("merge " + a + " " + c);
  EXPECT_NE(merge.err.find(c + ": does not belong with " + a + ": it is made with --seed 9"),
            std::string::npos)
      << merge.err;
  // A features part among evaluate parts.
  const std::string features_part = folder_.file("f");
  ASSERT_EQ(tactile("features --pipeline fur --labels " + labels() + " --out " +
                    folder_.file("t.csv") + " --shard 2/2 --part " + features_part)
                .exit_code,
            0);
  merge = tactile("merge " + a + " " + features_part);
  EXPECT_NE(merge.err.find(features_part + ": a part of `tactile features`, not of `tactile "
                                           "evaluate`"),
            std::string::npos)
      << merge.err;
  // A part cut short (a shard killed while writing cannot leave one: the write is atomic; a
  // copy cut in transfer can).
  const std::string text = read_text(a);
  std::ofstream(a, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() - 40);
  merge = tactile("merge " + a + " " + c);
  EXPECT_NE(merge.err.find(a + ": not a part file (cut short or damaged?)"), std::string::npos)
      << merge.err;
  EXPECT_FALSE(std::filesystem::exists(folder_.file("r.json")));
}

TEST_F(ShardCommands, WrongShardArgumentsAreRefusedBeforeAnyWork) {
  const std::string evaluate = "evaluate --features " + table() + " --classifier knn";
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {evaluate + " --out r.json --shard 0/4", "--shard: '0/4': the shard must be 1 to N"},
      {evaluate + " --out r.json --shard 2", "--shard: '2' is not I/N"},
      {evaluate + " --out r.json --part p", "--part: belongs to a shard: give --shard I/N too"},
      {evaluate + " --shard 1/2", "--shard: needs --out"},
      {evaluate + " --out r.json --shard 1/2 --save-model m.json",
       "--save-model: fits on every row"},
      {"features --pipeline fur --labels " + labels() + " --out t.csv --shard 3/2",
       "--shard: '3/2'"},
      {"merge", "PARTS is required"},
      {"merge " + table(), "not a part file"},
  };
  for (const Case& bad : cases) {
    const CommandResult result = tactile(bad.arguments);
    EXPECT_NE(result.exit_code, 0) << bad.arguments;
    EXPECT_NE((result.err + result.out).find(bad.expected), std::string::npos)
        << bad.arguments << ": " << result.err;
  }
}

}  // namespace
}  // namespace tactile

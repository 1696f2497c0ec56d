// `tactile cluster slurm` without Slurm: the sbatch files it writes (what they hold, how they
// quote), run by plain bash as a scheduler would, give what one process gives; what it refuses.
// The run on a real Slurm is tests/slurm/cluster_test.sh (`ctest -L slurm`).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_test_support.h"

namespace tactile {
namespace {

using test::CommandResult;
using test::read_text;
using test::TempFolder;

class ClusterCommand : public ::testing::Test {
 protected:
  // Runs tactile inside the test's folder, as a user on a login node would.
  CommandResult tactile(const std::string& arguments, const std::string& environment = "") {
    return test::run_program(
        "tactile", arguments, folder_,
        "cd '" + folder_.path().string() + "' &&" + (environment.empty() ? "" : " " + environment));
  }
  // Runs a written script with bash in the test's folder.
  int bash(const std::string& script, const std::string& environment = "") {
    const std::string command = "cd '" + folder_.path().string() + "' && " + environment +
                                " bash '" + script + "' >/dev/null 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string slurm(const std::string& command, const std::string& more = "") {
    return "cluster slurm --command \"" + command + "\" --shards 3 --out jobs " + more;
  }
  TempFolder folder_{"tactile-cluster"};
};

TEST_F(ClusterCommand, WritesAnArrayOfShardsAMergeAfterThemAndASubmitScript) {
  const CommandResult run =
      tactile(slurm("tactile features --pipeline fur --labels rec/labels.db --out table.csv",
                    "--partition short --time 00:10:00"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string jobs = folder_.file("jobs");
  const std::string shards = read_text(jobs + "/shards.sbatch");
  const std::string merge = read_text(jobs + "/merge.sbatch");
  const std::string submit = read_text(jobs + "/submit.sh");
  const std::string here = folder_.path().string();
  for (const std::string& line : std::vector<std::string>{
           "#SBATCH --array=1-3\n", "#SBATCH --chdir=" + here + "\n", "#SBATCH --partition=short\n",
           "#SBATCH --time=00:10:00\n", "#SBATCH --output=" + jobs + "/logs/shard-%a.job-%A.out\n",
           "#SBATCH --error=" + jobs + "/logs/shard-%a.job-%A.err\n",
           " features --pipeline fur --labels rec/labels.db --out table.csv \\\n  --shard "
           "\"${shard}/3\" --part " +
               jobs + "/parts/part-\"${shard}\"-of-3\n"})
    EXPECT_NE(shards.find(line), std::string::npos) << line << "\nnot in\n" << shards;
  // The command runs as the same tactile, by its absolute path.
  EXPECT_NE(shards.find("\n" + test::bin_dir() + "/tactile features "), std::string::npos)
      << shards;
  EXPECT_EQ(shards.find("--partition=batch"), std::string::npos) << "given, not an example";
  for (const std::string& line : std::vector<std::string>{
           " merge \\\n  " + jobs + "/parts/part-1-of-3 \\\n  " + jobs +
               "/parts/part-2-of-3 \\\n  " + jobs + "/parts/part-3-of-3 \\\n  --out " + here +
               "/table.csv\n",
           "#SBATCH --output=" + jobs + "/logs/merge.job-%j.out\n", "#SBATCH --partition=short\n"})
    EXPECT_NE(merge.find(line), std::string::npos) << line << "\nnot in\n" << merge;
  EXPECT_NE(submit.find("array=$(sbatch --parsable " + jobs + "/shards.sbatch)"), std::string::npos)
      << submit;
  EXPECT_NE(
      submit.find("sbatch --parsable --dependency=afterok:\"${array}\" " + jobs + "/merge.sbatch"),
      std::string::npos)
      << submit;
  EXPECT_FALSE(std::filesystem::exists(jobs + "/jobs.json")) << "nothing was submitted";
  EXPECT_TRUE(std::filesystem::is_directory(jobs + "/parts"));
  EXPECT_TRUE(std::filesystem::is_directory(jobs + "/logs"));
}

// The scripts run by bash alone, one shard at a time (as a shell loop or another scheduler
// would), then the merge: byte for byte the one-process table, under a name a shell must quote.
TEST_F(ClusterCommand, ScriptsRunByHandGiveTheOneProcessResultUnderANameThatNeedsQuotes) {
  ASSERT_EQ(tactile("simulate --skin fur --subjects 2 --trials 2 --out rec").exit_code, 0);
  const std::string features = "features --pipeline fur --labels rec/labels.db --recordings rec";
  const CommandResult one = tactile(features + " --out one.csv");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  // The file name holds a space, a single quote and double quotes: "it's a \"table\".csv".
  const CommandResult run =
      tactile(slurm("tactile " + features + " --out 'it'\\\\''s a '\\\\\\\"table\\\\\\\"'.csv'"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string result = folder_.file("it's a \"table\".csv");
  EXPECT_NE(read_text(folder_.file("jobs/merge.sbatch"))
                .find("'" + folder_.path().string() + "/it'\\''s a \"table\".csv'"),
            std::string::npos)
      << read_text(folder_.file("jobs/merge.sbatch"));
  EXPECT_NE(bash(folder_.file("jobs/shards.sbatch")), 0) << "no task id: refused";
  for (const char* shard : {"3", "1", "2"})
    ASSERT_EQ(bash(folder_.file("jobs/shards.sbatch"), std::string("SLURM_ARRAY_TASK_ID=") + shard),
              0)
        << shard;
  EXPECT_EQ(read_text(folder_.file("jobs/logs/shard-2.exit")), "0\n");
  EXPECT_FALSE(std::filesystem::exists(result)) << "a shard wrote the result";
  ASSERT_EQ(bash(folder_.file("jobs/merge.sbatch")), 0);
  const std::string merged = read_text(result);
  EXPECT_FALSE(merged.empty());
  EXPECT_EQ(merged, read_text(folder_.file("one.csv")));
}

TEST_F(ClusterCommand, RefusesWhatItCannotSplitOrShardNamingIt) {
  struct Refused {
    std::string command, expected;
  };
  for (const Refused& bad : std::vector<Refused>{
           {"tactile features --out 'table.csv", "unbalanced single quote at character 24"},
           {"tactile features --out \\\"table.csv", "unbalanced double quote at character 24"},
           {"tactile features --out table.csv \\\\", "a backslash at the end"},
           {"tactile features --out \\$HOME/t.csv", "unquoted `$` at character 24"},
           {"tactile features --out t.csv > log", "unquoted `>`"},
           {"tactile features --out t.csv; rm x", "unquoted `;`"},
           {"tactile info rec", "`tactile info` does not shard"},
           {"python3 features --out t.csv", "'python3' is not tactile"},
           {"tactile features --labels l.db", "`tactile features` names its result with --out"},
           {"tactile predict --model m.json rec",
            "`tactile predict` names its result with --labels"},
           {"tactile features --out t.csv --shard 1/2", "has --shard already"},
           {"tactile", "give a whole tactile command"},
       }) {
    const CommandResult run = tactile(slurm(bad.command));
    EXPECT_EQ(run.exit_code, 1) << bad.command;
    EXPECT_NE(run.err.find("--command: " + bad.expected), std::string::npos)
        << bad.command << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(folder_.file("jobs"))) << bad.command;
  }
}

TEST_F(ClusterCommand, SubmitWithoutSbatchOnPathSaysSoAndStatusWantsASubmittedFolder) {
  CommandResult run = tactile(slurm("tactile evaluate --features t.csv --out e.json", "--submit"),
                              "PATH=/nonexistent");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--submit: sbatch is not on PATH"), std::string::npos) << run.err;
  ASSERT_EQ(tactile(slurm("tactile evaluate --features t.csv --out e.json")).exit_code, 0);
  run = tactile("cluster status jobs");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("jobs.json: cannot open"), std::string::npos) << run.err;
  run = tactile("cluster resubmit jobs --shard 2");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("jobs.json: cannot open"), std::string::npos) << run.err;
  run = tactile("cluster slurm --command \"tactile evaluate --out e.json\" --shards 0 --out j2");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--shards: give the number of shards"), std::string::npos) << run.err;
}

// Slurm's clients stood in for by scripts on PATH: what --submit, status and resubmit ask
// them and how they read the answers (a real Slurm: tests/slurm/cluster_test.sh).
class ClusterWithFakeSlurm : public ClusterCommand {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(folder_.file("fake-bin"));
    const std::string calls = folder_.file("calls.log");
    // sbatch: job ids 101, 102, ... in the order of submission.
    fake("sbatch", "echo \"sbatch $*\" >> '" + calls + "'\nn=$(grep -c ^sbatch '" + calls +
                       "')\necho $((100 + n))\n");
    fake("scancel", "echo \"scancel $*\" >> '" + calls + "'\n");
    // squeue: shard 2 of array 101 failed, the merge 102 waits for ever.
    fake("squeue",
         "for a in \"$@\"; do case $a in --jobs=*) id=${a#--jobs=};; esac; done\n"
         "case $id in\n"
         "101) printf "
         "'101_1|COMPLETED|None\\n101_2|FAILED|NonZeroExitCode\\n101_3|COMPLETED|None\\n';;\n"
         "102) printf '102|PENDING|DependencyNeverSatisfied\\n';;\n"
         "*) echo 'slurm_load_jobs error: Invalid job id specified' >&2; exit 1;;\n"
         "esac\n");
    fake("sacct", "echo 'Slurm accounting storage is disabled'\nexit 1\n");
  }
  void fake(const std::string& name, const std::string& body) {
    const std::string path = folder_.file("fake-bin/" + name);
    std::ofstream(path) << "#!/bin/bash\n" << body;
    std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  }
  CommandResult with_slurm(const std::string& arguments) {
    return tactile(arguments, "PATH='" + folder_.file("fake-bin") + "':\"$PATH\"");
  }
};

TEST_F(ClusterWithFakeSlurm, SubmitsRecordsReportsAndResubmitsOnlyTheFailedShard) {
  CommandResult run = with_slurm(slurm("tactile features --labels l.db --out t.csv", "--submit"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("shards: job 101 (array 1-3)\nmerge: job 102"), std::string::npos)
      << run.out;
  const std::string jobs = folder_.file("jobs");
  EXPECT_EQ(read_text(folder_.file("calls.log")),
            "sbatch --parsable " + jobs +
                "/shards.sbatch\nsbatch --parsable --dependency=afterok:101 " + jobs +
                "/merge.sbatch\n");
  // What the shards left: parts 1 and 3, shard 2's exit code.
  std::ofstream(jobs + "/parts/part-1-of-3") << "";
  std::ofstream(jobs + "/parts/part-3-of-3") << "";
  std::ofstream(jobs + "/logs/shard-2.exit") << "1\n";
  run = with_slurm("cluster status jobs");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const std::string& line : std::vector<std::string>{
           "shard 1/3  job 101_1  completed  part present\n",
           "shard 2/3  job 101_2  failed  exit 1  (NonZeroExitCode)  part missing\n",
           "merge  job 102  pending  (DependencyNeverSatisfied)  result missing: " +
               folder_.file("t.csv") + "\n",
           "parts: 2 of 3 present (missing: shard 2)\n",
           "note: sacct: Slurm accounting storage is disabled - sacct needs slurmdbd"})
    EXPECT_NE(run.out.find(line), std::string::npos) << line << "\nnot in\n" << run.out;

  run = with_slurm("cluster resubmit jobs --shard 4");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--shard: 4 is not a shard of this job (1 to 3)"), std::string::npos)
      << run.err;
  run = with_slurm("cluster resubmit jobs --shard 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("cancelled the old merge, job 102\nshards 2: job 103\nmerge: job 104"),
            std::string::npos)
      << run.out;
  const std::string calls = read_text(folder_.file("calls.log"));
  EXPECT_NE(calls.find("scancel 102\nsbatch --parsable --array=2 " + jobs +
                       "/shards.sbatch\nsbatch --parsable --dependency=afterok:103 " + jobs +
                       "/merge.sbatch\n"),
            std::string::npos)
      << calls;
  EXPECT_FALSE(std::filesystem::exists(jobs + "/logs/shard-2.exit")) << "the old run's code";
  run = with_slurm("cluster status jobs");
  EXPECT_NE(run.out.find("shard 2/3  job 103_2  unknown"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("shard 3/3  job 101_3  completed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("merge  job 104  unknown"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace tactile

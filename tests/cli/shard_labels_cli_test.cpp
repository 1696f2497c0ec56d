// `--shard I/N` of `tactile simulate`, `segment`, `predict` and `verify`, and `tactile merge`
// of their parts: the merged result is what one process writes (the same recording files
// and labels.db bytes for simulate, the same labels for segment and predict, the same report
// for verify), with more shards than items too; a missing shard is named, a shard run again
// alone merges, parts of another run are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;

std::string quoted(const std::string& path) { return "'" + path + "'"; }

// Every file of a folder (name -> bytes), the part files left out.
std::map<std::string, std::string> folder_files(const std::string& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().find(".part-") == std::string::npos)
      files[entry.path().filename().string()] = test::read_text(entry.path());
  return files;
}

// A label store's labels as text, one per line: everything but the times the store stamps
// when it adds a label (created, modified: the wall clock of the run).
std::string labels_of(const std::string& database) {
  std::string text;
  for (const Label& label : LabelStore(database, LabelStore::OpenMode::kReadOnly).list())
    text += std::to_string(label.id) + " " + label.recording + " " + std::to_string(label.t0) +
            " " + std::to_string(label.t1) + " " + label.region + " " + label.class_name + " " +
            label.annotator + " " + to_string(label.source) + " " +
            std::to_string(label.confidence) + " " + label.note + " r" +
            std::to_string(label.revision) + "\n";
  return text;
}

std::string part_list(const std::string& stem, int count) {
  std::string list;
  for (int index = 1; index <= count; ++index) {
    list += ' ';
    list += quoted(stem + ".part-" + std::to_string(index) + "-of-" + std::to_string(count));
  }
  return list;
}

class ShardLabels : public ::testing::Test {
 protected:
  CommandResult tactile(const std::string& arguments) {
    return test::run_program("tactile", arguments, folder_);
  }
  std::string file(const std::string& name) const { return folder_.file(name); }

  // `simulate` of four fur recordings into `name`, whole or as one shard.
  CommandResult simulate(const std::string& name, const std::string& more = "") {
    return tactile("simulate --skin fur --subjects 4 --repetitions 1 --out " + quoted(file(name)) +
                   " " + more);
  }
  // Every shard of N, each alone, then the merge.
  void simulate_sharded(const std::string& name, int count) {
    for (int index = 1; index <= count; ++index) {
      const CommandResult shard =
          simulate(name, "--shard " + std::to_string(index) + "/" + std::to_string(count));
      ASSERT_EQ(shard.exit_code, 0) << shard.err;
      EXPECT_FALSE(fs::exists(file(name + "/labels.db"))) << "a shard wrote the store";
    }
    const CommandResult merged = tactile("merge" + part_list(file(name + "/simulate"), count));
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
  }

  test::TempFolder folder_{"tactile-shard-labels"};
};

TEST_F(ShardLabels, SimulateShardsMergeIntoTheOneProcessFolder) {
  ASSERT_EQ(simulate("one").exit_code, 0);
  const auto one = folder_files(file("one"));
  ASSERT_EQ(one.size(), 5u);        // four recordings and labels.db
  for (const int count : {3, 6}) {  // 6: more shards than trials, two parts empty
    const std::string name = "sharded" + std::to_string(count);
    simulate_sharded(name, count);
    EXPECT_EQ(folder_files(file(name)), one) << count << " shards";
  }
  const CommandResult demo = tactile("simulate --demo " + quoted(file("demo")) + " --shard 1/2");
  EXPECT_EQ(demo.exit_code, 1);
  EXPECT_NE(demo.err.find("the demo workspace does not shard"), std::string::npos) << demo.err;
}

TEST_F(ShardLabels, SimulateMergeNamesMissingShardsAndRecordings) {
  for (const char* shard : {"1/3", "3/3"})
    ASSERT_EQ(simulate("s", "--shard " + std::string(shard)).exit_code, 0);
  const std::string stem = file("s/simulate");
  CommandResult merged =
      tactile("merge " + quoted(stem + ".part-1-of-3") + " " + quoted(stem + ".part-3-of-3"));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(merged.err.find("shard 2/3 (" + stem + ".part-2-of-3) is missing"), std::string::npos)
      << merged.err;
  // Shard 2 run alone (after a kill, say): its recording lost meanwhile is named, run again it
  // merges.
  ASSERT_EQ(simulate("s", "--shard 2/3").exit_code, 0);
  fs::remove(file("s/fur-s02-t01.h5"));
  merged = tactile("merge" + part_list(stem, 3));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(
      merged.err.find("fur-s02-t01.h5: the recording " + stem + ".part-2-of-3 wrote is missing"),
      std::string::npos)
      << merged.err;
  EXPECT_FALSE(fs::exists(file("s/labels.db")));
  ASSERT_EQ(simulate("s", "--shard 2/3").exit_code, 0);
  merged = tactile("merge" + part_list(stem, 3));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("wrote 4 recordings"), std::string::npos) << merged.out;
  ASSERT_EQ(simulate("one").exit_code, 0);
  EXPECT_EQ(folder_files(file("s")), folder_files(file("one")));
  // A shard of another seed does not belong with the others.
  ASSERT_EQ(simulate("s", "--seed 2 --shard 2/3").exit_code, 0);
  merged = tactile("merge" + part_list(stem, 3));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(merged.err.find("does not belong with"), std::string::npos) << merged.err;
}

// Two stores with the ground truth of four fur recordings, for segment and predict to write
// into: one for one process, one for the shards' merge.
class ShardLabelStores : public ShardLabels {
 protected:
  void SetUp() override {
    ASSERT_EQ(simulate("rec").exit_code, 0);
    for (const char* name : {"one.db", "merged.db", "six.db"})
      fs::copy_file(file("rec/labels.db"), file(name));
  }
  // `tactile COMMAND ... --labels DB` as one process into one.db, as N shards + merge into
  // merged.db, and as 6 shards (more than the recordings) into six.db; the three alike.
  void expect_sharded_like_one(const std::string& command, const std::string& stem) {
    const CommandResult one = tactile(command + " --labels " + quoted(file("one.db")));
    ASSERT_EQ(one.exit_code, 0) << one.err;
    for (const auto& [database, count] :
         std::vector<std::pair<std::string, int>>{{"merged.db", 3}, {"six.db", 6}}) {
      const std::string before = labels_of(file(database));
      for (int index = 1; index <= count; ++index) {
        const CommandResult shard =
            tactile(command + " --labels " + quoted(file(database)) + " --shard " +
                    std::to_string(index) + "/" + std::to_string(count));
        ASSERT_EQ(shard.exit_code, 0) << shard.err;
      }
      EXPECT_EQ(labels_of(file(database)), before) << "a shard wrote the store";
      const CommandResult merged = tactile("merge" + part_list(file(database) + "." + stem, count));
      ASSERT_EQ(merged.exit_code, 0) << merged.err;
      // What it says per recording, and in all, is one process's (the store's name aside).
      std::string said = merged.out;
      said.replace(said.find(file(database)), file(database).size(), file("one.db"));
      EXPECT_EQ(said, one.out) << count << " shards";
      EXPECT_EQ(labels_of(file(database)), labels_of(file("one.db"))) << count << " shards";
    }
    EXPECT_NE(labels_of(file("one.db")), labels_of(file("rec/labels.db")));
  }
};

TEST_F(ShardLabelStores, SegmentShardsMergeIntoTheOneProcessLabels) {
  expect_sharded_like_one("segment " + quoted(file("rec")), "segment");
  // Again with --replace over the segments stored: replaced alike.
  expect_sharded_like_one("segment " + quoted(file("rec")) + " --replace", "segment");
}

TEST_F(ShardLabelStores, SegmentMergeRefusesMissingAndMismatchedShards) {
  const std::string segment =
      "segment " + quoted(file("rec")) + " --labels " + quoted(file("merged.db"));
  ASSERT_EQ(tactile(segment + " --shard 1/2").exit_code, 0);
  const std::string stem = file("merged.db.segment");
  CommandResult merged = tactile("merge " + quoted(stem + ".part-1-of-2"));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(merged.err.find("shard 2/2 (" + stem + ".part-2-of-2) is missing"), std::string::npos)
      << merged.err;
  ASSERT_EQ(tactile(segment + " --method threshold --shard 2/2").exit_code, 0);
  merged = tactile("merge" + part_list(stem, 2));
  EXPECT_EQ(merged.exit_code, 1);
  EXPECT_NE(merged.err.find("does not belong with"), std::string::npos) << merged.err;
  EXPECT_EQ(labels_of(file("merged.db")), labels_of(file("rec/labels.db")));
  // Shard 2 run again as it should have been: the merge goes through.
  ASSERT_EQ(tactile(segment + " --shard 2/2").exit_code, 0);
  merged = tactile("merge" + part_list(stem, 2));
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  ASSERT_EQ(
      tactile("segment " + quoted(file("rec")) + " --labels " + quoted(file("one.db"))).exit_code,
      0);
  EXPECT_EQ(labels_of(file("merged.db")), labels_of(file("one.db")));
}

TEST_F(ShardLabelStores, PredictShardsMergeIntoTheOneProcessLabels) {
  CommandResult run = tactile("features --pipeline fur --labels " + quoted(file("rec/labels.db")) +
                              " --out " + quoted(file("f.csv")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = tactile("evaluate --features " + quoted(file("f.csv")) +
                " --classifier knn:k=1 --protocol kfold:2 --pipeline fur --save-model " +
                quoted(file("model.json")));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string predict =
      "predict " + quoted(file("rec")) + " --model " + quoted(file("model.json"));
  expect_sharded_like_one(predict, "predict");
  // Twice: the earlier predictions replaced alike.
  expect_sharded_like_one(predict, "predict");

  // A shard run with another model does not belong with the others.
  fs::copy_file(file("model.json"), file("other.json"));
  { std::ofstream(file("other.json"), std::ios::app) << "\n"; }
  const std::string shard = predict + " --labels " + quoted(file("merged.db"));
  ASSERT_EQ(tactile(shard + " --shard 1/2").exit_code, 0);
  ASSERT_EQ(tactile("predict " + quoted(file("rec")) + " --model " + quoted(file("other.json")) +
                    " --labels " + quoted(file("merged.db")) + " --shard 2/2")
                .exit_code,
            0);
  run = tactile("merge" + part_list(file("merged.db.predict"), 2));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("does not belong with"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--model"), std::string::npos) << run.err;
  // A shard reads the store: one that is not there is named.
  run = tactile(predict + " --labels " + quoted(file("absent.db")) + " --shard 1/2");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("absent.db: no such label store"), std::string::npos) << run.err;
}

TEST_F(ShardLabelStores, VerifyShardsMergeIntoTheOneProcessReport) {
  // Problems to find: a damaged recording, and a label beyond its recording's end (found
  // with the span of a recording another shard checks).
  {
    std::ofstream(file("rec/broken.h5")) << "not HDF5";
    LabelStore store(file("rec/labels.db"));
    Label late;
    late.recording = "fur-s01-t01";
    late.t0 = 1000.0;
    late.t1 = 1001.0;
    late.class_name = "stroke";
    late.annotator = "test";
    store.add(late);
  }
  const std::string verify = "verify " + quoted(file("rec")) + " " + quoted(file("absent.h5"));
  const CommandResult one = tactile(verify + " --out " + quoted(file("one.json")));
  ASSERT_EQ(one.exit_code, 1) << one.err;
  EXPECT_NE(one.out.find("lies outside recording fur-s01-t01"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find("absent.h5: no such file or folder"), std::string::npos) << one.out;
  EXPECT_EQ(test::read_text(file("one.json")), tactile(verify + " --json").out);
  for (const int count : {3, 9}) {  // 9: more shards than the six files
    const std::string report = file("sharded" + std::to_string(count) + ".json");
    for (int index = 1; index <= count; ++index) {
      const CommandResult shard = tactile(verify + " --out " + quoted(report) + " --shard " +
                                          std::to_string(index) + "/" + std::to_string(count));
      ASSERT_EQ(shard.exit_code, 0) << shard.err;
    }
    EXPECT_FALSE(fs::exists(report));
    const CommandResult merged = tactile("merge" + part_list(report, count));
    EXPECT_EQ(merged.exit_code, 1) << merged.err;
    EXPECT_EQ(merged.out, one.out);
    EXPECT_EQ(merged.err, one.err);
    EXPECT_EQ(test::read_text(report), test::read_text(file("one.json"))) << count << " shards";
  }
  // No problems: exit 0, and the merge too.
  fs::remove(file("rec/broken.h5"));
  const std::string clean =
      "verify " + quoted(file("rec/fur-s01-t01.h5")) + " --out " + quoted(file("clean.json"));
  for (const char* shard : {"1/2", "2/2"})
    ASSERT_EQ(tactile(clean + " --shard " + shard).exit_code, 0);
  const CommandResult merged = tactile("merge" + part_list(file("clean.json"), 2));
  EXPECT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.err.find("verified 1 recording(s) and 0 label store(s): no problems"),
            std::string::npos)
      << merged.err;
  // A shard needs the report's name; a missing shard is named.
  EXPECT_NE(tactile(verify + " --shard 1/2").err.find("--shard: give --out REPORT.json"),
            std::string::npos);
  ASSERT_EQ(tactile(verify + " --out " + quoted(file("r.json")) + " --shard 1/2").exit_code, 0);
  const CommandResult missing = tactile("merge " + quoted(file("r.json.part-1-of-2")));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("shard 2/2"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace tactile

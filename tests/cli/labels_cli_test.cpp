// `tactile labels`: databases built with the core API, the binary run as a user would.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

class LabelsCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = folder_.path();
    database_ = (directory_ / "labels.db").string();
    LabelStore store(database_);
    Label label;
    label.recording = "nao/s01";
    label.t0 = 0.5;
    label.t1 = 1.5;
    label.region = "front";
    label.class_name = "stroke";
    label.annotator = "ana";
    label.note = "comma, \"quote\"";
    store.add(label);
    label.t0 = 2.0;
    label.t1 = 2.25;
    label.class_name = "poke";
    label.source = LabelSource::kSegmenter;
    label.confidence = 0.6;
    label.note.clear();
    store.add(label);
    label.recording = "nao/s02";
    label.class_name = "pat";
    store.add(label);
    store.set_classes("nao", {"pat", "poke", "stroke"});
  }
  // Runs `tactile ARGUMENTS`; stdout and stderr land in stdout.txt and stderr.txt.
  int run(const std::string& arguments) {
    const test::CommandResult result = test::run_program("tactile", arguments, folder_);
    std::ofstream(directory_ / "stdout.txt", std::ios::binary) << result.out;
    std::ofstream(directory_ / "stderr.txt", std::ios::binary) << result.err;
    return result.exit_code;
  }

  std::string text_of(const std::string& name) const { return test::read_text(directory_ / name); }

  test::TempFolder folder_{"labels_cli"};
  std::filesystem::path directory_;
  std::string database_;
};

TEST_F(LabelsCommandTest, ExportJsonWritesFilteredLabels) {
  const std::string out = (directory_ / "out.json").string();
  ASSERT_EQ(run("labels export '" + database_ + "' --json '" + out +
                "' --recording nao/s01 --source segmenter"),
            0)
      << text_of("stderr.txt");
  const nlohmann::json document = nlohmann::json::parse(text_of("out.json"));
  ASSERT_EQ(document.at("labels").size(), 1u);
  const nlohmann::json& label = document["labels"][0];
  EXPECT_EQ(label.at("recording"), "nao/s01");
  EXPECT_EQ(label.at("class"), "poke");
  EXPECT_EQ(label.at("source"), "segmenter");
  EXPECT_EQ(label.at("t0"), 2.0);
  EXPECT_EQ(label.at("t1"), 2.25);
  EXPECT_EQ(label.at("confidence"), 0.6);
}

TEST_F(LabelsCommandTest, ExportCsvQuotesNotes) {
  ASSERT_EQ(run("labels export '" + database_ + "' --csv '" + (directory_ / "out.csv").string() +
                "' --recording nao/s01"),
            0)
      << text_of("stderr.txt");
  const std::string csv = text_of("out.csv");
  EXPECT_NE(csv.find(",stroke,ana,manual,1,\"comma, \"\"quote\"\"\","), std::string::npos) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
}

TEST_F(LabelsCommandTest, ExportNeedsExactlyOneFormat) {
  const std::string out = (directory_ / "out.json").string();
  EXPECT_NE(run("labels export '" + database_ + "'"), 0);
  EXPECT_NE(text_of("stderr.txt").find("--csv"), std::string::npos);
  EXPECT_NE(run("labels export '" + database_ + "' --json '" + out + "' --csv '" + out + "'"), 0);
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(LabelsCommandTest, UnknownSourceIsNamed) {
  EXPECT_EQ(run("labels export '" + database_ + "' --json '" + (directory_ / "o.json").string() +
                "' --source oracle"),
            1);
  EXPECT_NE(text_of("stderr.txt").find("--source"), std::string::npos);
}

TEST_F(LabelsCommandTest, MissingDatabaseIsAnErrorAndIsNotCreated) {
  const std::string missing = (directory_ / "missing.db").string();
  EXPECT_EQ(
      run("labels export '" + missing + "' --json '" + (directory_ / "o.json").string() + "'"), 1);
  EXPECT_NE(text_of("stderr.txt").find(missing), std::string::npos);
  EXPECT_EQ(run("labels list '" + missing + "'"), 1);
  EXPECT_FALSE(std::filesystem::exists(missing));
}

TEST_F(LabelsCommandTest, ListPrintsATableAndJson) {
  ASSERT_EQ(run("labels list '" + database_ + "' --recording nao/s02"), 0);
  const std::string table = text_of("stdout.txt");
  EXPECT_EQ(table.rfind("id", 0), 0u) << table;
  EXPECT_NE(table.find("pat"), std::string::npos);
  EXPECT_EQ(table.find("stroke"), std::string::npos);
  EXPECT_NE(table.find("1 label\n"), std::string::npos);
  ASSERT_EQ(run("labels list '" + database_ + "' --json"), 0);
  EXPECT_EQ(nlohmann::json::parse(text_of("stdout.txt")).at("labels").size(), 3u);
}

TEST_F(LabelsCommandTest, ClassesPrintsTheVocabularyInOrder) {
  ASSERT_EQ(run("labels classes '" + database_ + "' nao"), 0);
  EXPECT_EQ(text_of("stdout.txt"), "pat\npoke\nstroke\n");
  EXPECT_EQ(run("labels classes '" + database_ + "' fur"), 1);
  EXPECT_NE(text_of("stderr.txt").find("fur"), std::string::npos);
}

TEST_F(LabelsCommandTest, NotADatabaseIsReported) {
  std::ofstream(directory_ / "junk.db") << "this is not sqlite, just text that is long enough";
  EXPECT_EQ(run("labels list '" + (directory_ / "junk.db").string() + "'"), 1);
  EXPECT_NE(text_of("stderr.txt").find("not a SQLite database"), std::string::npos)
      << text_of("stderr.txt");
}

// Every field but the store's own (id, created, modified).
nlohmann::json content_of(nlohmann::json labels) {
  for (auto& label : labels) {
    label.erase("id");
    label.erase("created");
    label.erase("modified");
  }
  return labels;
}

TEST_F(LabelsCommandTest, ImportRoundTripsWhatExportWrites) {
  {
    LabelStore store(database_);
    Label label;
    label.recording = "nao/s03";
    label.t0 = 1.0 / 3.0;
    label.t1 = 2.0;
    label.class_name = "pat";
    label.annotator = "zoë";
    label.note = "two\r\nlines, \"quoted\"";
    store.add(label);
  }
  ASSERT_EQ(
      run("labels export '" + database_ + "' --json '" + (directory_ / "all.json").string() + "'"),
      0);
  ASSERT_EQ(
      run("labels export '" + database_ + "' --csv '" + (directory_ / "all.csv").string() + "'"),
      0);
  const nlohmann::json original = nlohmann::json::parse(text_of("all.json"))["labels"];
  for (const char* format : {"csv", "json"}) {
    SCOPED_TRACE(format);
    const std::string copy = (directory_ / (std::string("copy-") + format + ".db")).string();
    ASSERT_EQ(run("labels import '" + copy + "' '" +
                  (directory_ / (std::string("all.") + format)).string() + "'"),
              0)
        << text_of("stderr.txt");
    EXPECT_EQ(text_of("stdout.txt"), "imported 4 labels into " + copy + "\n");
    ASSERT_EQ(
        run("labels export '" + copy + "' --json '" + (directory_ / "back.json").string() + "'"),
        0);
    EXPECT_EQ(content_of(nlohmann::json::parse(text_of("back.json"))["labels"]),
              content_of(original));
  }
}

TEST_F(LabelsCommandTest, ImportNamesTheLineOfABadLabelAndAddsNothing) {
  std::ofstream(directory_ / "bad.csv")
      << "id,recording,t0,t1,region,class,annotator,source,confidence,note,created,modified\r\n"
      << "1,rec,0.5,1.5,all,pat,ana,manual,1,\"a\r\nnote\",,\r\n"
      << "2,rec,2.5,1.5,all,pat,ana,manual,1,,,\r\n";
  const std::string copy = (directory_ / "copy.db").string();
  EXPECT_EQ(run("labels import '" + copy + "' '" + (directory_ / "bad.csv").string() + "'"), 1);
  // The second label starts on line 4: the note of the first spans two lines.
  EXPECT_NE(text_of("stderr.txt").find("bad.csv:4: t0 (2.5 s) must be before t1 (1.5 s)"),
            std::string::npos)
      << text_of("stderr.txt");
  EXPECT_FALSE(std::filesystem::exists(copy));
  std::ofstream(directory_ / "bad.json")
      << R"({"labels": [{"recording": "r", "t0": 1, "t1": 2, "region": "all", "class": "pat", "annotator": "a", "source": "sometimes"}]})";
  EXPECT_EQ(run("labels import '" + copy + "' '" + (directory_ / "bad.json").string() + "'"), 1);
  EXPECT_NE(text_of("stderr.txt").find("bad.json label 1"), std::string::npos)
      << text_of("stderr.txt");
}

TEST_F(LabelsCommandTest, AgreementComparesTwoLanes) {
  const std::string database = (directory_ / "two.db").string();
  {
    LabelStore store(database);
    auto add = [&](double t0, double t1, const char* class_name, LabelSource source,
                   const char* annotator) {
      Label label;
      label.recording = "r";
      label.t0 = t0;
      label.t1 = t1;
      label.class_name = class_name;
      label.source = source;
      label.annotator = annotator;
      store.add(label);
    };
    add(1, 3, "pat", LabelSource::kGroundTruth, "simulator");
    add(5, 7, "slap", LabelSource::kGroundTruth, "simulator");
    add(1, 3, "pat", LabelSource::kManual, "ana");
    add(5.5, 7, "stroke", LabelSource::kManual, "ana");
    add(8, 9, "pat", LabelSource::kManual, "ana");
  }
  ASSERT_EQ(run("labels agreement '" + database + "' --a ground-truth --b ana --json"), 0)
      << text_of("stderr.txt");
  const nlohmann::json agreement = nlohmann::json::parse(text_of("stdout.txt"));
  EXPECT_EQ(agreement["matched"], 2);
  EXPECT_NEAR(agreement["f1"].get<double>(), 0.8, 1e-12);
  EXPECT_EQ(agreement["disagreements"].size(), 2u);
  EXPECT_EQ(agreement["disagreements"][0]["kind"], "class");
  EXPECT_GT(agreement["kappa"].get<double>(), 0.0);
  ASSERT_EQ(run("labels agreement '" + database + "' --a ground-truth --b bob"), 1);
  EXPECT_NE(text_of("stderr.txt").find("--b: no labels in lane 'manual:bob'"), std::string::npos)
      << text_of("stderr.txt");
  // ana's stroke [5.5, 7) and a second label over it on the same region: an overlap.
  {
    LabelStore store(database);
    Label label;
    label.recording = "r";
    label.t0 = 6;
    label.t1 = 6.5;
    label.class_name = "pat";
    label.annotator = "ana";
    store.add(label);
  }
  ASSERT_EQ(run("labels check '" + database + "'"), 1);
  EXPECT_NE(text_of("stdout.txt").find("r 6.000-6.500 s: overlap: label 6 overlaps label 4"),
            std::string::npos)
      << text_of("stdout.txt");
}

// `labels check` holds each label against its recording beside the store: a label that ends
// after the recording, or is shorter than one of its samples, is an issue; `labels import` of
// the same file twice adds its labels once.
TEST_F(LabelsCommandTest, CheckReportsLabelsOutsideTheirRecordingAndImportIsIdempotent) {
  const std::string database = (directory_ / "bounded.db").string();
  Recording recording;
  recording.id = "r";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 50.0;
  skin.channels = {"ch0"};
  skin.units = {"V"};
  skin.samples = SampleMatrix::Zero(150, 1);  // 3 s
  recording.streams.push_back(skin);
  write_recording((directory_ / "r.h5").string(), recording);
  {
    LabelStore store(database);
    for (const auto& [t0, t1] : std::vector<std::pair<double, double>>{{0.5, 1.5}, {2.5, 3.5}}) {
      Label label;
      label.recording = "r";
      label.t0 = t0;
      label.t1 = t1;
      label.class_name = "pat";
      label.annotator = "ana";
      store.add(label);
    }
  }
  ASSERT_EQ(run("labels check '" + database + "'"), 1);
  EXPECT_NE(text_of("stdout.txt")
                .find("r 2.500-3.500 s: outside: label 2 (pat, 2.5 s to 3.5 s) ends after its "
                      "recording's end at 3.000 s"),
            std::string::npos)
      << text_of("stdout.txt");

  const std::string csv = (directory_ / "ours.csv").string();
  std::ofstream(csv) << "id,recording,t0,t1,region,class,annotator,source,confidence,note,"
                        "created,modified\n"
                     << "1,r,0.2,0.4,all,stroke,bob,manual,1,,,\n"
                     << "2,r,1.0,2.0,all,pat,bob,manual,1,,,\n";
  const std::string fresh = (directory_ / "fresh.db").string();
  ASSERT_EQ(run("labels import '" + fresh + "' '" + csv + "'"), 0) << text_of("stderr.txt");
  EXPECT_EQ(text_of("stdout.txt"), "imported 2 labels into " + fresh + "\n");
  ASSERT_EQ(run("labels import '" + fresh + "' '" + csv + "'"), 0) << text_of("stderr.txt");
  EXPECT_EQ(text_of("stdout.txt"),
            "imported 0 labels into " + fresh + "; 2 already there, not added again\n");
  EXPECT_EQ(LabelStore(fresh).count("r"), 2);
}

}  // namespace
}  // namespace tactile

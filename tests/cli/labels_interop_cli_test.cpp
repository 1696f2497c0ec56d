// `tactile labels export --eaf / --label-studio` and `labels import FILE.eaf / FILE.json`: the
// binary run as a user would, on a store with every kind of lane and on the hand-written files
// of tests/data/interop.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

const std::string kInteropFiles = test::test_data_dir() + "/interop/";

class LabelsInteropCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = folder_.path();
    database_ = (directory_ / "labels.db").string();
    LabelStore store(database_);
    auto add = [&](const char* recording, double t0, double t1, const char* class_name,
                   const char* annotator, LabelSource source) {
      Label label;
      label.recording = recording;
      label.t0 = t0;
      label.t1 = t1;
      label.class_name = class_name;
      label.annotator = annotator;
      label.source = source;
      return label;
    };
    Label noted = add("nao/s01", 0.5, 1.5, "stroke", "ana", LabelSource::kManual);
    noted.note = "comma, \"quote\" <tag> & more";
    noted.region = "front";
    store.add_many(
        {noted, add("nao/s01", 0.52, 1.4, "pat", "ben", LabelSource::kManual),
         add("nao/s01", 0.5, 1.45, "stroke", "protocol", LabelSource::kGroundTruth),
         add("nao/s01", 0.49, 1.6, "unknown", "segmenter:threshold", LabelSource::kSegmenter),
         add("nao/s02", 2.0, 2.25, "poke", "svm", LabelSource::kModel)});
    store.set_classes("nao", {"pat", "poke", "stroke", "tap"});
  }
  int run(const std::string& arguments) {
    result_ = test::run_program("tactile", arguments, folder_);
    return result_.exit_code;
  }
  // The store's labels, every field but id and the store's times, one line each, sorted (labels
  // starting together come back in the file's order, not the store's ids).
  static std::string store_content_of(const std::string& database) {
    std::vector<std::string> lines;
    for (const Label& label : LabelStore(database, LabelStore::OpenMode::kExisting).list())
      lines.push_back(label.recording + "|" + std::to_string(label.t0) + "|" +
                      std::to_string(label.t1) + "|" + label.region + "|" + label.class_name + "|" +
                      label.annotator + "|" + to_string(label.source) + "|" +
                      std::to_string(label.confidence) + "|" + label.note + "\n");
    std::sort(lines.begin(), lines.end());
    std::string text;
    for (const std::string& line : lines) text += line;
    return text;
  }

  test::TempFolder folder_{"labels_interop_cli"};
  std::filesystem::path directory_;
  std::string database_;
  test::CommandResult result_;
};

TEST_F(LabelsInteropCommandTest, ElanExportOfOneRecordingImportsBackEqual) {
  const std::string eaf = (directory_ / "s01.eaf").string();
  // Two recordings: the export asks which.
  EXPECT_EQ(run("labels export '" + database_ + "' --eaf '" + eaf + "'"), 1);
  EXPECT_NE(result_.err.find("one .eaf holds one recording"), std::string::npos) << result_.err;
  EXPECT_FALSE(std::filesystem::exists(eaf));
  ASSERT_EQ(
      run("labels export '" + database_ + "' --eaf '" + eaf + "' --recording nao/s01 --skin nao"),
      0)
      << result_.err;
  const std::string text = test::read_text(eaf);
  EXPECT_NE(text.find("<CVE_VALUE DESCRIPTION=\"\" LANG_REF=\"eng\">tap</CVE_VALUE>"),
            std::string::npos);
  const std::string copy = (directory_ / "copy.db").string();
  ASSERT_EQ(run("labels import '" + copy + "' '" + eaf + "'"), 0) << result_.err;
  EXPECT_EQ(result_.out, "imported 4 labels into " + copy + "\n");
  // Every time is on a millisecond, so the copy is equal field by field.
  const std::string original = store_content_of(database_);
  EXPECT_EQ(store_content_of(copy), original.substr(0, original.find("nao/s02")));
}

TEST_F(LabelsInteropCommandTest, LabelStudioExportOfEveryRecordingImportsBackEqual) {
  const std::string json = (directory_ / "tasks.json").string();
  ASSERT_EQ(run("labels export '" + database_ + "' --label-studio '" + json + "'"), 0)
      << result_.err;
  const std::string copy = (directory_ / "copy.db").string();
  ASSERT_EQ(run("labels import '" + copy + "' '" + json + "'"), 0) << result_.err;
  EXPECT_EQ(result_.out, "imported 5 labels into " + copy + "\n");
  EXPECT_EQ(store_content_of(copy), store_content_of(database_));
}

TEST_F(LabelsInteropCommandTest, ImportMapsTiersAndUsersAndRefusesUnalignedAnnotations) {
  const std::string copy = (directory_ / "copy.db").string();
  ASSERT_EQ(run("labels import '" + copy + "' '" + kInteropFiles +
                "session.eaf' --recording nao/s07 --tier 'Touch (Ana)=ground-truth' --tier "
                "'Touch (Ben)'"),
            0)
      << result_.err;
  EXPECT_EQ(result_.out, "imported 4 labels into " + copy + "\n");
  EXPECT_EQ(store_content_of(copy),
            "nao/s07|0.120000|0.870000|all|stroke|ana|ground-truth|1.000000|\n"
            "nao/s07|0.140000|0.905000|all|stroke|ben|manual|1.000000|\n"
            "nao/s07|1.500000|2.250000|all|pat|ana|ground-truth|1.000000|\n"
            "nao/s07|3.001000|3.999000|all|poke|ben|manual|1.000000|very short, maybe a tap\n");
  const std::string other = (directory_ / "other.db").string();
  EXPECT_EQ(run("labels import '" + other + "' '" + kInteropFiles + "unaligned.eaf'"), 1);
  EXPECT_NE(result_.err.find("unaligned.eaf tier 'Touch (Ben)' annotation 'a4': unaligned"),
            std::string::npos)
      << result_.err;
  EXPECT_FALSE(std::filesystem::exists(other));
  ASSERT_EQ(run("labels import '" + other + "' '" + kInteropFiles +
                "label_studio.json' --annotator 1=ana --annotator 2=ben"),
            0)
      << result_.err;
  EXPECT_EQ(result_.out, "imported 5 labels into " + other + "\n");
  EXPECT_EQ(store_content_of(other),
            "s07|0.120000|0.870000|all|stroke|ana|manual|1.000000|\n"
            "s07|0.140500|0.905000|all|stroke|ben|ground-truth|1.000000|\n"
            "s07|1.500000|2.250000|all|pat|ana|manual|1.000000|light, two fingers\n"
            "s07|3.001000|3.999000|all|poke|svm-2024-04|model|0.640000|\n"
            "s08|10.250000|11.000000|all|poke|ben|manual|1.000000|\n");
  EXPECT_EQ(
      run("labels import '" + other + "' '" + kInteropFiles + "label_studio.json' --annotator 1"),
      1);
  EXPECT_NE(result_.err.find("--annotator: expected USER=LANE, got '1'"), std::string::npos)
      << result_.err;
}

// An ELAN or Label Studio file given to `tactile import` is no recording: the refusal says
// where labels go instead of asking for a rate, and nothing is written.
TEST_F(LabelsInteropCommandTest, ALabelFileGivenToImportIsSentToLabelsImport) {
  for (const char* file : {"session.eaf", "label_studio.json"}) {
    SCOPED_TRACE(file);
    const std::string out = (directory_ / "not-written.h5").string();
    EXPECT_EQ(run("import '" + kInteropFiles + file + "' --layout nao --out '" + out + "'"), 1);
    EXPECT_NE(result_.err.find(std::string("), not a recording: labels go into a label store with "
                                           "`tactile labels import DB ")),
              std::string::npos)
        << result_.err;
    EXPECT_NE(result_.err.find(std::string(file).ends_with(".eaf") ? "(ELAN)" : "(Label Studio)"),
              std::string::npos)
        << result_.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace tactile

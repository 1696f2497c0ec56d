// `tactile labels export --eaf / --label-studio` and `labels import FILE.eaf / FILE.json`: the
// binary run as a user would, on a store with every kind of lane and on the hand-written files
// of tests/data/interop.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
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
  // The quality choice beside the labels is named, not dropped in silence.
  EXPECT_EQ(result_.out, "imported 5 labels into " + other +
                             "; left out what is no time span: 1 choices from 'quality'\n");
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

// Label Studio's import refuses a completed_by that is no member of the project: members are
// mapped by name, the others have none, and our own import still knows every name.
TEST_F(LabelsInteropCommandTest, LabelStudioExportGivesCompletedByToMappedMembersOnly) {
  const std::string json = (directory_ / "tasks.json").string();
  ASSERT_EQ(run("labels export '" + database_ + "' --label-studio '" + json +
                "' --member ana=7 --member protocol=lead@lab.org"),
            0)
      << result_.err;
  const nlohmann::json tasks = nlohmann::json::parse(test::read_text(json));
  std::vector<std::string> written;
  for (const nlohmann::json& task : tasks)
    for (const nlohmann::json& annotation : task["annotations"])
      written.push_back(annotation["tactile_annotator"].get<std::string>() + ":" +
                        (annotation.contains("completed_by") ? annotation["completed_by"].dump()
                                                             : std::string("-")));
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written,
            (std::vector<std::string>{"ana:7", "ben:-", "protocol:{\"email\":\"lead@lab.org\"}"}));
  const std::string copy = (directory_ / "copy.db").string();
  ASSERT_EQ(run("labels import '" + copy + "' '" + json + "'"), 0) << result_.err;
  EXPECT_EQ(store_content_of(copy), store_content_of(database_));
  EXPECT_EQ(run("labels export '" + database_ + "' --label-studio '" + json + "' --member anna=7"),
            1);
  EXPECT_NE(result_.err.find("--member: 'anna' is no annotator of the labels exported (ana, "
                             "ben, protocol)"),
            std::string::npos)
      << result_.err;
  EXPECT_EQ(run("labels export '" + database_ + "' --eaf '" + json +
                "' --recording nao/s01 --member ana=7"),
            1);
  EXPECT_NE(result_.err.find("--member: only for --label-studio"), std::string::npos)
      << result_.err;
}

// A task as Label Studio's own time-series example writes it: no completed_by, start and end
// in epoch milliseconds (a time column of dates; Label Studio 1.x JSON export).
TEST_F(LabelsInteropCommandTest, LabelStudioExampleTaskOfDatesImportsWithNoneAndTheStart) {
  const std::string json = (directory_ / "example.json").string();
  std::ofstream(json) << R"([{"id": 1, "data": {"csv_url": "/data/upload/1/a1b2c3d4-s07.csv"},
    "annotations": [{"result": [
      {"value": {"start": 1592250751951.8074, "end": 1592251071946.638, "instant": false,
                 "timeserieslabels": ["Run"]},
       "id": "S1DkU7FSku", "from_name": "label", "to_name": "ts", "type": "timeserieslabels"}]}],
    "predictions": []}])";
  const std::string copy = (directory_ / "copy.db").string();
  EXPECT_EQ(run("labels import '" + copy + "' '" + json + "'"), 1);
  EXPECT_NE(result_.err.find("task 1 annotation 1: no completed_by: map it with --annotator "
                             "none=NAME"),
            std::string::npos)
      << result_.err;
  EXPECT_EQ(run("labels import '" + copy + "' '" + json + "' --annotator none=ana"), 1);
  EXPECT_NE(result_.err.find("result 'S1DkU7FSku': start 1592250751951.8074 is in epoch "
                             "milliseconds"),
            std::string::npos)
      << result_.err;
  EXPECT_NE(result_.err.find("(no " + (directory_ / "s07.h5").string()), std::string::npos)
      << result_.err;
  EXPECT_NE(result_.err.find("give --start-ms"), std::string::npos) << result_.err;
  EXPECT_FALSE(std::filesystem::exists(copy));
  ASSERT_EQ(run("labels import '" + copy + "' '" + json +
                "' --annotator none=ana --start-ms 1592250751000"),
            0)
      << result_.err;
  EXPECT_EQ(store_content_of(copy), "s07|0.951807|320.946638|all|Run|ana|manual|1.000000|\n");
  // With the recording beside the store on a Unix clock, its start is known.
  Recording recording;
  recording.id = "s07";
  recording.layout_id = "grid:1x1";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 10.0;
  stream.start_time = 1592250750.0;
  stream.channels = {"c0"};
  stream.units = {""};
  stream.samples = SampleMatrix::Zero(3300, 1);  // 330 s: the labels must lie inside it
  recording.streams.push_back(std::move(stream));
  write_recording((directory_ / "s07.h5").string(), recording);
  const std::string other = (directory_ / "other.db").string();
  ASSERT_EQ(run("labels import '" + other + "' '" + json + "' --annotator none=ground-truth"), 0)
      << result_.err;
  EXPECT_EQ(store_content_of(other),
            "s07|1592250751.951807|1592251071.946638|all|Run||ground-truth|1.000000|\n");
  EXPECT_EQ(run("labels import '" + other + "' '" + json + "' --start-ms soon"), 1);
  EXPECT_NE(result_.err.find("--start-ms: 'soon' is not a Unix time in milliseconds"),
            std::string::npos)
      << result_.err;
}

// An audio project's regions (Label Studio 1.x JSON export, <Labels> over <Audio>) are spans in
// seconds; a project of image boxes only holds no label and is refused by what it holds.
TEST_F(LabelsInteropCommandTest, LabelStudioAudioRegionsImportAndBoxesAloneAreRefused) {
  const std::string audio = (directory_ / "audio.json").string();
  std::ofstream(audio) << R"([{"id": 7, "data": {"audio": "/data/upload/2/0f1e2d3c-s09.wav"},
    "annotations": [{"id": 31, "completed_by": 1, "result": [
      {"value": {"start": 1.25, "end": 3.75, "channel": 0, "labels": ["stroke"]},
       "id": "wavesurfer_4qkd", "from_name": "label", "to_name": "audio", "type": "labels"},
      {"value": {"choices": ["clean"]}, "id": "q1", "from_name": "quality", "to_name": "audio",
       "type": "choices"}]}]}])";
  const std::string copy = (directory_ / "copy.db").string();
  ASSERT_EQ(run("labels import '" + copy + "' '" + audio + "' --annotator 1=ana"), 0)
      << result_.err;
  EXPECT_EQ(result_.out, "imported 1 label into " + copy +
                             "; left out what is no time span: 1 choices from 'quality'\n");
  EXPECT_EQ(store_content_of(copy), "s09|1.250000|3.750000|all|stroke|ana|manual|1.000000|\n");
  const std::string boxes = (directory_ / "boxes.json").string();
  std::ofstream(boxes) << R"([{"id": 8, "data": {"image": "/data/upload/2/frame.png"},
    "annotations": [{"id": 32, "completed_by": 1, "result": [
      {"value": {"x": 10, "y": 20, "width": 30, "height": 40, "rectanglelabels": ["hand"]},
       "id": "b1", "from_name": "box", "to_name": "frame", "type": "rectanglelabels"}]}]}])";
  EXPECT_EQ(run("labels import '" + copy + "' '" + boxes + "'"), 1);
  EXPECT_NE(result_.err.find("boxes.json: no time spans, only 1 result of other controls (1 "
                             "rectanglelabels from 'box')"),
            std::string::npos)
      << result_.err;
}

}  // namespace
}  // namespace tactile

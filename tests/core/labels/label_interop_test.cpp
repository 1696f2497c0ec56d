// ELAN .eaf and Label Studio JSON, both ways: hand-written files of those tools read value by
// value, our exports read back equal, malformed elements refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "label_store_fixture.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/elan_and_label_studio.h"
#include "tactile/labels/label_file_commands.h"
#include "tactile/labelstore/label_store.h"
#include "temp_folder.h"
#include "test_paths.h"

namespace tactile {
namespace {

const std::string kInteropData = test::test_data_dir() + "/interop/";

// Every lane a store holds: ground truth, two annotators, a segmenter, a model; regions,
// notes with awkward text, confidences, times that are not whole milliseconds apart.
std::vector<Label> every_lane() {
  auto label = [](double t0, double t1, const std::string& class_name, const std::string& annotator,
                  LabelSource source) {
    Label made;
    made.recording = "nao/s01";
    made.t0 = t0;
    made.t1 = t1;
    made.class_name = class_name;
    made.annotator = annotator;
    made.source = source;
    return made;
  };
  std::vector<Label> labels;
  labels.push_back(label(0.5, 1.25, "stroke", "protocol", LabelSource::kGroundTruth));
  labels.back().region = "head";
  labels.push_back(label(0.512, 1.3, "stroke", "ana", LabelSource::kManual));
  labels.back().note = "two fingers, <light> & \"slow\"\nthen stop";
  labels.push_back(label(2.0, 2.25, "poke", "ana", LabelSource::kManual));
  labels.push_back(label(0.498, 1.27, "pat", "ben", LabelSource::kManual));
  labels.back().confidence = 0.5;
  labels.push_back(
      label(0.49, 1.31, kUnknownClass, "segmenter:threshold", LabelSource::kSegmenter));
  labels.back().confidence = 0.875;
  labels.push_back(label(2.001, 2.249, "poke", "svm", LabelSource::kModel));
  labels.back().confidence = 0.64;
  labels.back().region = "back";
  return labels;
}

// Labels compared as the store lists them (recording, t0, id), every field but the store's.
void expect_same_labels(const std::vector<Label>& expected, const std::vector<Label>& actual,
                        double time_tolerance) {
  ASSERT_EQ(expected.size(), actual.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    SCOPED_TRACE("label " + std::to_string(k));
    EXPECT_EQ(actual[k].recording, expected[k].recording);
    EXPECT_NEAR(actual[k].t0, expected[k].t0, time_tolerance);
    EXPECT_NEAR(actual[k].t1, expected[k].t1, time_tolerance);
    EXPECT_EQ(actual[k].region, expected[k].region);
    EXPECT_EQ(actual[k].class_name, expected[k].class_name);
    EXPECT_EQ(actual[k].annotator, expected[k].annotator);
    EXPECT_EQ(actual[k].source, expected[k].source);
    EXPECT_EQ(actual[k].confidence, expected[k].confidence);
    EXPECT_EQ(actual[k].note, expected[k].note);
  }
}

//---- ELAN

TEST_F(LabelStoreTest, ElanSessionOfTwoAnnotatorsIsReadValueByValue) {
  const std::vector<Label> labels =
      parse_eaf(read_text(kInteropData + "session.eaf"), "session.eaf");
  ASSERT_EQ(labels.size(), 5u);
  // Tier "Touch (Ana)": not a lane id, so its ANNOTATOR; the recording from the media's name.
  EXPECT_EQ(labels[0].recording, "s07");
  EXPECT_EQ(labels[0].annotator, "ana");
  EXPECT_EQ(labels[0].source, LabelSource::kManual);
  EXPECT_EQ(labels[0].class_name, "stroke");
  EXPECT_DOUBLE_EQ(labels[0].t0, 0.12);
  EXPECT_DOUBLE_EQ(labels[0].t1, 0.87);
  EXPECT_EQ(labels[1].class_name, "pat");
  EXPECT_DOUBLE_EQ(labels[1].t0, 1.5);
  EXPECT_DOUBLE_EQ(labels[1].t1, 2.25);
  EXPECT_EQ(labels[2].annotator, "ben");
  EXPECT_DOUBLE_EQ(labels[2].t0, 0.14);
  EXPECT_DOUBLE_EQ(labels[2].t1, 0.905);
  EXPECT_EQ(labels[2].note, "");
  // The comments tier depends on Ben's tier: its text is the note of annotation a4.
  EXPECT_EQ(labels[3].class_name, "poke");
  EXPECT_DOUBLE_EQ(labels[3].t0, 3.001);
  EXPECT_DOUBLE_EQ(labels[3].t1, 3.999);
  EXPECT_EQ(labels[3].note, "very short, maybe a tap");
  // The tier named "ground-truth" is the ground truth lane; its region from "ground-truth/region".
  EXPECT_EQ(labels[4].source, LabelSource::kGroundTruth);
  EXPECT_EQ(labels[4].annotator, "protocol");
  EXPECT_EQ(labels[4].region, "head");
  EXPECT_EQ(labels[3].region, "all");
  for (const Label& label : labels) EXPECT_EQ(label.confidence, 1.0);
}

TEST_F(LabelStoreTest, ElanTiersChosenByNameAreMappedToLanes) {
  InteropImport options;
  options.recording = "nao/s07";
  options.tiers = {{"Touch (Ben)", "model:ben-model"}, {"Touch (Ana)", "ground-truth"}};
  const std::vector<Label> labels =
      parse_eaf(read_text(kInteropData + "session.eaf"), "session.eaf", options);
  ASSERT_EQ(labels.size(), 4u);  // the "ground-truth" tier was not chosen
  EXPECT_EQ(labels[0].source, LabelSource::kGroundTruth);
  EXPECT_EQ(labels[0].recording, "nao/s07");
  EXPECT_EQ(labels[2].source, LabelSource::kModel);
  EXPECT_EQ(labels[2].annotator, "ben-model");
  EXPECT_EQ(labels[3].note, "very short, maybe a tap");
  options.tiers = {{"Touch (Carl)", ""}};
  EXPECT_EQ(test::refusal_of(
                [&] { parse_eaf(read_text(kInteropData + "session.eaf"), "s.eaf", options); }),
            "s.eaf: no tier named 'Touch (Carl)' (--tier)");
}

TEST_F(LabelStoreTest, InteropSourcesListTiersAndAnnotatorsWithTheirLanesAndCounts) {
  auto text = [](const InteropSources& found) {
    std::string listed = found.recording + ":";
    for (const InteropSource& source : found.sources)
      listed +=
          " [" + source.name + " -> " + source.lane + " " + std::to_string(source.labels) + "]";
    return listed;
  };
  // Dependent tiers (comments, regions) are not sources of labels.
  EXPECT_EQ(text(eaf_sources(read_text(kInteropData + "session.eaf"), "session.eaf")),
            "s07: [Touch (Ana) -> ana 2] [Touch (Ben) -> ben 2] [ground-truth -> ground-truth 1]");
  // User 2 gave the ground truth of task 41 and a plain annotation of task 42; the cancelled
  // annotation and the choices result count for nothing.
  EXPECT_EQ(text(label_studio_sources(read_text(kInteropData + "label_studio.json"), "ls.json")),
            "s07,s08: [1 -> manual:label-studio:1 2] [2 -> ground-truth 1]"
            " [svm-2024-04 -> model:svm-2024-04 1] [2 -> manual:label-studio:2 1]");
  EXPECT_EQ(test::refusal_of([] { eaf_sources("<a/>", "x.eaf"); }),
            "x.eaf: expected an ELAN document (ANNOTATION_DOCUMENT)");
}

TEST_F(LabelStoreTest, ElanUnalignedAnnotationIsRefusedNamingTierAndId) {
  EXPECT_EQ(
      test::refusal_of([&] { parse_eaf(read_text(kInteropData + "unaligned.eaf"), "u.eaf"); }),
      "u.eaf tier 'Touch (Ben)' annotation 'a4': unaligned: time slot 'ts9' has no time "
      "value (align it in ELAN first)");
}

TEST_F(LabelStoreTest, ElanExportOfEveryLaneReadsBackEqualToTheMillisecond) {
  const std::vector<Label> labels = every_lane();
  const std::string eaf = labels_eaf(labels, {"pat", "poke", "stroke", "tap"});
  // A tier per lane, the vocabulary with the classes beyond it, dependent tiers.
  for (const char* part :
       {"TIER_ID=\"ground-truth\"", "TIER_ID=\"manual:ana\"", "TIER_ID=\"manual:ben\"",
        "TIER_ID=\"segmenter:threshold\"", "TIER_ID=\"model:svm\"",
        "PARENT_REF=\"manual:ana\" TIER_ID=\"manual:ana/note\"", "TIER_ID=\"ground-truth/region\"",
        "TIER_ID=\"manual:ben/confidence\"",
        "<CVE_VALUE DESCRIPTION=\"\" LANG_REF=\"eng\">tap</CVE_VALUE>",
        "<CVE_VALUE DESCRIPTION=\"\" LANG_REF=\"eng\">unknown</CVE_VALUE>",
        "CONSTRAINTS=\"Symbolic_Association\""})
    EXPECT_NE(eaf.find(part), std::string::npos) << part;
  std::vector<Label> read = parse_eaf(eaf, "export.eaf");
  // Both sides in the store's order.
  LabelStore first((directory_ / "a.db").string()), second((directory_ / "b.db").string());
  first.add_many(labels);
  second.add_many(read);
  expect_same_labels(first.list(), second.list(), 0.0005);
  // Times on a millisecond come back exactly.
  EXPECT_EQ(second.list().front().t0, 0.49);
}

TEST_F(LabelStoreTest, ElanExportOfUnixTimesKeepsThemThroughAnOrigin) {
  std::vector<Label> labels = every_lane();
  for (Label& label : labels) {
    label.t0 += 1714550400.0;
    label.t1 += 1714550400.0;
  }
  const std::string eaf = labels_eaf(labels);
  EXPECT_NE(eaf.find("<PROPERTY NAME=\"tactile:time-origin\">1714550400</PROPERTY>"),
            std::string::npos);
  const std::vector<Label> read = parse_eaf(eaf, "unix.eaf");
  ASSERT_EQ(read.size(), labels.size());
  double worst = 0.0;
  for (const Label& label : read) {
    bool found = false;
    for (const Label& original : labels)
      if (original.annotator == label.annotator && std::abs(original.t0 - label.t0) < 0.0005 &&
          std::abs(original.t1 - label.t1) < 0.0005)
        found = true;
    EXPECT_TRUE(found) << label.annotator << " " << label.t0;
    worst = std::max(worst, label.t0);
  }
  EXPECT_GT(worst, 1714550400.0);
}

TEST_F(LabelStoreTest, ElanRefusesALabelShorterThanAMillisecondAndTwoRecordings) {
  std::vector<Label> labels = every_lane();
  labels[1].t1 = labels[1].t0 + 0.0002;
  labels[1].id = 7;
  EXPECT_EQ(test::refusal_of([&] { labels_eaf(labels); }),
            "ELAN export label 7: spans less than a millisecond (0.512-0.5122 s): ELAN counts "
            "whole milliseconds");
  labels = every_lane();
  labels[2].recording = "nao/s02";
  EXPECT_NE(test::refusal_of([&] { labels_eaf(labels); }).find("one .eaf holds one recording"),
            std::string::npos);
}

TEST_F(LabelStoreTest, ElanMalformedDocumentsAreRefusedByPlace) {
  EXPECT_NE(test::refusal_of([] {
              parse_eaf("<ANNOTATION_DOCUMENT><TIER>", "x.eaf");
            }).find("x.eaf:1: not XML"),
            std::string::npos);
  EXPECT_EQ(test::refusal_of([] { parse_eaf("<DOC/>", "x.eaf"); }),
            "x.eaf: expected an ELAN document (ANNOTATION_DOCUMENT)");
  const std::string head =
      "<ANNOTATION_DOCUMENT><HEADER><PROPERTY NAME=\"tactile:recording\">r</PROPERTY></HEADER>"
      "<TIME_ORDER><TIME_SLOT TIME_SLOT_ID=\"ts1\" TIME_VALUE=\"500\"/>"
      "<TIME_SLOT TIME_SLOT_ID=\"ts2\" TIME_VALUE=\"100\"/></TIME_ORDER><TIER TIER_ID=\"ana\">"
      "<ANNOTATION><ALIGNABLE_ANNOTATION ANNOTATION_ID=\"a9\" TIME_SLOT_REF1=\"ts1\" ";
  EXPECT_EQ(test::refusal_of([&] {
              parse_eaf(head +
                            "TIME_SLOT_REF2=\"ts2\"><ANNOTATION_VALUE>pat</ANNOTATION_VALUE>"
                            "</ALIGNABLE_ANNOTATION></ANNOTATION></TIER></ANNOTATION_DOCUMENT>",
                        "x.eaf");
            }),
            "x.eaf tier 'ana' annotation 'a9': ends at 0.1 s, not after its start 0.5 s");
  EXPECT_EQ(test::refusal_of([&] {
              parse_eaf(head +
                            "TIME_SLOT_REF2=\"ts7\"><ANNOTATION_VALUE>pat</ANNOTATION_VALUE>"
                            "</ALIGNABLE_ANNOTATION></ANNOTATION></TIER></ANNOTATION_DOCUMENT>",
                        "x.eaf");
            }),
            "x.eaf tier 'ana' annotation 'a9': time slot 'ts7' is not in the TIME_ORDER");
  InteropImport named;
  named.recording = "r";
  EXPECT_EQ(test::refusal_of([&] {
              parse_eaf(
                  "<ANNOTATION_DOCUMENT><TIME_ORDER><TIME_SLOT TIME_SLOT_ID=\"ts1\" "
                  "TIME_VALUE=\"-4\"/></TIME_ORDER></ANNOTATION_DOCUMENT>",
                  "x.eaf", named);
            }),
            "x.eaf time slot 'ts1' (line 1): TIME_VALUE '-4' is not a whole number of "
            "milliseconds in 0..4294967295");
}

//---- Label Studio

TEST_F(LabelStoreTest, LabelStudioExportOfTwoTasksIsReadValueByValue) {
  InteropImport options;
  options.annotators = {{"1", "ana"}};
  const std::vector<Label> labels =
      parse_label_studio(read_text(kInteropData + "label_studio.json"), "ls.json", options);
  // The cancelled annotation and the choices result are not labels.
  ASSERT_EQ(labels.size(), 5u);
  EXPECT_EQ(labels[0].recording, "s07");
  EXPECT_EQ(labels[0].annotator, "ana");
  EXPECT_EQ(labels[0].source, LabelSource::kManual);
  EXPECT_EQ(labels[0].class_name, "stroke");
  EXPECT_EQ(labels[0].t0, 0.12);
  EXPECT_EQ(labels[0].t1, 0.87);
  EXPECT_EQ(labels[1].class_name, "pat");
  EXPECT_EQ(labels[1].note, "light, two fingers");
  EXPECT_EQ(labels[1].t1, 2.25);
  // User 2's ground truth annotation: ground truth, the user named as Label Studio's.
  EXPECT_EQ(labels[2].source, LabelSource::kGroundTruth);
  EXPECT_EQ(labels[2].annotator, "label-studio:2");
  EXPECT_EQ(labels[2].t0, 0.1405);
  // The prediction: a model, its result's score as the confidence.
  EXPECT_EQ(labels[3].source, LabelSource::kModel);
  EXPECT_EQ(labels[3].annotator, "svm-2024-04");
  EXPECT_EQ(labels[3].confidence, 0.64);
  EXPECT_EQ(labels[3].t0, 3.001);
  // The second task: its own recording, user 2 not mapped.
  EXPECT_EQ(labels[4].recording, "s08");
  EXPECT_EQ(labels[4].annotator, "label-studio:2");
  EXPECT_EQ(labels[4].source, LabelSource::kManual);
  EXPECT_EQ(labels[4].t0, 10.25);
  EXPECT_EQ(labels[4].t1, 11.0);
}

TEST_F(LabelStoreTest, LabelStudioExportOfEveryLaneReadsBackExactly) {
  std::vector<Label> labels = every_lane();
  Label other = labels[1];
  other.recording = "nao/s02";
  other.t0 = 0.1 + 0.2;  // not a short decimal
  other.t1 = 1.0 / 3.0;
  labels.push_back(other);
  const std::string json = labels_label_studio(labels);
  ASSERT_TRUE(is_label_studio_json(json));
  const std::vector<Label> read = parse_label_studio(json, "export.json");
  LabelStore first((directory_ / "a.db").string()), second((directory_ / "b.db").string());
  first.add_many(labels);
  second.add_many(read);
  expect_same_labels(first.list(), second.list(), 0.0);
}

TEST_F(LabelStoreTest, LabelStudioMalformedResultsAreRefusedNamingTaskAndId) {
  const std::string task = R"([{"id": 5, "data": {"csv": "r.csv"}, "annotations": [{"id": 9,
      "completed_by": 1, "result": [{"id": "abc", "type": "timeserieslabels", "value": )";
  EXPECT_EQ(test::refusal_of([&] {
              parse_label_studio(task + R"({"start": 1, "end": 1, "instant": true,
                  "timeserieslabels": ["pat"]}}]}]}])",
                                 "ls.json");
            }),
            "ls.json task 5 annotation 9 result 'abc': an instant, not a span: a label needs a "
            "start and an end");
  EXPECT_EQ(test::refusal_of([&] {
              parse_label_studio(task + R"({"start": "2024-05-01 10:00:00", "end": 2,
                  "timeserieslabels": ["pat"]}}]}]}])",
                                 "ls.json");
            }),
            "ls.json task 5 annotation 9 result 'abc': 'start' is not a number (a time column "
            "of dates? give times in seconds)");
  EXPECT_EQ(test::refusal_of([&] {
              parse_label_studio(task + R"({"start": 1, "end": 2,
                  "timeserieslabels": ["pat", "poke"]}}]}]}])",
                                 "ls.json");
            }),
            "ls.json task 5 annotation 9 result 'abc': 'timeserieslabels' must hold exactly one "
            "label name");
  EXPECT_EQ(test::refusal_of([] { parse_label_studio(R"([{"id": 3, "data": {}}])", "ls.json"); }),
            "ls.json task 3: its data names no file: give --recording");
  EXPECT_FALSE(is_label_studio_json(R"({"labels": []})"));
}

//---- Label Studio as it writes its own files

// A task of Label Studio 1.x's JSON export of a TimeSeries project whose time column holds
// dates: the results are those of Label Studio's time-series documentation ("Output format
// example" of the Time Series Labeling template), start and end in epoch milliseconds, and
// like its example tasks the annotation has no completed_by. The CSV's name is an upload's.
std::string studio_dates_task(
    const std::string& annotation_keys = "",
    const std::string& data = R"({"csv_url": "/data/upload/1/a1b2c3d4-s07.csv"})") {
  return R"([{"id": 1, "data": )" + data + R"(, "annotations": [{)" + annotation_keys +
         R"("result": [
    {"value": {"start": 1592250751951.8074, "end": 1592251071946.638, "instant": false,
               "timeserieslabels": ["Run"]},
     "id": "S1DkU7FSku", "from_name": "label", "to_name": "ts", "type": "timeserieslabels"},
    {"value": {"start": 1592251231975.601, "end": 1592251461993.5276, "instant": false,
               "timeserieslabels": ["Run"]},
     "id": "XvagJo87mr", "from_name": "label", "to_name": "ts", "type": "timeserieslabels"}]}],
    "predictions": []}])";
}

TEST_F(LabelStoreTest, LabelStudioTaskWithoutCompletedByIsRefusedUntilNoneIsMapped) {
  EXPECT_EQ(test::refusal_of([] {
              InteropImport known;
              known.start_ms = 1592250751000.0;
              parse_label_studio(studio_dates_task(), "ls.json", known);
            }),
            "ls.json task 1 annotation 1: no completed_by: map it with --annotator none=NAME (a "
            "name, or a lane: ground-truth, model:NAME, ...)");
  InteropImport options;
  options.start_ms = 1592250751000.0;
  options.annotators = {{"none", "ana"}};
  std::vector<Label> labels = parse_label_studio(studio_dates_task(), "ls.json", options);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].annotator, "ana");
  EXPECT_EQ(labels[0].source, LabelSource::kManual);
  EXPECT_EQ(labels[0].recording, "s07");
  // A lane: the ground truth (which needs no person).
  options.annotators = {{"none", "ground-truth"}};
  labels = parse_label_studio(studio_dates_task(), "ls.json", options);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[1].source, LabelSource::kGroundTruth);
  EXPECT_EQ(labels[1].annotator, "");
  // "none" maps only annotations that name nobody: a user stays who it is.
  options.annotators = {{"none", "ana"}};
  labels = parse_label_studio(studio_dates_task(R"("completed_by": 4, )"), "ls.json", options);
  EXPECT_EQ(labels[0].annotator, "label-studio:4");
  // Listed for the workbench's dialog as "none", with no lane until one is typed.
  const InteropSources sources = label_studio_sources(studio_dates_task(), "ls.json");
  ASSERT_EQ(sources.sources.size(), 1u);
  EXPECT_EQ(sources.sources[0].name, "none");
  EXPECT_EQ(sources.sources[0].lane, "");
  EXPECT_EQ(sources.sources[0].labels, 2u);
}

TEST_F(LabelStoreTest, LabelStudioEpochMillisecondsArePlacedOnTheRecordingsClock) {
  InteropImport options;
  options.annotators = {{"none", "ana"}};
  // Nothing says when the recording started: refused naming the label and what to give.
  EXPECT_EQ(test::refusal_of([&] { parse_label_studio(studio_dates_task(), "ls.json", options); }),
            "ls.json task 1 annotation 1 result 'S1DkU7FSku': start 1592250751951.8074 is in "
            "epoch milliseconds (a TimeSeries whose time column holds dates), and the start of "
            "recording 's07' is not known (no recording file was looked for, and the task's "
            "data holds no column of epoch milliseconds): give --start-ms, the Unix time in "
            "milliseconds of its first sample");
  // --start-ms: the first sample's Unix time; a recording of its own clock starts at 0.
  options.start_ms = 1592250751000.0;
  std::vector<Label> labels = parse_label_studio(studio_dates_task(), "ls.json", options);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NEAR(labels[0].t0, 0.9518074, 1e-6);
  EXPECT_NEAR(labels[0].t1, 320.946638, 1e-6);
  EXPECT_NEAR(labels[1].t0, 480.975601, 1e-6);
  EXPECT_NEAR(labels[1].t1, 710.9935276, 1e-6);
  // The recording's own start: its first sample at 2.5 s on its clock is 1592250750000 ms.
  options.start_ms.reset();
  options.clock = [](const std::string& recording) {
    RecordingClock clock;
    clock.found = recording == "s07";
    clock.first_sample = 2.5;
    clock.start_ms = 1592250750000.0;
    return clock;
  };
  labels = parse_label_studio(studio_dates_task(), "ls.json", options);
  EXPECT_NEAR(labels[0].t0, 4.4518074, 1e-6);
  // --start-ms goes before it.
  options.start_ms = 1592250751000.0;
  labels = parse_label_studio(studio_dates_task(), "ls.json", options);
  EXPECT_NEAR(labels[0].t0, 3.4518074, 1e-6);
  // The task's first time value, when the task holds its series (valueType="json").
  options.start_ms.reset();
  options.clock = [](const std::string&) {
    RecordingClock clock;
    clock.found = true;
    clock.file = "ws/s07.h5";
    clock.missing = "starts at 0 s on a clock of its own and has no start_time";
    return clock;
  };
  labels = parse_label_studio(
      studio_dates_task("", R"({"recording": "s07", "ts": {"time": [1592250750951.8074,
          1592250750961.8074], "c0": [0.5, 0.25]}})"),
      "ls.json", options);
  EXPECT_NEAR(labels[0].t0, 1.0, 1e-6);
  EXPECT_NEAR(labels[1].t1, 711.0417202, 1e-6);
  // Without it, the recording file's reason is named.
  EXPECT_NE(test::refusal_of([&] { parse_label_studio(studio_dates_task(), "ls.json", options); })
                .find("(ws/s07.h5 starts at 0 s on a clock of its own and has no start_time, and "
                      "the task's data holds no column of epoch milliseconds)"),
            std::string::npos);
  // One end in milliseconds and the other not: refused.
  const std::string task =
      R"([{"id": 2, "data": {"recording": "r"}, "annotations": [{"completed_by": 1, "result": [
      {"id": "m", "type": "timeserieslabels", "value": {"start": 1592250751951.8, "end": 3,
      "timeserieslabels": ["pat"]}}]}]}])";
  EXPECT_EQ(test::refusal_of([&] { parse_label_studio(task, "ls.json", options); }),
            "ls.json task 2 annotation 1 result 'm': start 1592250751951.8 and end 3 are not "
            "both epoch milliseconds");
}

TEST_F(LabelStoreTest, RecordingClockIsTheRecordingsUnixClockOrItsStartTimeWithAZone) {
  auto write = [&](const std::string& id, double start_time, const Metadata& metadata) {
    Recording recording;
    recording.id = id;
    recording.layout_id = "grid:1x1";
    recording.metadata = metadata;
    Stream stream;
    stream.name = "skin";
    stream.rate_hz = 10.0;
    stream.start_time = start_time;
    stream.channels = {"c0"};
    stream.units = {""};
    stream.samples = SampleMatrix::Zero(8000, 1);  // 800 s: the labels lie inside it
    recording.streams.push_back(std::move(stream));
    write_recording((directory_ / (id + ".h5")).string(), recording);
  };
  const std::string folder = directory_.string();
  // A recording on a Unix clock (a sender's stamps): its first sample is its start.
  write("unix", 1592250750.5, {});
  RecordingClock clock = recording_clock(folder, "unix");
  EXPECT_TRUE(clock.found);
  EXPECT_EQ(clock.first_sample, 1592250750.5);
  ASSERT_TRUE(clock.start_ms);
  EXPECT_EQ(*clock.start_ms, 1592250750500.0);
  // Its own clock from 0, and a start_time with a zone.
  write("zoned", 0.0, {{"start_time", "2020-06-15T21:52:30.5+02:00"}});
  clock = recording_clock(folder, "zoned");
  ASSERT_TRUE(clock.start_ms);
  EXPECT_EQ(*clock.start_ms, 1592250750500.0);
  EXPECT_EQ(clock.first_sample, 0.0);
  // EDF's start_time is the recorder's local time: no zone, so no Unix time.
  write("edf", 0.0, {{"start_time", "2020-06-15T19:52:30"}});
  clock = recording_clock(folder, "edf");
  EXPECT_TRUE(clock.found);
  EXPECT_FALSE(clock.start_ms);
  EXPECT_EQ(clock.missing,
            "has start_time '2020-06-15T19:52:30', not an ISO 8601 date-time with a time zone "
            "(EDF gives the recorder's local time, which names none)");
  write("own", 3.0, {});
  EXPECT_EQ(recording_clock(folder, "own").missing,
            "starts at 3 s on a clock of its own and has no start_time");
  EXPECT_FALSE(recording_clock(folder, "absent").found);
  EXPECT_EQ(recording_clock(folder, "absent").file, (directory_ / "absent.h5").string());
  EXPECT_EQ(unix_milliseconds("2020-06-15T19:52:31.951Z"), 1592250751951.0);
  EXPECT_EQ(unix_milliseconds("2020-06-15 14:52:31-0500"), 1592250751000.0);
  EXPECT_EQ(unix_milliseconds("1969-12-31T23:59:59Z"), -1000.0);
  EXPECT_FALSE(unix_milliseconds("2020-06-15T19:52:31"));
  EXPECT_FALSE(unix_milliseconds("2020-13-15T19:52:31Z"));
  EXPECT_FALSE(unix_milliseconds("15.06.2020 19:52:31 UTC"));
  // import_label_file looks in the store's folder: the recording's Unix clock places them.
  const std::string file = (directory_ / "tasks.json").string();
  std::ofstream(file) << studio_dates_task("",
                                           R"({"csv_url": "/data/upload/1/a1b2c3d4-unix.csv"})");
  InteropImport options;
  options.annotators = {{"none", "ana"}};
  const LabelImport imported = import_label_file(path_, file, options);
  EXPECT_EQ(imported.added, 2u);
  EXPECT_TRUE(imported.left_out.empty());
  const std::vector<Label> stored = LabelStore(path_).list();
  ASSERT_EQ(stored.size(), 2u);
  EXPECT_EQ(stored[0].recording, "unix");
  EXPECT_NEAR(stored[0].t0, 1592250751.9518074, 1e-6);
}

// Label Studio 1.x's JSON export of an audio project (<Labels> over <Audio>): each region a
// "labels" result in seconds with its channel; beside it a Choices control, a text's named
// entity (a "labels" result over <Text>: character offsets with the text) and an image box.
TEST_F(LabelStoreTest, LabelStudioAudioRegionsAreSpansAndOtherControlsAreCountedByKind) {
  const std::string audio = R"([{"id": 7, "data": {"audio": "/data/upload/2/0f1e2d3c-s09.wav"},
    "annotations": [{"id": 31, "completed_by": 1, "ground_truth": false, "was_cancelled": false,
      "result": [
        {"value": {"start": 1.225, "end": 3.7, "channel": 0, "labels": ["stroke"]},
         "id": "wavesurfer_4qkd", "from_name": "label", "to_name": "audio", "type": "labels",
         "origin": "manual"},
        {"value": {"start": 5.5, "end": 6.125, "channel": 0, "labels": ["pat"]},
         "id": "wavesurfer_9xa1", "from_name": "label", "to_name": "audio", "type": "labels",
         "origin": "manual", "meta": {"text": ["soft"]}},
        {"value": {"choices": ["clean"]}, "id": "q1", "from_name": "quality",
         "to_name": "audio", "type": "choices", "origin": "manual"},
        {"value": {"choices": ["loud"]}, "id": "q2", "from_name": "quality",
         "to_name": "audio", "type": "choices", "origin": "manual"},
        {"value": {"start": 0, "end": 5, "text": "Touch", "labels": ["verb"]}, "id": "t1",
         "from_name": "ner", "to_name": "transcript", "type": "labels", "origin": "manual"},
        {"value": {"x": 10, "y": 20, "width": 30, "height": 40, "rotation": 0,
                   "rectanglelabels": ["hand"]}, "id": "b1", "from_name": "box",
         "to_name": "frame", "type": "rectanglelabels", "origin": "manual"}]}],
    "predictions": []}])";
  std::vector<std::string> left_out;
  const std::vector<Label> labels = parse_label_studio(audio, "audio.json", {}, &left_out);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].recording, "s09");
  EXPECT_EQ(labels[0].class_name, "stroke");
  EXPECT_EQ(labels[0].t0, 1.225);
  EXPECT_EQ(labels[0].t1, 3.7);
  EXPECT_EQ(labels[0].annotator, "label-studio:1");
  EXPECT_EQ(labels[1].class_name, "pat");
  EXPECT_EQ(labels[1].note, "soft");
  EXPECT_EQ(left_out,
            (std::vector<std::string>{"2 choices from 'quality'",
                                      "1 labels from 'ner' (spans of a text, not of time)",
                                      "1 rectanglelabels from 'box'"}));
  // Audio regions count as the annotator's labels in the dialog's list.
  const InteropSources sources = label_studio_sources(audio, "audio.json");
  ASSERT_EQ(sources.sources.size(), 1u);
  EXPECT_EQ(sources.sources[0].labels, 2u);
  // A file of other controls only is refused, not read as "0 labels".
  const std::string boxes = R"([{"id": 8, "data": {"image": "/data/upload/2/frame.png"},
    "annotations": [{"id": 32, "completed_by": 1, "result": [
        {"value": {"x": 10, "y": 20, "width": 30, "height": 40,
                   "rectanglelabels": ["hand"]}, "id": "b1", "from_name": "box",
         "to_name": "frame", "type": "rectanglelabels"},
        {"value": {"ranges": [{"start": 3, "end": 40}], "timelinelabels": ["touch"]},
         "id": "v1", "from_name": "timeline", "to_name": "video", "type": "timelinelabels"}]}]}])";
  EXPECT_EQ(test::refusal_of([&] { parse_label_studio(boxes, "boxes.json"); }),
            "boxes.json: no time spans, only 2 results of other controls (1 rectanglelabels "
            "from 'box', 1 timelinelabels from 'timeline' (video frames, not seconds)): a label "
            "is a TimeSeriesLabels span or an Audio Labels region");
  // An audio region's time is seconds: one past 1e11 s is no audio's.
  const std::string far = R"([{"id": 9, "data": {"audio": "a.wav"}, "annotations": [{
      "completed_by": 1, "result": [{"id": "w", "type": "labels", "value": {"start": 2e11,
      "end": 3e11, "labels": ["pat"]}}]}]}])";
  EXPECT_EQ(test::refusal_of([&] { parse_label_studio(far, "far.json"); }),
            "far.json task 9 annotation 1 result 'w': a time of 2e+11 s is beyond any "
            "recording (times are seconds of the audio)");
}

TEST_F(LabelStoreTest, LabelStudioExportGivesCompletedByToMembersOnly) {
  const std::vector<Label> labels = every_lane();
  InteropExport options;
  options.members = {{"ana", "7"}, {"ben", "ben@lab.org"}};
  const nlohmann::json tasks = nlohmann::json::parse(labels_label_studio(labels, options));
  ASSERT_EQ(tasks.size(), 1u);
  std::map<std::string, nlohmann::json> by_name;
  for (const nlohmann::json& annotation : tasks[0]["annotations"])
    by_name[annotation["tactile_annotator"].get<std::string>()] = annotation;
  ASSERT_EQ(by_name.size(), 3u);
  // A user id as a number, an e-mail as Label Studio's import resolves it; nothing for the
  // unmapped "protocol" (Label Studio gives it to whoever imports).
  EXPECT_EQ(by_name["ana"]["completed_by"], 7);
  EXPECT_EQ(by_name["ben"]["completed_by"], (nlohmann::json{{"email", "ben@lab.org"}}));
  EXPECT_FALSE(by_name["protocol"].contains("completed_by"));
  // Our own import still gives each label its annotator.
  LabelStore first((directory_ / "a.db").string()), second((directory_ / "b.db").string());
  first.add_many(labels);
  second.add_many(parse_label_studio(labels_label_studio(labels, options), "export.json"));
  expect_same_labels(first.list(), second.list(), 0.0);
  // Nor an invented number without members.
  EXPECT_EQ(labels_label_studio(labels).find("completed_by"), std::string::npos);
  options.members = {{"anna", "7"}};
  EXPECT_EQ(test::refusal_of([&] { labels_label_studio(labels, options); }),
            "--member: 'anna' is no annotator of the labels exported (ana, ben, protocol)");
  options.members = {{"ana", "Ana"}};
  EXPECT_EQ(test::refusal_of([&] { labels_label_studio(labels, options); }),
            "--member: 'ana=Ana': a member is a Label Studio user id (a number) or e-mail");
}

//---- Into a store, all or nothing

TEST_F(LabelStoreTest, InteropImportAddsAllOrNothing) {
  EXPECT_EQ(import_label_file(path_, kInteropData + "session.eaf").added, 5u);
  EXPECT_THROW(import_label_file(path_, kInteropData + "unaligned.eaf"), Error);
  const LabelImport studio = import_label_file(path_, kInteropData + "label_studio.json");
  EXPECT_EQ(studio.added, 5u);
  EXPECT_EQ(studio.left_out, std::vector<std::string>{"1 choices from 'quality'"});
  EXPECT_EQ(imported_labels_line(studio, "labels.db"),
            "imported 5 labels into labels.db; left out what is no time span: 1 choices from "
            "'quality'");
  LabelStore store(path_);
  EXPECT_EQ(store.count(), 10);
  EXPECT_EQ(store.count("s08"), 1);
}

// The same file imported again changes nothing: each label the store holds already is left
// as it is and counted, so a second import of a session does not double its labels.
TEST_F(LabelStoreTest, ImportingTheSameLabelFileTwiceChangesNothing) {
  const LabelImport first = import_label_file(path_, kInteropData + "session.eaf");
  EXPECT_EQ(first.added, 5u);
  EXPECT_EQ(first.already, 0u);
  const LabelImport again = import_label_file(path_, kInteropData + "session.eaf");
  EXPECT_EQ(again.added, 0u);
  EXPECT_EQ(again.already, 5u);
  EXPECT_EQ(LabelStore(path_).count(), 5);
  EXPECT_EQ(imported_labels_line(again, "labels.db"),
            "imported 0 labels into labels.db; 5 already there, not added again");
}

// A recording beside the store (DB's folder/<id>.h5) bounds its labels: one that ends after
// the recording, or is shorter than one of its samples, refuses the whole file by name.
TEST_F(LabelStoreTest, ALabelOutsideItsRecordingBesideTheStoreRefusesTheFile) {
  Recording recording;
  recording.id = "session";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 100.0;
  skin.channels = {"ch0"};
  skin.units = {"V"};
  skin.samples = SampleMatrix::Zero(200, 1);  // 2 s
  recording.streams.push_back(skin);
  write_recording((directory_ / "session.h5").string(), recording);
  const auto file_with = [&](double t0, double t1) {
    const std::string path = (directory_ / "labels.csv").string();
    std::ofstream(path) << "id,recording,t0,t1,region,class,annotator,source,confidence,note,"
                           "created,modified\n"
                        << "1,session,0.5,1.0,all,pat,ana,manual,1,,,\n"
                        << "2,session," << t0 << "," << t1 << ",all,stroke,ana,manual,1,,,\n";
    return path;
  };
  try {
    import_label_file(path_, file_with(1.5, 2.5));
    ADD_FAILURE() << "a label ending at 2.5 s of a 2-s recording was imported";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("ends after its recording's end at 2.000 s"),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW(import_label_file(path_, file_with(1.5, 1.505)), Error);  // half a sample
  EXPECT_EQ(LabelStore(path_).count(), 0);                               // nothing of either file
  EXPECT_EQ(import_label_file(path_, file_with(1.5, 2.0)).added, 2u);    // to the last sample's end
}

}  // namespace
}  // namespace tactile

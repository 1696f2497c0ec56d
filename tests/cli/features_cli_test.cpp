// `tactile segment` and `tactile features`: grid recordings and labels built with the core
// API, the binary run as a user would.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"
#include "tactile/features/dataset.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/segment/segmenter.h"

namespace tactile {
namespace {

using test::CommandResult;

constexpr double kRate = 100.0;

// A 3 x 3 blob (1 at the centre, 0.5 around) on a 5 x 5 grid at `sample`.
void press(Stream& stream, int64_t sample, int64_t row, int64_t column) {
  for (int64_t dr = -1; dr <= 1; ++dr)
    for (int64_t dc = -1; dc <= 1; ++dc)
      stream.samples(sample, (row + dr) * 5 + column + dc) = (dr == 0 && dc == 0) ? 1.0f : 0.5f;
}

class FeaturesCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    database_ = folder_.file("labels.db");
    LabelStore store(database_);
    // Two subjects; each recording: presses (still) at 0.5 s and 2.5 s, swipes (moving
    // along row 2) at 1.5 s and 4.0 s, 0.6 s each.
    for (const std::string subject : {"s01", "s02"}) {
      const SkinLayout layout = make_grid_layout(5, 5);
      Recording recording;
      recording.id = "grid-" + subject;
      recording.layout_id = layout.id;
      recording.metadata = {{"subject", subject}, {"trial", "1"}, {"condition", "bench"}};
      Stream stream;
      stream.name = "skin";
      stream.rate_hz = kRate;
      for (const Channel& channel : layout.channels) {
        stream.channels.push_back(channel.name);
        stream.units.push_back(channel.unit);
      }
      stream.samples = SampleMatrix::Zero(600, 25);
      for (double start : {0.5, 2.5})
        for (int64_t sample = 0; sample < 60; ++sample)
          press(stream, static_cast<int64_t>(start * kRate) + sample, 2, 2);
      for (double start : {1.5, 4.0})
        for (int64_t sample = 0; sample < 60; ++sample)
          press(stream, static_cast<int64_t>(start * kRate) + sample, 2, 1 + sample / 20);
      recording.streams.push_back(std::move(stream));
      write_recording(folder_.file(recording.id + ".h5"), recording);
      for (const auto& [start, name] : std::vector<std::pair<double, std::string>>{
               {0.5, "press"}, {1.5, "swipe"}, {2.5, "press"}, {4.0, "swipe"}}) {
        Label label;
        label.recording = recording.id;
        label.t0 = start;
        label.t1 = start + 0.6;
        label.class_name = name;
        label.annotator = "test";
        label.source = LabelSource::kGroundTruth;
        store.add(label);
      }
    }
  }

  CommandResult tactile(const std::string& arguments) {
    return test::run_program("tactile", arguments, folder_);
  }
  std::string quoted(const std::string& name) const { return "'" + folder_.file(name) + "'"; }
  std::string features(const std::string& out, const std::string& more = {}) const {
    return "features --pipeline generic --labels " + quoted("labels.db") + " --out " + quoted(out) +
           " " + more;
  }
  int64_t column_of(const Dataset& dataset, const std::string& name) const {
    for (size_t index = 0; index < dataset.columns.size(); ++index)
      if (dataset.columns[index].name == name) return static_cast<int64_t>(index);
    ADD_FAILURE() << "no column " << name;
    return 0;
  }

  test::TempFolder folder_{"features_cli"};
  std::string database_;
};

TEST_F(FeaturesCommand, GroundTruthSegmentsBecomeOneCsvRowEach) {
  const CommandResult run = tactile(features("table.csv"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("8 rows x 683 features from 2 recordings, 0 segments skipped"),
            std::string::npos)
      << run.out;
  const Dataset dataset = read_dataset_csv(folder_.file("table.csv"));
  ASSERT_EQ(dataset.rows(), 8);
  ASSERT_EQ(dataset.columns.size(),
            25u * 26 + 27 + 1 + 5);  // per channel, the busiest, neighbours, the map
  EXPECT_EQ(dataset.columns.front().name, "ch0.hjorth_activity");
  EXPECT_EQ(dataset.columns.back().name, "contact.spread");
  // The store's order: by recording, then time.
  EXPECT_EQ(dataset.classes, (std::vector<std::string>{"press", "swipe", "press", "swipe", "press",
                                                       "swipe", "press", "swipe"}));
  EXPECT_EQ(dataset.subjects[4], "s02");
  EXPECT_EQ(dataset.recordings[0], "grid-s01");
  EXPECT_EQ(dataset.segment_ids[1], 2);
  EXPECT_EQ(dataset.metadata[0].at("trial"), "1");
  EXPECT_EQ(dataset.metadata[0].at("layout"), "grid:5x5");
  EXPECT_EQ(dataset.metadata[1].at("t0"), "1.5");
  EXPECT_EQ(dataset.metadata[1].count("subject"), 0u);
  // A swipe's centroid travels two taxel pitches; a press stays put.
  const int64_t displacement = column_of(dataset, "centroid.displacement");
  EXPECT_NEAR(dataset.features(0, displacement), 0.0, 1e-9);
  EXPECT_NEAR(dataset.features(1, displacement), 20.0, 1e-6);
  const std::string header = test::read_text(folder_.path() / "table.csv");
  EXPECT_NE(header.find("contact.spread,class,subject,recording,segment_id,condition,"
                        "layout,region,t0,t1,trial\n"),
            std::string::npos);
  EXPECT_NE(test::read_text(folder_.path() / "table.csv.log").find("0 of 8 segments skipped"),
            std::string::npos);
}

TEST_F(FeaturesCommand, ArffHasTheClassListAndOneDataLinePerRow) {
  const CommandResult run = tactile(features("table.arff", "--threads 2"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string text = test::read_text(folder_.path() / "table.arff");
  EXPECT_NE(text.find("@relation generic\n"), std::string::npos);
  EXPECT_NE(text.find("@attribute ch12.peak numeric\n"), std::string::npos);
  EXPECT_NE(text.find("@attribute class {press,swipe}\n"), std::string::npos);
  const std::string data = text.substr(text.find("@data\n") + 6);
  EXPECT_EQ(std::count(data.begin(), data.end(), '\n'), 8);
  EXPECT_EQ(text.find("grid-s01"), std::string::npos);
}

TEST_F(FeaturesCommand, JsonSummaryHasPerClassCountsAndMeans) {
  const CommandResult run = tactile(features("table.csv", "--json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(run.out);
  EXPECT_EQ(summary.at("rows"), 8);
  EXPECT_EQ(summary.at("skipped"), 0);
  EXPECT_EQ(summary.at("columns").size(), 683u);
  EXPECT_EQ(summary.at("class_counts").at("swipe"), 4);
  EXPECT_NEAR(summary.at("class_means").at("swipe").at("centroid.path_length").get<double>(), 20.0,
              1e-6);
  EXPECT_NEAR(summary.at("class_means").at("press").at("centroid.path_length").get<double>(), 0.0,
              1e-9);
}

TEST_F(FeaturesCommand, SegmenterSegmentsTakeTheGroundTruthTheyOverlapMost) {
  {
    LabelStore store(database_);
    Label segment;
    segment.recording = "grid-s01";
    segment.class_name = kUnknownClass;
    segment.annotator = "segmenter:test";
    segment.source = LabelSource::kSegmenter;
    for (const auto& [t0, t1] : std::vector<std::pair<double, double>>{
             {1.3, 2.6},     // 0.6 s of the swipe, 0.1 s of the second press
             {5.0, 5.5}}) {  // touches nothing
      segment.t0 = t0;
      segment.t1 = t1;
      store.add(segment);
    }
  }
  const CommandResult run = tactile(features("segments.csv", "--source segmenter"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Dataset dataset = read_dataset_csv(folder_.file("segments.csv"));
  EXPECT_EQ(dataset.classes, (std::vector<std::string>{"swipe", "unknown"}));
}

TEST_F(FeaturesCommand, SkippedSegmentsAreReportedAndLogged) {
  {
    LabelStore store(database_);
    Label tiny;
    tiny.recording = "grid-s02";
    tiny.t0 = 3.201;
    tiny.t1 = 3.205;  // between two samples: nothing to extract from
    tiny.class_name = "press";
    tiny.annotator = "test";
    tiny.source = LabelSource::kGroundTruth;
    store.add(tiny);
  }
  const CommandResult run = tactile(features("table.csv"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("skipped: grid-s02 segment 9: segment holds no samples"),
            std::string::npos)
      << run.err;
  const std::string log = test::read_text(folder_.path() / "table.csv.log");
  EXPECT_NE(log.find("1 of 9 segments skipped"), std::string::npos) << log;
  EXPECT_NE(log.find("grid-s02\t9\t"), std::string::npos) << log;
  EXPECT_EQ(read_dataset_csv(folder_.file("table.csv")).rows(), 8);
}

TEST_F(FeaturesCommand, BadPipelineParametersOrOutputNameTheProblem) {
  CommandResult run = tactile("features --pipeline kabolli --labels " + quoted("labels.db") +
                              " --out " + quoted("t.csv"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("kabolli"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("generic"), std::string::npos) << run.err;
  run = tactile(features("t.csv", "--params threshold=2"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--params: threshold=2"), std::string::npos) << run.err;
  run = tactile(features("t.csv", "--params treshold=0.3"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("treshold"), std::string::npos) << run.err;
  run = tactile(features("t.txt"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--out"), std::string::npos) << run.err;
  run = tactile(features("t.csv", "--source guess"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--source"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(folder_.path() / "t.csv"));
}

TEST_F(FeaturesCommand, MissingRecordingFileIsNamedAndNothingIsWritten) {
  std::filesystem::remove(folder_.path() / "grid-s02.h5");
  const CommandResult run = tactile(features("table.csv"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("grid-s02.h5: recording file missing"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(folder_.path() / "table.csv"));
  // --recordings points elsewhere: every file is missing there.
  std::filesystem::create_directory(folder_.path() / "elsewhere");
  const CommandResult moved = tactile(features("table.csv", "--recordings " + quoted("elsewhere")));
  EXPECT_NE(moved.err.find("elsewhere/grid-s01.h5"), std::string::npos) << moved.err;
}

TEST_F(FeaturesCommand, ListAndDescribePrintPipelinesAndColumns) {
  const CommandResult list = tactile("features --list");
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_NE(list.out.find("generic  Any layout"), std::string::npos) << list.out;
  const CommandResult describe = tactile("features --describe generic --layout grid:2x2");
  ASSERT_EQ(describe.exit_code, 0) << describe.err;
  EXPECT_NE(describe.out.find("ch3.integral"), std::string::npos) << describe.out;
  EXPECT_NE(describe.out.find("contact.max_area"), std::string::npos);
  EXPECT_NE(describe.out.find("137 columns (generic on grid:2x2)"), std::string::npos);
  EXPECT_EQ(tactile("features --describe generic").exit_code, 1);
}

TEST_F(FeaturesCommand, SegmentRefusesUnknownMethodsAndMissingFiles) {
  CommandResult run = tactile("segment " + quoted("grid-s01.h5") + " --labels " +
                              quoted("labels.db") + " --method guesswork");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("--method: unknown segmenter 'guesswork'"), std::string::npos) << run.err;
  const std::vector<std::string> methods = segmenter_methods();
  ASSERT_FALSE(methods.empty()) << "no segmenter is registered";
  run = tactile("segment " + quoted("absent.h5") + " --labels " + quoted("labels.db") +
                " --method " + methods.front());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("absent.h5: no such recording file or folder"), std::string::npos)
      << run.err;
}

// Without --method each recording gets its skin's own segmenter (its record's): fur's is
// threshold, flux's excitation; a grid layout, no skin, gets adaptive.
TEST_F(FeaturesCommand, SegmentWithoutAMethodRunsEachSkinsOwn) {
  for (const char* skin : {"fur", "flux"})
    ASSERT_EQ(tactile(std::string("simulate --skin ") + skin +
                      " --subjects 1 --repetitions 1 --out " + quoted("skins"))
                  .exit_code,
              0);
  const CommandResult run = tactile("segment " + quoted("skins") + " --labels " + quoted("own.db"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("fur-s01-t01: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" segments (threshold)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" segments (excitation)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("(segmenter:excitation, segmenter:threshold)"), std::string::npos)
      << run.out;
}

// The whole chain on the fur pipeline's threshold segmenter, which reads grid recordings
// as rising pressure with a calibration peak of 1.
TEST_F(FeaturesCommand, SegmentThenFeaturesOnAFolder) {
  const std::vector<std::string> methods = segmenter_methods();
  ASSERT_NE(std::find(methods.begin(), methods.end(), "threshold"), methods.end())
      << "the threshold segmenter is not registered";
  const std::string segment = "segment " + quoted("") + " --labels " + quoted("labels.db") +
                              " --method threshold --params signal=rising,calibration_peak=1";
  CommandResult run = tactile(segment);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("from 2 recordings stored"), std::string::npos) << run.out;
  LabelFilter filter;
  filter.source = LabelSource::kSegmenter;
  const int64_t first = static_cast<int64_t>(LabelStore(database_).list(filter).size());
  EXPECT_GE(first, 2);
  // Again with --replace: the same segments, not twice as many.
  run = tactile(segment + " --replace");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(static_cast<int64_t>(LabelStore(database_).list(filter).size()), first);
  run = tactile(features("segments.csv", "--source segmenter"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Dataset dataset = read_dataset_csv(folder_.file("segments.csv"));
  EXPECT_GE(dataset.rows(), 2);
  for (const std::string& name : dataset.classes)
    EXPECT_TRUE(name == "press" || name == "swipe" || name == "unknown") << name;
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// The loop `features` -> `evaluate --save-model` -> `predict`: a model's answers become
// labels of source model, one per segment, with score and margin; a second run replaces.
TEST_F(FeaturesCommand, PredictWritesModelLabelsFromASavedModel) {
  ASSERT_EQ(tactile(features("features.csv")).exit_code, 0);
  const CommandResult trained =
      tactile("evaluate --features " + quoted("features.csv") +
              " --classifier knn:k=1 --protocol kfold:2 --pipeline generic --save-model " +
              quoted("model.json"));
  ASSERT_EQ(trained.exit_code, 0) << trained.err;
  const nlohmann::json model = nlohmann::json::parse(test::read_text(folder_.file("model.json")));
  EXPECT_EQ(model["pipeline"], "generic");
  // Every setting of the pipeline, the defaults of this build included, so that a later
  // default cannot change what predict extracts with this model.
  EXPECT_EQ(model["pipeline_params"], "modality=display,per_channel=auto,stream=,threshold=0.2");
  EXPECT_EQ(model["layout"], "grid:5x5");
  EXPECT_EQ(model["classes"], nlohmann::json({"press", "swipe"}));

  const std::string predict = "predict " + quoted("grid-s01.h5") + " " + quoted("grid-s02.h5") +
                              " --model " + quoted("model.json") + " --labels " +
                              quoted("labels.db");
  const CommandResult first = tactile(predict);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_NE(first.out.find("8 predictions from 2 recordings"), std::string::npos) << first.out;
  LabelFilter filter;
  filter.source = LabelSource::kModel;
  std::vector<Label> predicted = LabelStore(database_).list(filter);
  ASSERT_EQ(predicted.size(), 8u);
  for (const Label& label : predicted) {
    EXPECT_EQ(label.annotator, "model");
    EXPECT_TRUE(label.class_name == "press" || label.class_name == "swipe") << label.class_name;
    EXPECT_GE(label.confidence, 0.5);  // 1-NN votes: the winner holds the whole vote
    EXPECT_NE(label.note.find("margin="), std::string::npos) << label.note;
  }
  // The model learned these very segments: every answer is the ground truth.
  LabelFilter truth_filter;
  truth_filter.source = LabelSource::kGroundTruth;
  const std::vector<Label> truth = LabelStore(database_).list(truth_filter);
  for (const Label& label : predicted)
    for (const Label& known : truth)
      if (known.recording == label.recording && known.t0 == label.t0) {
        EXPECT_EQ(known.class_name, label.class_name);
      }

  const CommandResult second = tactile(predict);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("(replaced 4)"), std::string::npos) << second.out;
  EXPECT_EQ(LabelStore(database_).list(filter).size(), 8u);
}

TEST_F(FeaturesCommand, PredictRefusesAModelOfAnotherSkinOrWithoutPipeline) {
  ASSERT_EQ(tactile(features("features.csv")).exit_code, 0);
  ASSERT_EQ(tactile("evaluate --features " + quoted("features.csv") +
                    " --classifier knn --protocol kfold:2 --pipeline generic --save-model " +
                    quoted("model.json"))
                .exit_code,
            0);
  nlohmann::json model = nlohmann::json::parse(test::read_text(folder_.file("model.json")));
  model["layout"] = "nao";
  std::ofstream(folder_.file("nao.json")) << model.dump();
  const CommandResult other = tactile("predict " + quoted("grid-s01.h5") + " --model " +
                                      quoted("nao.json") + " --labels " + quoted("labels.db"));
  EXPECT_NE(other.exit_code, 0);
  EXPECT_NE(other.err.find("the model is for 'nao'"), std::string::npos) << other.err;
  model["layout"] = "grid:5x5";
  model["pipeline"] = "";
  std::ofstream(folder_.file("bare.json")) << model.dump();
  const CommandResult bare = tactile("predict " + quoted("grid-s01.h5") + " --model " +
                                     quoted("bare.json") + " --labels " + quoted("labels.db"));
  EXPECT_NE(bare.exit_code, 0);
  EXPECT_NE(bare.err.find("does not name its feature pipeline"), std::string::npos) << bare.err;
  LabelFilter filter;
  filter.source = LabelSource::kModel;
  EXPECT_TRUE(LabelStore(database_).list(filter).empty());  // nothing half-written
}

}  // namespace
}  // namespace tactile

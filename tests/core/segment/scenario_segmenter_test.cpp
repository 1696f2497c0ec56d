// Scenario segmenter (spec §4.1): stage command time stamps become one label per stage.
#include <gtest/gtest.h>

#include <limits>

#include "tactile/error.h"
#include "tactile/segment/scenario.h"

namespace tactile {
namespace {

SkinLayout staged_layout() {
  SkinLayout layout = make_strip_layout(2, "strip:2");
  layout.classes = {"Hello.", "Let's shake hands.", "Nice to meet you.", "Bye-bye!"};
  return layout;
}

// A 10 s skin stream at 100 Hz and one command per (time, stage).
Recording staged_recording(const std::vector<std::pair<double, float>>& commands_sent) {
  Recording recording;
  recording.id = "trial";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 100.0;
  skin.channels = {"ch0", "ch1"};
  skin.units = {"", ""};
  skin.samples = SampleMatrix::Zero(1000, 2);
  recording.streams.push_back(skin);
  Stream commands;
  commands.name = "commands";
  commands.channels = {"stage"};
  commands.units = {""};
  commands.samples.resize(static_cast<Eigen::Index>(commands_sent.size()), 1);
  for (size_t k = 0; k < commands_sent.size(); ++k) {
    commands.timestamps.push_back(commands_sent[k].first);
    commands.samples(Eigen::Index(k), 0) = commands_sent[k].second;
  }
  recording.streams.push_back(commands);
  return recording;
}

TEST(ScenarioSegmenter, OneLabelPerStageFromCommandToNextCommand) {
  const std::vector<Label> labels = segment_scenario(
      staged_recording({{0.5, 0}, {2.25, 1}, {4.0, 2}, {7.5, 3}}), staged_layout(), {});
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[0].class_name, "Hello.");
  EXPECT_DOUBLE_EQ(labels[0].t0, 0.5);
  EXPECT_DOUBLE_EQ(labels[0].t1, 2.25);
  EXPECT_EQ(labels[2].class_name, "Nice to meet you.");
  EXPECT_DOUBLE_EQ(labels[2].t0, 4.0);
  EXPECT_DOUBLE_EQ(labels[2].t1, 7.5);
  // The last stage runs to the end of the skin stream (1000 samples at 100 Hz).
  EXPECT_EQ(labels[3].class_name, "Bye-bye!");
  EXPECT_DOUBLE_EQ(labels[3].t1, 10.0);
  for (const Label& label : labels) {
    EXPECT_EQ(label.recording, "trial");
    EXPECT_EQ(label.region, "all");
    EXPECT_EQ(label.source, LabelSource::kSegmenter);
    EXPECT_EQ(label.annotator, "segmenter:scenario");
  }
}

TEST(ScenarioSegmenter, MissingCommandMergesIntoThePreviousStage) {
  const std::vector<Label> labels =
      segment_scenario(staged_recording({{0.5, 0}, {4.0, 2}, {7.5, 3}}), staged_layout(), {});
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].class_name, "Hello.");
  EXPECT_DOUBLE_EQ(labels[0].t1, 4.0);
  EXPECT_EQ(labels[1].class_name, "Nice to meet you.");
}

TEST(ScenarioSegmenter, RepeatedCommandContinuesTheStage) {
  const std::vector<Label> labels =
      segment_scenario(staged_recording({{0.5, 0}, {1.0, 0}, {4.0, 1}}), staged_layout(), {});
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_DOUBLE_EQ(labels[0].t0, 0.5);
  EXPECT_DOUBLE_EQ(labels[0].t1, 4.0);
}

TEST(ScenarioSegmenter, DropsAStageShorterThanTwoSamples) {
  // Stage 1 lasts 15 ms: a single sample at 100 Hz (the one at 2.01 s).
  const std::vector<Label> labels = segment_scenario(
      staged_recording({{0.5, 0}, {2.005, 1}, {2.02, 2}, {11.0, 3}}), staged_layout(), {});
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].class_name, "Hello.");
  EXPECT_EQ(labels[1].class_name, "Nice to meet you.");
  EXPECT_DOUBLE_EQ(labels[1].t1, 11.0);  // the command after the recording's end is dropped
}

TEST(ScenarioSegmenter, StageOutsideTheLayoutNamesTheSample) {
  try {
    segment_scenario(staged_recording({{0.5, 0}, {2.0, 7}}), staged_layout(), {});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "trial stream commands sample 1");
    EXPECT_NE(error.message().find("stage 7"), std::string::npos) << error.message();
  }
}

TEST(ScenarioSegmenter, NaNStageIsAnError) {
  EXPECT_THROW(segment_scenario(staged_recording({{0.5, std::numeric_limits<float>::quiet_NaN()}}),
                                staged_layout(), {}),
               Error);
}

TEST(ScenarioSegmenter, TimeGoingBackIsAnError) {
  try {
    segment_scenario(staged_recording({{2.0, 0}, {1.0, 1}}), staged_layout(), {});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("goes back"), std::string::npos) << error.message();
  }
}

TEST(ScenarioSegmenter, MissingCommandStreamIsAnError) {
  Recording recording = staged_recording({{0.5, 0}});
  recording.streams.pop_back();
  try {
    segment_scenario(recording, staged_layout(), {});
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "trial stream commands");
  }
}

TEST(ScenarioSegmenter, NoCommandsGiveNoLabels) {
  EXPECT_TRUE(segment_scenario(staged_recording({}), staged_layout(), {}).empty());
}

}  // namespace
}  // namespace tactile

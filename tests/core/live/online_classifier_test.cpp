// Online classification of a simulated fur stream with a model fitted on other trials: the
// stream between touches is "no touch", each touch gets one final decision after it ends,
// and the final decisions mostly agree with the offline pipeline on the same recording.
#include "tactile/live/online_classifier.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/predict.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

class OnlineClassifierTest : public ::testing::Test {
 protected:
  void SetUp() override {
    layout_ = load_layout("fur");
    SimulationOptions options;
    options.subjects = 3;
    std::vector<CorpusRecording> jobs;
    for (int subject = 0; subject < 3; ++subject) {
      SimulatedTrial trial = skin_record("fur").simulate(layout_, options, subject, 0);
      CorpusRecording job;
      job.id = trial.recording.id;
      job.path = directory_.file(job.id + ".h5");
      write_recording(job.path, trial.recording);
      job.segments = trial.labels;
      job.ground_truth = trial.labels;
      jobs.push_back(std::move(job));
    }
    const auto extractor = make_feature_extractor("fur", {});
    const CorpusDataset corpus = extract_corpus(*extractor, jobs);
    model_json_ = fit_model_document(corpus.dataset, "linear-svm", 1, "fur");
    held_out_ = skin_record("fur").simulate(layout_, options, 1, 1);
  }

  SavedModel model() const { return model_from_json(model_json_, "test model"); }

  testing::TemporaryDirectory directory_;
  SkinLayout layout_;
  nlohmann::json model_json_;
  SimulatedTrial held_out_;
};

TEST_F(OnlineClassifierTest, DecidesEveryTouchOnceAndNoTouchBetween) {
  const Stream& stream = held_out_.recording.streams.front();
  SourceInfo info;
  info.layout_id = "fur";
  info.rate_hz = stream.rate_hz;
  info.channels = stream.channels;
  info.units = stream.units;
  info.metadata = held_out_.recording.metadata;
  LiveSampleSource source(info, 100000);
  OnlineClassifier online(model(), layout_, info, default_online_options("fur"));
  std::vector<OnlineDecision> decisions;
  for (int64_t row = 0; row < stream.sample_count(); ++row) {
    const Eigen::VectorXf values = stream.samples.row(row).transpose();
    source.add(stream.time_of(row),
               std::span<const float>(values.data(), static_cast<size_t>(values.size())));
    online.update(source);
    online.wait_idle();
    for (OnlineDecision& decision : online.take()) decisions.push_back(std::move(decision));
  }
  EXPECT_EQ(online.error(), "");
  // Offline: the same model on the same touches.
  const Predictions offline =
      predict_segments(model(), held_out_.recording, layout_, held_out_.labels);
  ASSERT_EQ(offline.labels.size(), held_out_.labels.size());
  int matched = 0, agreed = 0, no_touch_inside = 0, no_touch = 0;
  for (size_t k = 0; k < held_out_.labels.size(); ++k) {
    const Label& touch = held_out_.labels[k];
    // The final decision about this touch: the one overlapping it most.
    const OnlineDecision* best = nullptr;
    double best_overlap = 0.0;
    int finals = 0;
    for (const OnlineDecision& decision : decisions) {
      if (!decision.final) continue;
      const double overlap = std::min(decision.t1, touch.t1) - std::max(decision.t0, touch.t0);
      if (overlap > 0.5 * (touch.t1 - touch.t0)) ++finals;
      if (overlap > best_overlap) best_overlap = overlap, best = &decision;
    }
    EXPECT_LE(finals, 1) << "touch " << k << " decided " << finals << " times";
    if (!best) continue;
    ++matched;
    if (best->class_name == offline.labels[k].class_name) ++agreed;
  }
  for (const OnlineDecision& decision : decisions) {
    if (decision.class_name != kNoTouchClass) continue;
    ++no_touch;
    for (const Label& touch : held_out_.labels)
      if (decision.t1 > touch.t0 + 0.3 && decision.t0 < touch.t1 - 0.3) ++no_touch_inside;
  }
  const int touches = static_cast<int>(held_out_.labels.size());
  std::printf("touches %d, decided %d, agreeing with offline %d; no touch %d (%d inside touches)\n",
              touches, matched, agreed, no_touch, no_touch_inside);
  EXPECT_GE(matched, touches * 8 / 10) << matched << " of " << touches << " touches decided";
  EXPECT_GE(agreed, matched * 7 / 10) << agreed << " of " << matched << " agree with offline";
  EXPECT_GT(no_touch, 20);
  EXPECT_LE(no_touch_inside, no_touch / 10) << no_touch_inside << " 'no touch' inside touches";
}

TEST_F(OnlineClassifierTest, RefusesAModelOfAnotherSkin) {
  SourceInfo info;
  info.rate_hz = 250;
  info.channels = {"a"};
  EXPECT_THROW(OnlineClassifier(model(), load_layout("nao"), info, default_online_options("nao")),
               Error);
  OnlineOptions options = default_online_options("fur");
  options.segmenter = "guess";
  info.rate_hz = 15;
  EXPECT_THROW(OnlineClassifier(model(), layout_, info, options), Error);
}

}  // namespace
}  // namespace tactile

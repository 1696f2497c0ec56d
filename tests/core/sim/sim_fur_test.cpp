#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/simulator.h"
#include "tactile/stats/statistics.h"

namespace tactile {

// Defined in core/src/sim/fur_sim.cpp (registered as the "fur" generator).
SimulatedTrial simulate_fur_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial);

namespace {

const SkinLayout& fur_layout() {
  static const SkinLayout layout = load_layout("fur");
  return layout;
}

// Five subjects, two trials each (one from the front, one from behind), default options.
const std::vector<SimulatedTrial>& corpus() {
  static const std::vector<SimulatedTrial> trials = [] {
    std::vector<SimulatedTrial> result;
    SimulationOptions options;
    options.seed = 11;
    for (int subject = 0; subject < 5; ++subject)
      for (int trial = 0; trial < 2; ++trial)
        result.push_back(simulate_fur_trial(fur_layout(), options, subject, trial));
    return result;
  }();
  return trials;
}

const Stream& fur_skin(const SimulatedTrial& trial) { return trial.recording.streams.at(0); }

struct FrameRange {
  int64_t first = 0, last = 0;
};

FrameRange frames_of(const Stream& stream, double t0, double t1) {
  const int64_t first = std::max<int64_t>(0, static_cast<int64_t>(std::floor(t0 * stream.rate_hz)));
  const int64_t last = std::min<int64_t>(stream.sample_count() - 1,
                                         static_cast<int64_t>(std::ceil(t1 * stream.rate_hz)));
  return {first, last};
}

// Mean raw reading of every cell over the `seconds` before t0: the quiescent level.
Eigen::VectorXf rest_level(const Stream& stream, double t0, double seconds) {
  const FrameRange range = frames_of(stream, t0 - seconds, t0);
  return stream.samples.middleRows(range.first, range.last - range.first)
      .colwise()
      .mean()
      .transpose();
}

// Pressure seen by each cell: how far its reading fell below its quiescent level.
Eigen::VectorXf drop_at(const Stream& stream, const Eigen::VectorXf& rest, int64_t frame) {
  return rest - stream.samples.row(frame).transpose();
}

// Spec §3.2: first-order high-pass at 0.2 Hz of u = 1023 - raw.
std::vector<double> high_pass(const Stream& stream, int64_t channel) {
  const double rc = 1.0 / (2.0 * 3.14159265358979 * 0.2), dt = 1.0 / stream.rate_hz;
  const double alpha = rc / (rc + dt);
  std::vector<double> y(static_cast<size_t>(stream.sample_count()));
  double previous_u = 1023.0 - stream.samples(0, channel), previous_y = 0.0;
  for (int64_t t = 0; t < stream.sample_count(); ++t) {
    const double u = 1023.0 - stream.samples(t, channel);
    previous_y = alpha * (previous_y + u - previous_u);
    previous_u = u;
    y[static_cast<size_t>(t)] = previous_y;
  }
  return y;
}

std::vector<double> calibration_peaks(const SimulatedTrial& trial) {
  std::vector<double> peaks;
  std::stringstream text(trial.recording.metadata.at("calibration_peak"));
  std::string number;
  while (std::getline(text, number, ',')) peaks.push_back(std::stod(number));
  return peaks;
}

//---- Determinism and format -----------------------------------------------------------------

TEST(FurSimulator, SameSeedSubjectAndTrialGiveIdenticalBytes) {
  SimulationOptions options;
  options.seed = 5;
  options.repetitions = 2;
  const SimulatedTrial first = simulate_fur_trial(fur_layout(), options, 2, 1);
  const SimulatedTrial second = simulate_fur_trial(fur_layout(), options, 2, 1);
  ASSERT_EQ(fur_skin(first).samples.rows(), fur_skin(second).samples.rows());
  EXPECT_EQ(0, std::memcmp(fur_skin(first).samples.data(), fur_skin(second).samples.data(),
                           sizeof(float) * fur_skin(first).samples.size()));
  ASSERT_EQ(first.labels.size(), second.labels.size());
  for (size_t k = 0; k < first.labels.size(); ++k) {
    EXPECT_EQ(first.labels[k].t0, second.labels[k].t0);
    EXPECT_EQ(first.labels[k].t1, second.labels[k].t1);
    EXPECT_EQ(first.labels[k].class_name, second.labels[k].class_name);
    EXPECT_EQ(first.labels[k].region, second.labels[k].region);
  }
  EXPECT_EQ(first.recording.metadata, second.recording.metadata);

  options.seed = 6;
  const SimulatedTrial other = simulate_fur_trial(fur_layout(), options, 2, 1);
  const bool same_shape = fur_skin(other).samples.rows() == fur_skin(first).samples.rows();
  EXPECT_FALSE(same_shape && fur_skin(other).samples == fur_skin(first).samples);
}

TEST(FurSimulator, RecordingCarriesIdLayoutApproachAndCalibration) {
  const SimulatedTrial& trial = corpus()[3];  // subject 1, trial 1
  EXPECT_EQ(trial.recording.id, simulated_recording_id("fur", 1, 1));
  EXPECT_EQ(trial.recording.layout_id, "fur");
  EXPECT_EQ(trial.recording.metadata.at("subject"), "s02");
  const std::string approach = trial.recording.metadata.at("approach");
  EXPECT_TRUE(approach == "front" || approach == "back");
  // A subject's two trials come from opposite sides.
  EXPECT_NE(approach, corpus()[2].recording.metadata.at("approach"));
  const Stream& stream = fur_skin(trial);
  EXPECT_EQ(stream.name, "skin");
  EXPECT_DOUBLE_EQ(stream.rate_hz, 15.0);
  EXPECT_EQ(stream.channel_count(), 160);
  const std::vector<double> peaks = calibration_peaks(trial);
  ASSERT_EQ(peaks.size(), 160u);
  for (double peak : peaks) EXPECT_GT(peak, 50.0);
}

TEST(FurSimulator, LabelCountIsClassesTimesRepetitions) {
  EXPECT_EQ(corpus()[0].labels.size(), 6u * 5u);  // default: five per class
  SimulationOptions options;
  options.repetitions = 2;
  const SimulatedTrial trial = simulate_fur_trial(fur_layout(), options, 0, 0);
  std::map<std::string, int> per_class;
  for (const Label& label : trial.labels) ++per_class[label.class_name];
  EXPECT_EQ(trial.labels.size(), 12u);
  for (const std::string& name : fur_layout().classes) EXPECT_EQ(per_class[name], 2) << name;
}

TEST(FurSimulator, NegativeRepetitionsNameTheOption) {
  SimulationOptions options;
  options.repetitions = -1;
  try {
    simulate_fur_trial(fur_layout(), options, 0, 0);
    FAIL() << "expected tactile::Error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "--repetitions");
  }
}

TEST(FurSimulator, LabelsAreDisjointGroundTruthInsideTheRecording) {
  for (const SimulatedTrial& trial : corpus()) {
    double previous_end = 0.0;
    for (const Label& label : trial.labels) {
      EXPECT_EQ(label.recording, trial.recording.id);
      EXPECT_GT(label.t0, previous_end + 1.0) << "a rest of over a second separates gestures";
      EXPECT_GT(label.t1, label.t0);
      EXPECT_LT(label.t1, fur_skin(trial).duration());
      EXPECT_EQ(label.source, LabelSource::kGroundTruth);
      EXPECT_EQ(label.annotator, "simulator");
      EXPECT_EQ(label.confidence, 1.0);
      const Group* region = fur_layout().find_group(label.region);
      ASSERT_NE(region, nullptr) << label.region;
      EXPECT_EQ(region->kind, "region");
      previous_end = label.t1;
    }
  }
}

TEST(FurSimulator, EveryValueIsAWholeCountInsideTheTenBitRange) {
  for (const SimulatedTrial& trial : corpus()) {
    const auto& samples = fur_skin(trial).samples;
    EXPECT_TRUE(samples.allFinite());
    EXPECT_GE(samples.minCoeff(), 0.0f);
    EXPECT_LE(samples.maxCoeff(), 1023.0f);
    EXPECT_TRUE((samples.array() == samples.array().round()).all());
  }
}

TEST(FurSimulator, QuietFurReadsAboutHalfTheRangeAndFallsWhenPressed) {
  const SimulatedTrial& trial = corpus()[0];
  const Eigen::VectorXf rest = rest_level(fur_skin(trial), trial.labels[0].t0, 1.5);
  EXPECT_GT(rest.mean(), 250.0f);
  EXPECT_LT(rest.mean(), 700.0f);
  // Bigger (lower) cells conduct more at rest, so they read lower (paper 002 §2.1).
  EXPECT_LT(rest.tail(16).mean(), rest.head(16).mean());
}

//---- Class signatures measured from the samples ---------------------------------------------

TEST(FurSimulator, TickleNeverSaturatesWhileTheOtherGesturesMostlyDo) {
  std::map<std::string, int> gestures, saturated;
  for (const SimulatedTrial& trial : corpus())
    for (const Label& label : trial.labels) {
      const FrameRange range = frames_of(fur_skin(trial), label.t0, label.t1);
      const float lowest =
          fur_skin(trial).samples.middleRows(range.first, range.last - range.first + 1).minCoeff();
      ++gestures[label.class_name];
      if (lowest == 0.0f) ++saturated[label.class_name];  // the ADC floor
    }
  EXPECT_EQ(saturated["tickle"], 0);
  for (const std::string name : {"slap", "pat", "fondle", "stroke", "push"})
    EXPECT_GT(saturated[name], gestures[name] / 2) << name;
}

TEST(FurSimulator, NormalisedByItsCalibrationOnlyTickleStaysBelowFullScale) {
  // Spec §3.2-3.3 as the feature pipeline will run it: high-pass, divide by the calibration
  // peak from the metadata, clip to [0, 1]. Paper 002 Fig 6: every gesture but tickling
  // drives some cell to 1.
  std::map<std::string, int> gestures, full;
  for (const SimulatedTrial& trial : corpus()) {
    const Stream& stream = fur_skin(trial);
    const std::vector<double> peaks = calibration_peaks(trial);
    std::vector<std::vector<double>> filtered;
    for (int64_t channel = 0; channel < stream.channel_count(); ++channel)
      filtered.push_back(high_pass(stream, channel));
    for (const Label& label : trial.labels) {
      const FrameRange range = frames_of(stream, label.t0, label.t1);
      double highest = 0.0;
      for (int64_t channel = 0; channel < stream.channel_count(); ++channel)
        for (int64_t frame = range.first; frame <= range.last; ++frame)
          highest = std::max(highest, filtered[channel][frame] / peaks[channel]);
      ++gestures[label.class_name];
      if (highest >= 1.0) ++full[label.class_name];
    }
  }
  EXPECT_EQ(full["tickle"], 0);
  for (const std::string name : {"slap", "pat", "fondle", "stroke", "push"})
    EXPECT_GT(full[name], gestures[name] * 3 / 4) << name;
}

// Drop-weighted centre of the cells pressed well below their rest level, per frame.
std::vector<Point2> contact_centres(const SimulatedTrial& trial, const Label& label) {
  const Stream& stream = fur_skin(trial);
  const Eigen::VectorXf rest = rest_level(stream, label.t0, 0.8);
  const FrameRange range = frames_of(stream, label.t0, label.t1);
  std::vector<Point2> centres;
  for (int64_t frame = range.first; frame <= range.last; ++frame) {
    const Eigen::VectorXf drop = drop_at(stream, rest, frame);
    double weight = 0.0, x = 0.0, y = 0.0;
    for (const Taxel& taxel : fur_layout().taxels) {
      const double value = drop(taxel.channels[0]);
      if (value < 60.0) continue;
      weight += value;
      x += value * taxel.position.x;
      y += value * taxel.position.y;
    }
    if (weight > 0) centres.push_back({x / weight, y / weight});
  }
  return centres;
}

// How far (mm) the contact's centre gets from where it first was.
double longest_travel(const std::vector<Point2>& centres) {
  double longest = 0.0;
  for (const Point2& centre : centres)
    longest =
        std::max(longest, std::hypot(centre.x - centres.front().x, centre.y - centres.front().y));
  return longest;
}

TEST(FurSimulator, StrokeContactTravelsWhilePushStaysPut) {
  std::map<std::string, std::vector<double>> travel;
  for (const SimulatedTrial& trial : corpus())
    for (const Label& label : trial.labels) {
      if (label.class_name != "stroke" && label.class_name != "push") continue;
      const std::vector<Point2> centres = contact_centres(trial, label);
      ASSERT_FALSE(centres.empty());
      travel[label.class_name].push_back(longest_travel(centres));
    }
  EXPECT_GT(stats::median(travel["stroke"]), 60.0);
  EXPECT_GT(stats::median(travel["stroke"]), 3.0 * stats::median(travel["push"]));
}

TEST(FurSimulator, FondleIsDoneInSeveralWaysMostOftenByKneadingInPlace) {
  // Paper 002 Table 1: fondle's errors spread over pat, stroke, tickle and push. Our fondles
  // mostly knead in place, and now and then travel like a stroke.
  int fondles = 0, in_place = 0, travelling = 0;
  for (const SimulatedTrial& trial : corpus())
    for (const Label& label : trial.labels) {
      if (label.class_name != "fondle") continue;
      ++fondles;
      const std::vector<Point2> centres = contact_centres(trial, label);
      if (centres.empty()) continue;
      const double travel = longest_travel(centres);
      in_place += travel < 40.0 ? 1 : 0;
      travelling += travel > 60.0 ? 1 : 0;
    }
  ASSERT_GT(fondles, 40);
  EXPECT_GT(in_place, fondles / 3);
  EXPECT_GT(travelling, 0);
  EXPECT_LT(travelling, fondles / 2);
}

// Seconds during which some cell reads well below its quiet level.
double contact_seconds(const SimulatedTrial& trial, const Label& label) {
  const Stream& stream = fur_skin(trial);
  const Eigen::VectorXf rest = rest_level(stream, label.t0, 0.8);
  const FrameRange range = frames_of(stream, label.t0, label.t1 + 0.5);
  int64_t first = -1, last = -1;
  for (int64_t frame = range.first; frame <= range.last; ++frame)
    if (drop_at(stream, rest, frame).maxCoeff() > 40.0f) {
      if (first < 0) first = frame;
      last = frame;
    }
  return first < 0 ? 0.0 : (last - first + 1) / stream.rate_hz;
}

TEST(FurSimulator, SlapIsShorterThanPush) {
  double longest_slap = 0.0, shortest_push = 1e9;
  for (const SimulatedTrial& trial : corpus())
    for (const Label& label : trial.labels) {
      if (label.class_name == "slap")
        longest_slap = std::max(longest_slap, contact_seconds(trial, label));
      if (label.class_name == "push")
        shortest_push = std::min(shortest_push, contact_seconds(trial, label));
    }
  EXPECT_GT(longest_slap, 0.0);
  EXPECT_LT(longest_slap, 0.5);
  EXPECT_GT(shortest_push, 1.0);
}

TEST(FurSimulator, FrontAndBackApproachesTouchDifferentPartsOfTheHead) {
  std::map<std::string, std::vector<double>> heights;
  for (const SimulatedTrial& trial : corpus())
    for (const Label& label : trial.labels)
      for (const Point2& centre : contact_centres(trial, label))
        heights[trial.recording.metadata.at("approach")].push_back(centre.y);
  // From the front the hand lands on the crown (small y), from behind lower down.
  EXPECT_LT(stats::median(heights["front"]) + 60.0, stats::median(heights["back"]));
}

TEST(FurSimulator, QuiescentOffsetShiftsAfterAContactButTheHighPassRemovesIt) {
  int pushes = 0, shifted = 0;
  for (const SimulatedTrial& trial : corpus()) {
    const Stream& stream = fur_skin(trial);
    const std::vector<double> peaks = calibration_peaks(trial);
    for (size_t k = 0; k + 1 < trial.labels.size(); ++k) {
      const Label& label = trial.labels[k];
      if (label.class_name != "push") continue;
      const Eigen::VectorXf before = rest_level(stream, label.t0, 0.8);
      const FrameRange range = frames_of(stream, label.t0, label.t1);
      Eigen::Index cell = 0;
      stream.samples.middleRows(range.first, range.last - range.first + 1)
          .colwise()
          .minCoeff()
          .minCoeff(&cell);
      // Quiet level between one and 1.2 s after the release (the next gesture comes later).
      const float after = rest_level(stream, label.t1 + 1.2, 0.2)(cell);
      const double step = std::abs(after - before(cell));
      ++pushes;
      if (step >= 3.0) ++shifted;
      EXPECT_LT(step, 0.1 * peaks[cell]) << "the settling step is small";
      // After the high-pass and the clip of spec §3.3, the shifted level stays far below
      // the segmentation threshold (0.1 of the calibration range) through the rest.
      const std::vector<double> filtered = high_pass(stream, cell);
      const FrameRange rest = frames_of(stream, label.t1 + 0.3, trial.labels[k + 1].t0 - 0.1);
      for (int64_t frame = rest.first; frame <= rest.last; ++frame)
        EXPECT_LT(filtered[frame] / peaks[cell], 0.05) << trial.recording.id << " frame " << frame;
    }
  }
  ASSERT_GT(pushes, 20);
  EXPECT_GT(shifted, pushes * 7 / 10);
}

}  // namespace
}  // namespace tactile

// Sensor faults laid over simulated recordings (sim/sensor_faults.h).
#include "tactile/sim/sensor_faults.h"

#include <gtest/gtest.h>

#include "tactile/error.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

SimulatedTrial fur_trial() {
  SimulationOptions options;
  options.repetitions = 1;
  return skin_record("fur").simulate(load_layout("fur"), options, 0, 0);
}

TEST(SensorFaults, ParsesPresetsAndPairsAndRefusesNonsense) {
  EXPECT_FALSE(parse_sensor_faults("none", "test").any());
  EXPECT_FALSE(parse_sensor_faults("", "test").any());
  const SensorFaults realistic = parse_sensor_faults("realistic", "test");
  EXPECT_EQ(realistic.stuck, 2);
  EXPECT_GT(realistic.rest, 0.0);
  const SensorFaults changed = parse_sensor_faults("realistic,stuck=0", "test");
  EXPECT_EQ(changed.stuck, 0);
  EXPECT_EQ(changed.dead, realistic.dead);
  EXPECT_EQ(parse_sensor_faults("drift=0.5", "test").drift, 0.5);
  EXPECT_THROW(parse_sensor_faults("wobble=1", "test"), Error);
  EXPECT_THROW(parse_sensor_faults("stuck=-1", "test"), Error);
  EXPECT_THROW(parse_sensor_faults("rest=2", "test"), Error);
  EXPECT_THROW(parse_sensor_faults("realisticx", "test"), Error);
}

TEST(SensorFaults, AreTheSameForTheSameSeedAndDifferForAnother) {
  const SkinLayout layout = load_layout("fur");
  const SensorFaults faults = parse_sensor_faults("realistic", "test");
  SimulatedTrial first = fur_trial(), second = fur_trial(), third = fur_trial();
  const SampleMatrix clean = first.recording.streams.front().samples;
  apply_sensor_faults(first, layout, faults, 7, 0, 0);
  apply_sensor_faults(second, layout, faults, 7, 0, 0);
  apply_sensor_faults(third, layout, faults, 8, 0, 0);
  EXPECT_EQ(first.recording.streams.front().samples, second.recording.streams.front().samples);
  EXPECT_NE(first.recording.streams.front().samples, third.recording.streams.front().samples);
  EXPECT_NE(first.recording.streams.front().samples, clean);
  EXPECT_EQ(first.labels.size(), second.labels.size());
  EXPECT_EQ(first.recording.metadata.count("faults"), 1u);
}

TEST(SensorFaults, StuckChannelsHoldOneValueAndDeadOnesReadZero) {
  const SkinLayout layout = load_layout("fur");
  SimulatedTrial trial = fur_trial();
  apply_sensor_faults(trial, layout, parse_sensor_faults("stuck=2,dead=1", "test"), 1, 0, 0);
  const SampleMatrix& samples = trial.recording.streams.front().samples;
  const Eigen::Index rows = samples.rows();
  int dead = 0, stuck = 0;
  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    if ((samples.col(c).array() == 0.0f).all()) ++dead;
    // Stuck from some moment in the first half on: the last half is one value.
    else if ((samples.col(c).tail(rows / 2).array() == samples(rows - 1, c)).all())
      ++stuck;
  }
  EXPECT_EQ(dead, 1);
  EXPECT_GE(stuck, 2);  // quiet channels of a clean fur may hold one value too
}

TEST(SensorFaults, ARestingHandPressesOnlyBetweenTheLabels) {
  const SkinLayout layout = load_layout("fur");
  SimulatedTrial trial = fur_trial();
  const Stream clean = trial.recording.streams.front();
  apply_sensor_faults(trial, layout, parse_sensor_faults("rest=1,rest_gap=1", "test"), 1, 0, 0);
  const Stream& rested = trial.recording.streams.front();
  int64_t changed_inside = 0, changed_outside = 0;
  for (int64_t t = 0; t < clean.sample_count(); ++t) {
    const double time = clean.time_of(t);
    bool inside = false;
    for (const Label& label : trial.labels)
      inside = inside || (time >= label.t0 && time < label.t1);
    const bool changed = (rested.samples.row(t).array() != clean.samples.row(t).array()).any();
    (inside ? changed_inside : changed_outside) += changed;
  }
  EXPECT_EQ(changed_inside, 0);
  EXPECT_GT(changed_outside, 0);
}

TEST(SensorFaults, CrosstalkMovesTheNeighboursOfATouchedTaxel) {
  const SkinLayout layout = load_layout("fur");
  SimulatedTrial trial = fur_trial();
  const SampleMatrix clean = trial.recording.streams.front().samples;
  apply_sensor_faults(trial, layout, parse_sensor_faults("crosstalk=0.1", "test"), 1, 0, 0);
  const SampleMatrix& talked = trial.recording.streams.front().samples;
  // Every change is a share of the neighbours' swing: never more than 0.1 of the largest.
  const float largest = (clean.rowwise() - clean.colwise().minCoeff()).cwiseAbs().maxCoeff();
  const float moved = (talked - clean).cwiseAbs().maxCoeff();
  EXPECT_GT(moved, 0.0f);
  EXPECT_LE(moved, 0.1f * largest * 1.001f);
}

}  // namespace
}  // namespace tactile

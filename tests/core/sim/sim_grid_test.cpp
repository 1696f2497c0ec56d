// The pressure grid simulator (grid:RxC): reproducible, labelled as planned, touched where
// the plan says and at places that vary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

#include "tactile/error.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/stats/statistics.h"

namespace tactile {
namespace {

SimulationOptions grid_options(int repetitions = 3, uint64_t seed = 3) {
  SimulationOptions options;
  options.seed = seed;
  options.repetitions = repetitions;
  return options;
}

TEST(GridSimulator, SameSeedSubjectAndTrialGiveIdenticalBytes) {
  const SkinLayout layout = make_grid_layout(9, 12);
  const SimulatedTrial first = simulate_grid_trial(layout, grid_options(), 1, 2);
  const SimulatedTrial second = simulate_grid_trial(layout, grid_options(), 1, 2);
  const SampleMatrix& a = first.recording.streams.at(0).samples;
  const SampleMatrix& b = second.recording.streams.at(0).samples;
  ASSERT_EQ(a.rows(), b.rows());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(float) * static_cast<size_t>(a.size())));
  ASSERT_EQ(first.labels.size(), second.labels.size());
  for (size_t k = 0; k < first.labels.size(); ++k) {
    EXPECT_EQ(first.labels[k].t0, second.labels[k].t0);
    EXPECT_EQ(first.labels[k].class_name, second.labels[k].class_name);
  }
  const SimulatedTrial other = simulate_grid_trial(layout, grid_options(3, 4), 1, 2);
  const SampleMatrix& c = other.recording.streams.at(0).samples;
  EXPECT_FALSE(c.rows() == a.rows() && c == a);
}

TEST(GridSimulator, LabelsAreEveryGestureRepetitionsTimesInOrderInsideTheRecording) {
  const SkinLayout layout = make_grid_layout(16, 16);
  const SimulatedTrial trial = simulate_grid_trial(layout, grid_options(4), 0, 0);
  std::map<std::string, int> per_class;
  double previous_end = 0.0;
  for (const Label& label : trial.labels) {
    ++per_class[label.class_name];
    EXPECT_GT(label.t1, label.t0);
    EXPECT_GE(label.t0, previous_end);  // disjoint, in time order
    previous_end = label.t1;
    EXPECT_EQ(label.source, LabelSource::kGroundTruth);
    EXPECT_EQ(label.recording, "grid-16x16-s01-t01");
  }
  EXPECT_LT(previous_end, trial.recording.duration());
  ASSERT_EQ(per_class.size(), 7u);
  // A pat is one to three contacts, each its own touch; every other gesture is one.
  for (const std::string& name : grid_gesture_classes())
    if (name != "pat") {
      EXPECT_EQ(per_class[name], 4) << name;
    }
  EXPECT_GE(per_class["pat"], 4);
  EXPECT_LE(per_class["pat"], 12);
  EXPECT_EQ(trial.recording.layout_id, "grid:16x16");
}

TEST(GridSimulator, EachPatIsItsOwnTouchAndTheGridReleasesBetweenThem) {
  const SkinLayout layout = make_grid_layout(16, 16);
  const SimulatedTrial trial = simulate_grid_trial(layout, grid_options(10), 1, 0);
  const Stream& stream = trial.recording.streams.at(0);
  // The grid's summed counts per frame; its rest drifts, so each pair is measured from the
  // quietest frame within 5 s.
  const Eigen::VectorXd total = stream.samples.cast<double>().rowwise().sum();
  const auto frame_of = [&](double t) {
    return std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::llround(t * kGridRateHz)), 0,
                                    total.size() - 1);
  };
  int pats = 0, close = 0, tickles = 0;
  for (size_t k = 0; k < trial.labels.size(); ++k) {
    const Label& label = trial.labels[k];
    tickles += label.class_name == "tickle";
    if (label.class_name != "pat") continue;
    ++pats;
    if (k + 1 == trial.labels.size() || trial.labels[k + 1].class_name != "pat") continue;
    const Label& next = trial.labels[k + 1];
    if (next.t0 - label.t1 > 0.4) continue;
    // Two pats of one gesture: between the two presses the grid comes back near its rest.
    ++close;
    const Eigen::Index from = frame_of(label.t0 - 5.0);
    const double quiet = total.segment(from, frame_of(next.t1 + 5.0) - from + 1).minCoeff();
    double low = std::numeric_limits<double>::infinity();
    for (Eigen::Index t = frame_of(label.t1 - 0.04); t <= frame_of(next.t0 + 0.04); ++t)
      low = std::min(low, total(t) - quiet);
    const double first =
        total.segment(frame_of(label.t0), frame_of(label.t1) - frame_of(label.t0) + 1).maxCoeff() -
        quiet;
    const double second =
        total.segment(frame_of(next.t0), frame_of(next.t1) - frame_of(next.t0) + 1).maxCoeff() -
        quiet;
    EXPECT_LT(low, 0.5 * std::min(first, second)) << label.t0;
  }
  EXPECT_GT(pats, 10);  // some pats have two or three contacts
  EXPECT_GE(close, 3);
  // A tickle's fingers touch at once: one touch.
  EXPECT_EQ(tickles, 10);
}

TEST(GridSimulator, EveryValueIsAWholeTenBitCountAndRestLevelsDifferPerTaxel) {
  const SimulatedTrial trial = simulate_grid_trial(make_grid_layout(10, 10), grid_options(2), 0, 0);
  const SampleMatrix& samples = trial.recording.streams.at(0).samples;
  EXPECT_TRUE((samples.array() == samples.array().round()).all());
  EXPECT_GE(samples.minCoeff(), 0.0f);
  EXPECT_LE(samples.maxCoeff(), 1023.0f);
  std::set<float> rests;
  for (Eigen::Index taxel = 0; taxel < samples.cols(); ++taxel)
    rests.insert(samples(0, taxel));  // the first frame is before any touch
  EXPECT_GT(rests.size(), 50u);
}

// The taxel that rose most over a touch, as (row, column).
std::pair<double, double> most_pressed(const SampleMatrix& samples, int64_t columns, double rate,
                                       double t0, double t1) {
  const auto first = static_cast<Eigen::Index>(std::ceil(t0 * rate));
  const auto last = static_cast<Eigen::Index>(std::ceil(t1 * rate));
  Eigen::Index best = 0;
  double rise = -1e9;
  for (Eigen::Index taxel = 0; taxel < samples.cols(); ++taxel) {
    const double rest = samples(0, taxel);
    const double peak = samples.col(taxel).segment(first, last - first).maxCoeff();
    if (peak - rest > rise) rise = peak - rest, best = taxel;
  }
  return {static_cast<double>(best / columns), static_cast<double>(best % columns)};
}

TEST(GridSimulator, ATapOrPushPressesMostWherePlannedAndPlacesVary) {
  const SkinLayout layout = make_grid_layout(16, 20);
  const SimulationOptions options = grid_options(6);
  double seconds = 0.0;
  const std::vector<GridTouch> plan = plan_grid_touches(16, 20, options, 2, 0, seconds);
  const SimulatedTrial trial = simulate_grid_trial(layout, options, 2, 0);
  ASSERT_EQ(plan.size(), trial.labels.size());
  EXPECT_NEAR(seconds, trial.recording.duration(), 0.05);
  const SampleMatrix& samples = trial.recording.streams.at(0).samples;
  std::set<std::pair<double, double>> places;
  std::vector<double> rows, columns;
  int checked = 0;
  for (size_t k = 0; k < plan.size(); ++k) {
    EXPECT_EQ(trial.labels[k].t0, plan[k].t0);
    EXPECT_EQ(trial.labels[k].t1, plan[k].t1);
    rows.push_back(plan[k].row);
    columns.push_back(plan[k].column);
    const std::string& gesture = grid_gesture_classes()[static_cast<size_t>(plan[k].gesture)];
    if (gesture != "tap" && gesture != "push") continue;
    const auto [row, column] = most_pressed(samples, 20, kGridRateHz, plan[k].t0, plan[k].t1);
    // Within the patch's middle (a stuck or dead taxel there moves it by one).
    EXPECT_LE(std::hypot(row - plan[k].row, column - plan[k].column), 1.5) << gesture << " " << k;
    places.insert({row, column});
    ++checked;
  }
  EXPECT_GE(checked, 10);
  EXPECT_GE(places.size(), static_cast<size_t>(checked) - 2);
  EXPECT_GT(std::sqrt(stats::variance(rows)), 3.0);
  EXPECT_GT(std::sqrt(stats::variance(columns)), 3.5);
}

TEST(GridSimulator, RefusesALayoutThatIsNoGrid) {
  EXPECT_THROW(simulate_grid_trial(make_strip_layout(16), grid_options(), 0, 0), Error);
  EXPECT_THROW(simulate_grid_trial(make_grid_layout(4, 4), grid_options(), -1, 0), Error);
}

}  // namespace
}  // namespace tactile

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/sim/flux_sensor.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

//---- Measuring a generated trial from its samples only

SimulatedTrial generate(uint64_t seed, int subject, int trial, int repetitions = 0) {
  SimulationOptions options;
  options.seed = seed;
  options.repetitions = repetitions;
  return skin_record("flux").simulate(load_layout("flux"), options, subject, trial);
}

// The default trial of one subject, generated once for the whole suite.
const SimulatedTrial& default_trial() {
  static const SimulatedTrial trial = generate(11, 2, 0);
  return trial;
}

const Stream& skin(const SimulatedTrial& trial) { return *trial.recording.find_stream("skin"); }

int column_of(const Stream& stream, const std::string& name) {
  const auto found = std::find(stream.channels.begin(), stream.channels.end(), name);
  return found == stream.channels.end() ? -1 : static_cast<int>(found - stream.channels.begin());
}

// The top-layer channel name of zone k (1-based), read from the layout's groups.
std::string zone_channel(const SkinLayout& layout, int zone) {
  const Group* group = layout.find_group("zone" + std::to_string(zone));
  const Taxel* taxel = layout.find_taxel(group->taxels.at(0));
  return layout.channels.at(taxel->channels.at(0)).name;
}

double mean_between(const Stream& stream, int column, double t0, double t1) {
  const int64_t first = stream.index_at(t0), last = stream.index_at(t1);
  double sum = 0.0;
  for (int64_t n = first; n <= last; ++n) sum += stream.samples(n, column);
  return sum / static_cast<double>(last - first + 1);
}

// Rise of a channel during a gesture: its peak over the contact (and the fast release) above
// the level just before the contact.
double rise(const Stream& stream, int column, const Label& label) {
  const double before = mean_between(stream, column, label.t0 - 0.3, label.t0 - 0.01);
  const int64_t first = stream.index_at(label.t0), last = stream.index_at(label.t1 + 0.3);
  return stream.samples.col(column).segment(first, last - first + 1).maxCoeff() - before;
}

double time_of_peak(const Stream& stream, int column, const Label& label) {
  const int64_t first = stream.index_at(label.t0), last = stream.index_at(label.t1 + 0.3);
  Eigen::Index at = 0;
  stream.samples.col(column).segment(first, last - first + 1).maxCoeff(&at);
  return stream.time_of(first + at);
}

int zone_of_touch(const std::string& class_name) {
  return class_name.rfind("touch", 0) == 0 ? class_name[5] - '0' : 0;
}

//---- Shape of the output

TEST(SimFlux, SameSeedSubjectAndTrialGiveIdenticalBytes) {
  const SimulatedTrial a = generate(5, 1, 2, 2);
  const SimulatedTrial b = generate(5, 1, 2, 2);
  const SimulatedTrial other = generate(6, 1, 2, 2);
  const SampleMatrix& x = skin(a).samples;
  const SampleMatrix& y = skin(b).samples;
  ASSERT_EQ(x.rows(), y.rows());
  ASSERT_EQ(x.cols(), y.cols());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), sizeof(float) * x.size()), 0);
  ASSERT_EQ(a.labels.size(), b.labels.size());
  for (size_t k = 0; k < a.labels.size(); ++k) {
    EXPECT_EQ(a.labels[k].t0, b.labels[k].t0);
    EXPECT_EQ(a.labels[k].t1, b.labels[k].t1);
    EXPECT_EQ(a.labels[k].class_name, b.labels[k].class_name);
    EXPECT_EQ(a.labels[k].region, b.labels[k].region);
  }
  EXPECT_EQ(a.recording.metadata, b.recording.metadata);
  const SampleMatrix& z = skin(other).samples;
  EXPECT_TRUE(z.rows() != x.rows() ||
              std::memcmp(x.data(), z.data(), sizeof(float) * x.size()) != 0);
}

TEST(SimFlux, StreamHoldsTheEightRealSerpentinesAtOneKilohertz) {
  const SimulatedTrial& trial = default_trial();
  const Stream& stream = skin(trial);
  EXPECT_EQ(stream.rate_hz, 1000.0);
  EXPECT_EQ(stream.channels,
            (std::vector<std::string>{"x1", "x2", "x3", "x4", "y1", "y2", "y3", "y4"}));
  EXPECT_EQ(stream.samples.cols(), 8);
  EXPECT_EQ(trial.recording.id, "flux-s03-t01");
  EXPECT_EQ(trial.recording.layout_id, "flux");
  EXPECT_EQ(trial.recording.metadata.at("subject"), "s03");
  const double temperature = std::stod(trial.recording.metadata.at("temperature_c"));
  EXPECT_GE(temperature, 10.0);
  EXPECT_LE(temperature, 50.0);
}

TEST(SimFlux, EverySampleIsAFiniteTenBitCount) {
  const SampleMatrix& samples = skin(default_trial()).samples;
  for (Eigen::Index c = 0; c < samples.cols(); ++c)
    for (Eigen::Index n = 0; n < samples.rows(); ++n) {
      const float value = samples(n, c);
      ASSERT_TRUE(std::isfinite(value));
      ASSERT_GE(value, 0.0f);
      ASSERT_LE(value, 1023.0f);
      ASSERT_EQ(value, std::round(value)) << "sample " << n << " channel " << c;
    }
}

TEST(SimFlux, OneGroundTruthLabelPerGestureInsideTheRecording) {
  const SimulatedTrial& trial = default_trial();
  const SkinLayout layout = load_layout("flux");
  ASSERT_EQ(trial.labels.size(), layout.classes.size() * 10);
  std::map<std::string, int> per_class;
  const double duration = skin(trial).duration();
  // The first contact leaves the device a rest at start-up (spec 5.3: V0 from the first window).
  double previous_end = 1.0 - 5.0;
  for (const Label& label : trial.labels) {
    ++per_class[label.class_name];
    EXPECT_EQ(label.recording, trial.recording.id);
    EXPECT_EQ(label.source, LabelSource::kGroundTruth);
    EXPECT_EQ(label.annotator, "simulator");
    EXPECT_EQ(label.confidence, 1.0);
    EXPECT_GT(label.t0, previous_end + 5.0) << "the 5 s window of the previous event must fit";
    EXPECT_GT(label.t1, label.t0);
    EXPECT_LT(label.t1 + 5.0, duration);
    if (zone_of_touch(label.class_name) > 0)
      EXPECT_EQ(label.region.rfind("zone", 0), 0u) << label.region;
    else
      EXPECT_EQ(label.region, "all");
    EXPECT_TRUE(label.region == "all" || layout.find_group(label.region) != nullptr);
    previous_end = label.t1;
  }
  for (const std::string& name : layout.classes) EXPECT_EQ(per_class[name], 10) << name;
}

TEST(SimFlux, RepetitionsOptionSetsTheLabelCount) {
  EXPECT_EQ(generate(3, 0, 0, 2).labels.size(), 12u);
}

//---- Class signatures measured from the samples

TEST(SimFlux, ReleasedPressRelaxesWithAboutSevenSecondTimeConstant) {
  const SimulatedTrial& trial = default_trial();
  const Stream& stream = skin(trial);
  const double first_contact = trial.labels.front().t0;
  std::vector<double> constants;
  for (const Label& label : trial.labels) {
    if (zone_of_touch(label.class_name) == 0) continue;
    // The pressed serpentine: the one that rose most.
    int pressed = 0;
    for (int c = 0; c < stream.channel_count(); ++c)
      if (rise(stream, c, label) > rise(stream, pressed, label)) pressed = c;
    const double rest = mean_between(stream, pressed, 0.2, first_contact - 0.1);
    // Least-squares line through log(signal above rest) from 0.5 s to 4.5 s after release.
    double sum_t = 0, sum_y = 0, sum_tt = 0, sum_ty = 0;
    int points = 0;
    for (int64_t n = stream.index_at(label.t1 + 0.5); n <= stream.index_at(label.t1 + 4.5); ++n) {
      const double above = stream.samples(n, pressed) - rest;
      if (above < 3.0) continue;
      const double t = stream.time_of(n) - label.t1, y = std::log(above);
      sum_t += t, sum_y += y, sum_tt += t * t, sum_ty += t * y, ++points;
    }
    ASSERT_GT(points, 3000) << "press at " << label.t0 << " s left too little signal to fit";
    const double slope = (points * sum_ty - sum_t * sum_y) / (points * sum_tt - sum_t * sum_t);
    constants.push_back(-1.0 / slope);
  }
  ASSERT_EQ(constants.size(), 40u);
  std::sort(constants.begin(), constants.end());
  const double median = constants[constants.size() / 2];
  EXPECT_GT(median, 5.0);
  EXPECT_LT(median, 9.0);
  EXPECT_GT(constants.front(), 4.0);
  EXPECT_LT(constants.back(), 10.0);
}

TEST(SimFlux, TouchOnAZoneExcitesTheSerpentineOverItMost) {
  const SkinLayout layout = load_layout("flux");
  for (int subject = 0; subject < 3; ++subject) {
    const SimulatedTrial trial = subject == 2 ? default_trial() : generate(11, subject, 0);
    const Stream& stream = skin(trial);
    int touches = 0, right = 0;
    for (const Label& label : trial.labels) {
      const int zone = zone_of_touch(label.class_name);
      if (zone == 0) continue;
      ++touches;
      int best = 1;
      double best_rise = -1.0;
      for (int candidate = 1; candidate <= 4; ++candidate) {
        const double value =
            rise(stream, column_of(stream, zone_channel(layout, candidate)), label);
        if (value > best_rise) best = candidate, best_rise = value;
      }
      right += best == zone;
      EXPECT_GT(best_rise, 40.0) << "a press moves the ADC by tens of counts";
    }
    EXPECT_EQ(touches, 40);
    EXPECT_GE(right, 38) << "subject " << subject;
  }
}

TEST(SimFlux, CaressPeaksOnItsFirstZoneBeforeItsLast) {
  const SkinLayout layout = load_layout("flux");
  const SimulatedTrial& trial = default_trial();
  const Stream& stream = skin(trial);
  const int zone1 = column_of(stream, zone_channel(layout, 1));
  const int zone4 = column_of(stream, zone_channel(layout, 4));
  int caresses = 0, ordered = 0;
  for (const Label& label : trial.labels) {
    const double lag = time_of_peak(stream, zone4, label) - time_of_peak(stream, zone1, label);
    if (label.class_name == "caress14") {
      ++caresses;
      ordered += lag > 0.1;
    } else if (label.class_name == "caress41") {
      ++caresses;
      ordered += lag < -0.1;
    }
  }
  EXPECT_EQ(caresses, 20);
  EXPECT_GE(ordered, 19);
}

TEST(SimFlux, NeighboursOfThePressedSerpentineRiseLessThanItButMoreThanFarOnes) {
  const SkinLayout layout = load_layout("flux");
  const SimulatedTrial& trial = default_trial();
  const Stream& stream = skin(trial);
  int events = 0, neighbours_below_pressed = 0, neighbours_above_far = 0;
  double pressed_sum = 0, neighbour_sum = 0, far_sum = 0;
  for (const Label& label : trial.labels) {
    const int zone = zone_of_touch(label.class_name);
    if (zone == 0) continue;
    double pressed = 0, neighbour = 0, far = 0;
    int neighbours = 0, fars = 0;
    for (int other = 1; other <= 4; ++other) {
      const double value = rise(stream, column_of(stream, zone_channel(layout, other)), label);
      if (other == zone)
        pressed = value;
      else if (std::abs(other - zone) == 1)
        neighbour += value, ++neighbours;
      else
        far += value, ++fars;
    }
    neighbour /= neighbours;
    ++events;
    neighbours_below_pressed += neighbour < pressed;
    if (fars > 0) {
      far /= fars;
      neighbours_above_far += neighbour > far;
      far_sum += far;
    }
    pressed_sum += pressed, neighbour_sum += neighbour;
  }
  EXPECT_GE(neighbours_below_pressed, events - 1);
  // Every zone has a far zone on this 4-zone sensor.
  EXPECT_GE(neighbours_above_far, events - 2);
  // Crosstalk is measurable (paper Fig 6), but well below the direct response.
  EXPECT_GT(neighbour_sum, 0.08 * pressed_sum);
  EXPECT_LT(neighbour_sum, 0.6 * pressed_sum);
  EXPECT_GT(neighbour_sum, 1.5 * far_sum);
}

TEST(SimFlux, EveryGestureCrossesTheSpecOnsetAndRelaxesBeforeTheNext) {
  // Spec 5.3/5.5: e = reading / V0 - 1 on the top serpentines, onset at |e| > 0.05, and no new
  // onset until every channel has been back under 0.05 for 0.5 s.
  const SkinLayout layout = load_layout("flux");
  for (int subject : {2, 4}) {
    const SimulatedTrial trial = subject == 2 ? default_trial() : generate(11, subject, 0);
    const Stream& stream = skin(trial);
    std::vector<int> top;
    std::vector<double> rest;
    for (int zone = 1; zone <= 4; ++zone) {
      top.push_back(column_of(stream, zone_channel(layout, zone)));
      rest.push_back(mean_between(stream, top.back(), 0.0, 0.009));
    }
    auto largest_change = [&](double t0, double t1) {
      double largest = 0.0;
      for (size_t c = 0; c < top.size(); ++c)
        for (int64_t n = stream.index_at(t0); n <= stream.index_at(t1); ++n)
          largest = std::max(largest, std::abs(stream.samples(n, top[c]) / rest[c] - 1.0));
      return largest;
    };
    for (size_t k = 0; k < trial.labels.size(); ++k) {
      const Label& label = trial.labels[k];
      EXPECT_GT(largest_change(label.t0, label.t1 + 0.1), 0.05)
          << label.class_name << " at " << label.t0;
      const double next = k + 1 < trial.labels.size() ? trial.labels[k + 1].t0 : stream.duration();
      EXPECT_LT(largest_change(next - 0.6, next - 0.01), 0.05) << "before " << next << " s";
    }
  }
}

//---- Sensor and subjects

TEST(SimFlux, WarmerTrialsRestAtHigherCounts) {
  // Paper 004 Fig 5: the baseline resistance rises 1.03 Ohm/degC.
  std::vector<double> temperatures, rests;
  for (int subject = 0; subject < 6; ++subject) {
    const SimulatedTrial trial = generate(21, subject, 0, 1);
    const Stream& stream = skin(trial);
    temperatures.push_back(std::stod(trial.recording.metadata.at("temperature_c")));
    rests.push_back(mean_between(stream, 0, 0.1, trial.labels.front().t0 - 0.1));
  }
  for (size_t a = 0; a < rests.size(); ++a)
    for (size_t b = 0; b < rests.size(); ++b)
      if (temperatures[a] > temperatures[b] + 2.0) {
        EXPECT_GT(rests[a], rests[b]);
      }
  const auto coldest = std::min_element(temperatures.begin(), temperatures.end());
  const auto warmest = std::max_element(temperatures.begin(), temperatures.end());
  const double slope =
      (rests[warmest - temperatures.begin()] - rests[coldest - temperatures.begin()]) /
      (*warmest - *coldest);
  EXPECT_NEAR(slope, 1.03 * sim::flux_counts_per_ohm(), 0.25);
}

TEST(SimFlux, SubjectsKeepTheirPressDurationAcrossTrials) {
  // Mean press duration per (subject, trial), measured from the ground-truth contact times.
  std::vector<std::vector<double>> means(5);
  for (int subject = 0; subject < 5; ++subject)
    for (int trial = 0; trial < 2; ++trial) {
      double sum = 0;
      int count = 0;
      for (const Label& label : generate(31, subject, trial, 3).labels)
        if (zone_of_touch(label.class_name) > 0) sum += label.t1 - label.t0, ++count;
      means[subject].push_back(sum / count);
    }
  double within = 0, grand = 0;
  std::vector<double> subject_means;
  for (const auto& trials : means) {
    within += std::abs(trials[0] - trials[1]);
    subject_means.push_back(0.5 * (trials[0] + trials[1]));
    grand += subject_means.back();
  }
  within /= 5, grand /= 5;
  double between = 0;
  for (double mean : subject_means) between += std::abs(mean - grand);
  between /= 5;
  EXPECT_GT(between, 1.5 * within);
}

TEST(SimFlux, NegativeRepetitionsAreRefused) {
  SimulationOptions options;
  options.repetitions = -1;
  EXPECT_THROW(skin_record("flux").simulate(load_layout("flux"), options, 0, 0), Error);
}

TEST(SimFlux, LayoutWithoutLayersIsRefusedNamingIt) {
  try {
    sim::flux_geometry(make_strip_layout(4, "strip:4"));
    FAIL() << "a strip has no serpentine layers";
  } catch (const Error& error) {
    EXPECT_NE(error.where().find("strip:4"), std::string::npos);
  }
}

}  // namespace
}  // namespace tactile

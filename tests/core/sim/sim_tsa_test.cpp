#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <set>

#include "tactile/error.h"
#include "tactile/sim/tsa_sim.h"
#include "tactile/stats/statistics.h"

namespace tactile {
namespace {

//---- Measuring events from the samples alone ------------------------------------------------
// These helpers read only the layout, the samples and the label's time span, region and note:
// a small independent event analysis (spec §2.3-2.10), not the generator's internal state.

constexpr double kFrame = 0.125;
constexpr double kActiveRise = 10.0;  // counts above the pre-touch baseline (~6 noise sigma)

struct PadOnSheet {
  int column = 0;
  double x = 0.0;  // column index on the sheet (pitch units)
  double y = 0.0;  // row index on the sheet
};

// Pads of every sheet in `region`, with their 4x4 grid coordinates (x right, y down).
std::map<std::string, std::vector<PadOnSheet>> sheets_in_region(const SkinLayout& layout,
                                                                const std::string& region) {
  const Group* location = layout.find_group(region);
  const std::set<int64_t> inside(location->taxels.begin(), location->taxels.end());
  std::map<std::string, std::vector<PadOnSheet>> result;
  for (const Group& group : layout.groups) {
    if (group.kind != "sheet" || !inside.count(group.taxels.front())) continue;
    double left = 1e9, top = 1e9;
    for (int64_t id : group.taxels) {
      left = std::min(left, layout.find_taxel(id)->position.x);
      top = std::min(top, layout.find_taxel(id)->position.y);
    }
    for (int64_t id : group.taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      result[group.id].push_back({taxel->channels.front(),
                                  std::round((taxel->position.x - left) / 7.0),
                                  std::round((taxel->position.y - top) / 7.0)});
    }
  }
  return result;
}

struct Event {
  int frames = 0;                 // frames with an active pad (N_ev)
  int most_pads = 0;              // largest number of active pads in one frame
  std::vector<Point2> centroids;  // per active frame, pitch units (eq 7)
};

// The event of one label on the sheet of its region with the most active frames (spec §2.1).
Event measure_event(const SkinLayout& layout, const Stream& stream, const Label& label) {
  const int64_t first = static_cast<int64_t>(std::floor((label.t0 - 0.2) / kFrame));
  const int64_t last = static_cast<int64_t>(std::floor((label.t1 + 0.2) / kFrame));
  // The hand was away for at least a second before the contact.
  const int64_t idle_first = static_cast<int64_t>(std::ceil((label.t0 - 0.95) / kFrame));
  const int64_t idle_last = static_cast<int64_t>(std::floor((label.t0 - 0.3) / kFrame)) - 1;
  Event best;
  for (const auto& [sheet, pads] : sheets_in_region(layout, label.region)) {
    Event event;
    for (int64_t frame = first; frame <= last; ++frame) {
      int active = 0;
      double sum_x = 0.0, sum_y = 0.0;
      for (const PadOnSheet& pad : pads) {
        double baseline = 0.0;
        for (int64_t idle = idle_first; idle <= idle_last; ++idle)
          baseline += stream.samples(idle, pad.column);
        baseline /= static_cast<double>(idle_last - idle_first + 1);
        if (stream.samples(frame, pad.column) - baseline > kActiveRise) {
          ++active;
          sum_x += pad.x;
          sum_y += pad.y;
        }
      }
      if (active == 0) continue;
      ++event.frames;
      event.most_pads = std::max(event.most_pads, active);
      event.centroids.push_back({sum_x / active, sum_y / active});
    }
    if (event.frames > best.frames) best = event;
  }
  return best;
}

// Spec §2.10: direction code of a centroid path (A_min = 0.5, rho = 0.5, d_min = 0.5).
int direction_code(const std::vector<Point2>& path) {
  const size_t count = path.size();
  if (count < 2) return 0;
  const double dx = path.back().x - path.front().x;
  const double dy = path.back().y - path.front().y;
  const double net = std::hypot(dx, dy);
  double length = 0.0, area = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const Point2& a = path[k];
    const Point2& b = path[(k + 1) % count];
    if (k + 1 < count) length += std::hypot(b.x - a.x, b.y - a.y);
    area += 0.5 * (a.x * b.y - b.x * a.y);
  }
  if (count >= 3 && std::abs(area) >= 0.5 && net < 0.5 * length) return area > 0 ? 1 : 2;
  if (net < 0.5) return 0;
  double angle = std::atan2(-dy, dx) * 180.0 / std::numbers::pi;
  if (angle < 0) angle += 360.0;
  const int sector = static_cast<int>(std::floor((angle + 22.5) / 45.0)) % 8;
  static const int codes[8] = {3, 9, 6, 8, 4, 10, 5, 7};
  return codes[sector];
}

// Largest distance of a centroid from the event's mean centroid (pitch units).
double centroid_wander(const Event& event) {
  Point2 mean;
  for (const Point2& c : event.centroids) {
    mean.x += c.x / event.centroids.size();
    mean.y += c.y / event.centroids.size();
  }
  double wander = 0.0;
  for (const Point2& c : event.centroids)
    wander = std::max(wander, std::hypot(c.x - mean.x, c.y - mean.y));
  return wander;
}

// Largest distance between two centroids of the event (pitch units).
double centroid_travel(const Event& event) {
  double travel = 0.0;
  for (const Point2& a : event.centroids)
    for (const Point2& b : event.centroids)
      travel = std::max(travel, std::hypot(a.x - b.x, a.y - b.y));
  return travel;
}

std::string note_value(const std::string& note, const std::string& key) {
  const size_t start = note.find(key + "=");
  if (start == std::string::npos) return {};
  const size_t value = start + key.size() + 1;
  return note.substr(value, note.find(' ', value) - value);
}

int direction_code_named(const std::string& name) {
  for (int code = 0; code <= 10; ++code)
    if (name == sim::tsa::direction_name(static_cast<sim::tsa::Direction>(code))) return code;
  return -1;
}

struct Measured {
  Label label;
  Event event;
};

// Events of several subjects' first trials, by class name.
std::map<std::string, std::vector<Measured>> measure_subjects(int subjects) {
  const SkinLayout layout = load_layout("tsa");
  SimulationOptions options;
  options.seed = 11;
  std::map<std::string, std::vector<Measured>> by_class;
  for (int subject = 0; subject < subjects; ++subject) {
    const SimulatedTrial trial = simulate_tsa_trial(layout, options, subject, 0);
    for (const Label& label : trial.labels)
      by_class[label.class_name].push_back(
          {label, measure_event(layout, trial.recording.streams.front(), label)});
  }
  return by_class;
}

const std::map<std::string, std::vector<Measured>>& measured() {
  static const auto events = measure_subjects(6);
  return events;
}

std::vector<double> values_of(const std::string& class_name, double (*value)(const Measured&)) {
  std::vector<double> values;
  for (const Measured& m : measured().at(class_name)) values.push_back(value(m));
  return values;
}

//---- Trial structure -------------------------------------------------------------------------

TEST(SimTsa, SameSeedGivesIdenticalBytesAndAnotherSeedDiffers) {
  const SkinLayout layout = load_layout("tsa");
  SimulationOptions options;
  options.seed = 5;
  const SimulatedTrial a = simulate_tsa_trial(layout, options, 1, 2);
  const SimulatedTrial b = simulate_tsa_trial(layout, options, 1, 2);
  const SampleMatrix& samples_a = a.recording.streams.front().samples;
  const SampleMatrix& samples_b = b.recording.streams.front().samples;
  ASSERT_EQ(samples_a.rows(), samples_b.rows());
  ASSERT_EQ(samples_a.cols(), samples_b.cols());
  EXPECT_EQ(0, std::memcmp(samples_a.data(), samples_b.data(), samples_a.size() * sizeof(float)));
  ASSERT_EQ(a.labels.size(), b.labels.size());
  for (size_t k = 0; k < a.labels.size(); ++k) {
    EXPECT_EQ(a.labels[k].t0, b.labels[k].t0);
    EXPECT_EQ(a.labels[k].t1, b.labels[k].t1);
    EXPECT_EQ(a.labels[k].class_name, b.labels[k].class_name);
    EXPECT_EQ(a.labels[k].note, b.labels[k].note);
  }
  options.seed = 6;
  const SimulatedTrial c = simulate_tsa_trial(layout, options, 1, 2);
  const SampleMatrix& samples_c = c.recording.streams.front().samples;
  EXPECT_TRUE(samples_c.rows() != samples_a.rows() ||
              std::memcmp(samples_a.data(), samples_c.data(), samples_a.size() * sizeof(float)) !=
                  0);
}

TEST(SimTsa, OneGroundTruthLabelPerGestureInsideTheRecording) {
  const SkinLayout layout = load_layout("tsa");
  SimulationOptions options;
  const SimulatedTrial trial = simulate_tsa_trial(layout, options, 0, 0);
  ASSERT_EQ(trial.labels.size(), 6u * sim::tsa::kDefaultRepetitions);
  const Stream& stream = trial.recording.streams.front();
  EXPECT_EQ(stream.name, "skin");
  EXPECT_EQ(stream.rate_hz, 8.0);
  EXPECT_EQ(trial.recording.id, "tsa-s01-t01");
  EXPECT_EQ(trial.recording.layout_id, "tsa");
  EXPECT_EQ(trial.recording.metadata.at("group"), "male");
  std::map<std::string, int> per_class;
  double previous_end = 0.0;
  for (const Label& label : trial.labels) {
    EXPECT_GT(label.t0, previous_end + 1.0);  // rests of at least a second
    EXPECT_LT(label.t0, label.t1);
    EXPECT_LT(label.t1, stream.duration() - 1.0);  // a tail of rest
    previous_end = label.t1;
    ++per_class[label.class_name];
    EXPECT_EQ(label.recording, trial.recording.id);
    EXPECT_EQ(label.source, LabelSource::kGroundTruth);
    EXPECT_EQ(label.annotator, "simulator");
    const Group* region = layout.find_group(label.region);
    ASSERT_NE(region, nullptr) << label.region;
    EXPECT_EQ(region->kind, "location");
  }
  for (const std::string& class_name : layout.classes)
    EXPECT_EQ(per_class[class_name], sim::tsa::kDefaultRepetitions) << class_name;

  options.repetitions = 2;
  EXPECT_EQ(simulate_tsa_trial(layout, options, 1, 0).labels.size(), 12u);
  EXPECT_EQ(simulate_tsa_trial(layout, options, 1, 0).recording.metadata.at("group"), "female");
}

TEST(SimTsa, CountsAreWholeTwelveBitWordsAndTouchesRaiseThem) {
  const SkinLayout layout = load_layout("tsa");
  const SimulatedTrial trial = simulate_tsa_trial(layout, SimulationOptions{}, 2, 1);
  const SampleMatrix& samples = trial.recording.streams.front().samples;
  ASSERT_EQ(samples.cols(), 672);
  for (Eigen::Index k = 0; k < samples.size(); ++k) {
    const float value = samples.data()[k];
    ASSERT_TRUE(std::isfinite(value));
    ASSERT_GE(value, 0.0f);
    ASSERT_LE(value, 4095.0f);
    ASSERT_EQ(value, std::round(value));
  }
  // Every gesture shows on its region; between gestures the skin is quiet.
  for (const Label& label : trial.labels) {
    const Event event = measure_event(layout, trial.recording.streams.front(), label);
    EXPECT_GE(event.frames, 1) << label.class_name << " at " << label.t0;
  }
}

TEST(SimTsa, BadOptionsAndLayoutsAreReportedAsErrors) {
  const SkinLayout layout = load_layout("tsa");
  SimulationOptions options;
  options.repetitions = -1;
  EXPECT_THROW(simulate_tsa_trial(layout, options, 0, 0), Error);
  EXPECT_THROW(simulate_tsa_trial(layout, SimulationOptions{}, -1, 0), Error);
  SkinLayout grid = make_grid_layout(4, 4);
  grid.classes = layout.classes;
  try {
    simulate_tsa_trial(grid, SimulationOptions{}, 0, 0);
    FAIL() << "a layout without sheets was accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), grid.id);
    EXPECT_NE(error.message().find("sheet"), std::string::npos);
  }
}

//---- Front-end pieces ------------------------------------------------------------------------

TEST(SimTsaFrontEnd, PadCoverageGoesFromOffToOnAcrossTheFootprintEdge) {
  sim::tsa::Footprint palm;
  palm.centre = {0.0, 0.0};
  palm.half_length = 20.0;
  palm.half_width = 15.0;
  EXPECT_DOUBLE_EQ(sim::tsa::pad_coverage({3.0, 2.0}, 3.5, palm), 1.0);
  EXPECT_DOUBLE_EQ(sim::tsa::pad_coverage({40.0, 0.0}, 3.5, palm), 0.0);
  // Edge through the pad's centre: half covered; the long axis reaches further than the short.
  EXPECT_NEAR(sim::tsa::pad_coverage({20.0, 0.0}, 3.5, palm), 0.5, 1e-9);
  EXPECT_NEAR(sim::tsa::pad_coverage({0.0, 15.0}, 3.5, palm), 0.5, 1e-9);
  EXPECT_GT(sim::tsa::pad_coverage({18.0, 0.0}, 3.5, palm), 0.5);
  EXPECT_LT(sim::tsa::pad_coverage({0.0, 17.0}, 3.5, palm), 0.5);
  palm.angle = std::numbers::pi / 2;  // long axis along y now
  EXPECT_GT(sim::tsa::pad_coverage({0.0, 18.0}, 3.5, palm), 0.5);
  // A fingertip smaller than the pad covers at most its own area.
  sim::tsa::Footprint tip;
  tip.half_length = 2.0;
  tip.half_width = 2.0;
  EXPECT_NEAR(sim::tsa::pad_coverage({0.0, 0.0}, 4.0, tip), 0.25, 1e-9);
}

TEST(SimTsaFrontEnd, CouplingRisesAroundContactAndFootprintFollowsTheDirection) {
  sim::tsa::Touch touch;
  touch.direction = sim::tsa::Direction::kDownToUp;
  touch.contact_start = 1.0;
  touch.contact_end = 2.0;
  touch.approach = 0.04;
  touch.start = {0.0, 10.0};
  touch.end = {0.0, -10.0};
  EXPECT_EQ(sim::tsa::coupling_at(touch, 0.9), 0.0);
  EXPECT_NEAR(sim::tsa::coupling_at(touch, 1.0), 0.5, 1e-9);
  EXPECT_EQ(sim::tsa::coupling_at(touch, 1.5), 1.0);
  EXPECT_EQ(sim::tsa::coupling_at(touch, 2.1), 0.0);
  EXPECT_NEAR(sim::tsa::footprint_at(touch, 0.5).centre.y, 10.0, 1e-9);
  EXPECT_NEAR(sim::tsa::footprint_at(touch, 1.5).centre.y, 0.0, 1e-9);
  EXPECT_NEAR(sim::tsa::footprint_at(touch, 3.0).centre.y, -10.0, 1e-9);
  const Point2 up = sim::tsa::direction_vector(sim::tsa::Direction::kDownToUp);
  EXPECT_EQ(up.y, -1.0);  // y grows downwards on the map
}

//---- Class signatures, measured from the samples ---------------------------------------------

TEST(SimTsaSignature, PalmClassesCoverMorePadsThanFingerClasses) {
  auto pads = [](const Measured& m) { return static_cast<double>(m.event.most_pads); };
  std::vector<double> palm = values_of("T5", pads), finger = values_of("T3", pads);
  for (double v : values_of("T6", pads)) palm.push_back(v);
  for (double v : values_of("T4", pads)) finger.push_back(v);
  std::sort(palm.begin(), palm.end());
  std::sort(finger.begin(), finger.end());
  // Nine in ten palm events cover more pads than nine in ten finger events.
  EXPECT_GT(palm[palm.size() / 10], finger[finger.size() * 9 / 10]);
  EXPECT_GE(stats::median(palm), 3.0 * stats::median(finger));
}

TEST(SimTsaSignature, SlidingCentroidsTravelWhileMomentaryOnesStayWithinOnePitch) {
  for (const char* sliding : {"T2", "T3", "T6"}) {
    int moved = 0, straight = 0;
    for (const Measured& m : measured().at(sliding)) {
      const int chosen = direction_code_named(note_value(m.label.note, "direction"));
      if (chosen < 3) continue;  // circles may return near their start
      ++straight;
      moved += centroid_travel(m.event) > 1.0;
    }
    ASSERT_GT(straight, 5) << sliding;
    EXPECT_GE(moved, 0.9 * straight) << sliding;
  }
  for (const char* momentary : {"T1", "T5"}) {
    int still = 0;
    const auto& events = measured().at(momentary);
    for (const Measured& m : events) still += centroid_wander(m.event) <= 1.0;
    EXPECT_GE(still, 0.95 * events.size()) << momentary;
  }
}

TEST(SimTsaSignature, MomentaryEventsLastFewerFramesThanSlidingOnes) {
  auto frames = [](const Measured& m) { return static_cast<double>(m.event.frames); };
  for (const char* momentary : {"T1", "T5"}) {
    const double taps = stats::median(values_of(momentary, frames));
    EXPECT_LE(taps, 3.0) << momentary;
    for (const char* sliding : {"T2", "T3", "T6"})
      EXPECT_LT(taps, stats::median(values_of(sliding, frames))) << momentary << " vs " << sliding;
  }
  // Slow slides last longest.
  EXPECT_GT(stats::median(values_of("T2", frames)), 2.0 * stats::median(values_of("T3", frames)));
}

TEST(SimTsaSignature, SlidingDirectionsFromTheCentroidPathMatchTheChosenOnes) {
  for (const char* sliding : {"T2", "T3", "T6"}) {
    int agree = 0;
    const auto& events = measured().at(sliding);
    for (const Measured& m : events) {
      const int chosen = direction_code_named(note_value(m.label.note, "direction"));
      ASSERT_GE(chosen, 1) << m.label.note;
      agree += direction_code(m.event.centroids) == chosen;
    }
    EXPECT_GE(agree, 0.7 * events.size()) << sliding;
  }
  // Stationary touches mostly read as "no direction"; a touch that lands or lifts mid-scan
  // can shift its first or last centroid by half a pitch, so not always. Slides almost never.
  auto none_share = [](std::initializer_list<const char*> classes) {
    int none = 0, count = 0;
    for (const char* class_name : classes)
      for (const Measured& m : measured().at(class_name)) {
        ++count;
        none += direction_code(m.event.centroids) == 0;
      }
    return static_cast<double>(none) / count;
  };
  EXPECT_GE(none_share({"T1", "T4", "T5"}), 0.5);
  EXPECT_LE(none_share({"T2", "T3", "T6"}), 0.1);
}

}  // namespace
}  // namespace tactile

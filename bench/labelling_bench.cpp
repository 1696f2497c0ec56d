// Labelling benchmark (issue "Labelling in the workbench"), one run so the figures are
// ratios:
//   - whole workbench frames (skin, plot, the timeline's lanes, the label table) over a
//     1-hour recording whose lanes hold 100,000 labels against the same with 100: the
//     same views, zooming from the whole hour down to 2 s, panning, zooming out;
//   - the lanes' own part: lane_spans over those views;
//   - the time an edit takes to be committed (LabelStore::add: one transaction,
//     synchronous=FULL, WAL) in the store of 100,000 labels.
//   labelling_bench DIR
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_support.h"
#include "osmesa_renderer.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/lanes.h"
#include "tactile/labelstore/label_store.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
using tactile::bench::percentile;
constexpr double kSeconds = 3600.0;
constexpr double kRate = 100.0;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A 1-hour grid:4x4 recording and a label store with `count` labels over it, in three
// lanes (ground truth, an annotator, a segmenter).
std::string make_workspace(const std::filesystem::path& folder, int count) {
  std::filesystem::create_directories(folder);
  const std::string recording_path = (folder / "hour.h5").string();
  if (!std::filesystem::exists(recording_path)) {
    tactile::Stream stream;
    stream.name = "skin";
    stream.rate_hz = kRate;
    for (int k = 0; k < 16; ++k) stream.channels.push_back("ch" + std::to_string(k));
    const auto samples = static_cast<int64_t>(kSeconds * kRate);
    stream.samples.resize(samples, 16);
    std::mt19937 random(1);
    std::normal_distribution<float> noise(0.0f, 0.01f);
    for (int64_t row = 0; row < samples; ++row)
      for (int column = 0; column < 16; ++column)
        stream.samples(row, column) = ((row / 300) % 7 == column % 7 ? 0.8f : 0.0f) + noise(random);
    tactile::Recording recording;
    recording.id = "hour";
    recording.layout_id = "grid:4x4";
    recording.streams = {std::move(stream)};
    tactile::write_recording(recording_path, recording);
  }
  const std::string store_path = (folder / "labels.db").string();
  std::filesystem::remove(store_path);
  tactile::LabelStore store(store_path);
  std::vector<tactile::Label> labels;
  const char* classes[] = {"pat", "slap", "stroke", "poke"};
  const double spacing = kSeconds / (count / 3.0 + 1.0);
  for (int k = 0; k < count; ++k) {
    tactile::Label label;
    label.recording = "hour";
    const int lane = k % 3;
    label.t0 = (k / 3) * spacing + 0.01 * lane;
    label.t1 = label.t0 + spacing * 0.6;
    label.class_name = classes[k % 4];
    label.source = lane == 0   ? tactile::LabelSource::kGroundTruth
                   : lane == 1 ? tactile::LabelSource::kManual
                               : tactile::LabelSource::kSegmenter;
    label.annotator = lane == 0 ? "simulator" : lane == 1 ? "ana" : "segmenter:threshold";
    labels.push_back(label);
  }
  store.add_many(labels);
  return recording_path;
}

// A user's path over the hour: zoom in about a point from all of it to 2 s, pan,
// zoom out again.
std::vector<std::pair<double, double>> views() {
  std::vector<std::pair<double, double>> result;
  double centre = 1234.5, span = kSeconds;
  while (span > 2.0) {
    result.emplace_back(std::max(0.0, centre - span / 2), std::min(kSeconds, centre + span / 2));
    span *= 0.8;
  }
  for (int k = 0; k < 40; ++k) {
    centre += span / 5;
    result.emplace_back(centre - span / 2, centre + span / 2);
  }
  while (span < kSeconds) {
    span = std::min(kSeconds, span / 0.8);
    result.emplace_back(std::max(0.0, centre - span / 2), std::min(kSeconds, centre + span / 2));
  }
  return result;
}

struct Figures {
  double frame_median = 0, frame_p90 = 0, lanes_median_us = 0;
  double own_median = 0, own_p90 = 0;  // the workbench's own work: data, lanes, draw lists
};

Figures browse(const std::string& recording) {
  tactile::OffscreenRenderer renderer(1400, 800);
  tactile::WorkbenchOptions options;
  options.open_path = recording;
  options.settings_path =
      (std::filesystem::path(recording).parent_path() / "settings.json").string();
  tactile::Workbench workbench(options);
  const tactile::Document& document = *workbench.state().document;
  std::vector<double> frames, lanes, own;
  for (int round = 0; round < 2; ++round)
    for (const auto& [t0, t1] : views()) {
      tactile::WorkbenchState& state = workbench.state();
      state.plot.view_t0 = t0;
      state.plot.view_t1 = t1;
      state.plot.fitted = true;
      state.clock.seek((t0 + t1) / 2);
      const auto begin = Clock::now();
      renderer.new_frame();
      workbench.frame(0.0);
      // Up to here the workbench's own work; the rest is llvmpipe filling pixels, whose
      // cost is the area the blocks cover, not the number of labels behind them.
      const double built = milliseconds_since(begin);
      renderer.render();
      const double frame = milliseconds_since(begin);
      const auto lanes_begin = Clock::now();
      size_t spans = 0;
      for (const tactile::LaneIndex& lane : document.lanes.lanes)
        spans += tactile::lane_spans(lane, t0, t1, 1100).size();
      const double lane_time = milliseconds_since(lanes_begin) * 1000.0;
      if (spans > 100000) std::printf("impossible\n");
      if (round == 1) frames.push_back(frame), lanes.push_back(lane_time), own.push_back(built);
    }
  return {percentile(frames, 0.5), percentile(frames, 0.9), percentile(lanes, 0.5),
          percentile(own, 0.5), percentile(own, 0.9)};
}

double commit_ms(const std::string& store_path) {
  tactile::LabelStore store(store_path);
  std::vector<double> times;
  for (int k = 0; k < 60; ++k) {
    tactile::Label label;
    label.recording = "hour";
    label.t0 = 10.0 + k;
    label.t1 = label.t0 + 0.5;
    label.class_name = "pat";
    label.annotator = "bench";
    const auto begin = Clock::now();
    store.add(label);
    times.push_back(milliseconds_since(begin));
  }
  return percentile(times, 0.5);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: labelling_bench DIR\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  const std::string few = make_workspace(folder / "few", 100);
  const std::string many = make_workspace(folder / "many", 100000);
  // Alternated, three times each, and the median of the runs' medians: llvmpipe's
  // threads make single runs vary by a tenth.
  std::vector<Figures> few_runs, many_runs;
  for (int run = 0; run < 3; ++run) {
    few_runs.push_back(browse(few));
    many_runs.push_back(browse(many));
  }
  auto middle = [](std::vector<Figures> runs) {
    Figures result;
    auto pick = [&](double Figures::*field) {
      std::vector<double> values;
      for (const Figures& figures : runs) values.push_back(figures.*field);
      result.*field = percentile(values, 0.5);
    };
    for (double Figures::*field :
         {&Figures::frame_median, &Figures::frame_p90, &Figures::lanes_median_us,
          &Figures::own_median, &Figures::own_p90})
      pick(field);
    return result;
  };
  const Figures with_few = middle(few_runs);
  const Figures with_many = middle(many_runs);
  const double commit = commit_ms((folder / "many" / "labels.db").string());
  std::printf("workbench frame, 1 h, lanes of 100 labels: %.2f ms median, %.2f ms p90\n",
              with_few.frame_median, with_few.frame_p90);
  std::printf("workbench frame, 1 h, lanes of 100,000 labels: %.2f ms median, %.2f ms p90\n",
              with_many.frame_median, with_many.frame_p90);
  std::printf("  100,000 / 100: %.2fx median, %.2fx p90 (target <= 1.2x)\n",
              with_many.frame_median / with_few.frame_median,
              with_many.frame_p90 / with_few.frame_p90);
  std::printf(
      "the workbench's own work per frame (data, lanes, draw lists): %.3f ms vs %.3f ms "
      "median: %.2fx; p90 %.2fx\n",
      with_many.own_median, with_few.own_median, with_many.own_median / with_few.own_median,
      with_many.own_p90 / with_few.own_p90);
  std::printf("lanes' own part (lane_spans, 3 lanes): %.1f us vs %.1f us median\n",
              with_many.lanes_median_us, with_few.lanes_median_us);
  std::printf(
      "an edit committed (LabelStore::add, synchronous=FULL) in the store of 100,000: %.2f ms "
      "median\n",
      commit);
  return 0;
}

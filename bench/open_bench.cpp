// Opening a recording costs the same whatever its length (issue 41): the whole workbench,
// headless, opens a minute and an hour of Robovie's 274 films (named as its layout names them,
// so the skin view reads them) and draws until the skin and the plot have been drawn; nine
// runs of each, alternated, the median of each and their ratio, and of each of the three
// frames. The files are made once in
// DIR (rest with 8-bit noise, a touch on a few films every 20 s). Then the parts that read the
// file, alone: the source, the skin's colour scale, the first instant.
//   open_bench DIR
//   OPEN_BENCH_VIEW=signals open_bench DIR   (only that view, over the whole window)
//   OPEN_BENCH_NO_PARTS=1 open_bench DIR     (the openings alone)
//   OPEN_BENCH_ONLY=hour open_bench DIR      (one of the two files, to profile it)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_support.h"
#include "process_memory.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/signal/display_scale.h"
#include "tactile/signal/sample_source.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 105.0;  // Robovie's films as the simulator records them
constexpr int kRuns = 9;         // openings of each file, alternated; the medians are reported

void make(const std::string& path, double seconds) {
  if (std::filesystem::exists(path)) return;
  const tactile::SkinLayout layout = tactile::load_layout("robovie");
  const auto samples = static_cast<int64_t>(seconds * kRate);
  const auto channels = static_cast<int>(layout.channels.size());
  tactile::Stream stream;
  stream.name = "skin";
  stream.rate_hz = kRate;
  for (const tactile::Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  stream.samples.resize(samples, channels);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> noise(-2, 2);
  for (int channel = 0; channel < channels; ++channel) {
    float* column = stream.samples.col(channel).data();
    for (int64_t index = 0; index < samples; ++index) {
      const int64_t phase = (index + channel * 37) % 2100;
      const float touch = phase < 150 && channel % 9 == 0 ? 60.0f * std::sin(phase * 0.02f) : 0.0f;
      column[index] = static_cast<float>(noise(random)) + std::round(touch);
    }
  }
  tactile::Recording recording;
  recording.id = std::filesystem::path(path).stem().string();
  recording.layout_id = "robovie";
  recording.streams = {std::move(stream)};
  tactile::write_recording(path, recording);
}

// Seconds from asking to open until three frames are drawn (the first draws every view; the
// skin's colour scale and the plot's columns come from the file's overview): the opening
// itself (the document, its source, the label store) and the three frames.
struct Opened {
  double open = 0.0;
  double frames = 0.0;
  double frame[3] = {};  // each frame: building it, then drawing it
  double total() const { return open + frames; }
};

Opened open_once(tactile::bench::PacedFrames& frames, const std::string& path,
                 const std::string& folder) {
  tactile::WorkbenchOptions options;
  options.open_path = path;
  options.settings_path = folder + "/settings.json";
  options.labels_path = folder + "/open-bench-labels.db";
  options.annotator = "bench";
  if (const char* view = std::getenv("OPEN_BENCH_VIEW")) options.only_view = view;
  Opened opened;
  const auto start = Clock::now();
  tactile::Workbench workbench(options);
  const auto open = Clock::now();
  opened.open = std::chrono::duration<double>(open - start).count();
  for (int k = 0; k < 3; ++k) {
    const auto begun = Clock::now();
    frames.renderer.new_frame();
    workbench.frame(1.0 / 60.0);
    frames.renderer.render();
    opened.frame[k] = std::chrono::duration<double>(Clock::now() - begun).count();
  }
  opened.frames = std::chrono::duration<double>(Clock::now() - open).count();
  if (!workbench.state().error.empty())
    std::fprintf(stderr, "open_bench: %s\n", workbench.state().error.c_str());
  return opened;
}

// The parts of an opening that read the file, timed alone on a source of their own: opening
// the source (attributes, the overview and its pyramid), the skin's colour scale over every
// channel (display_scale.h) and the values of every channel at the first instant.
struct Parts {
  double source = 0.0, scale = 0.0, instant = 0.0;
};

Parts parts_of(const std::string& path) {
  Parts parts;
  auto start = Clock::now();
  const tactile::FileSampleSource source(path);
  parts.source = std::chrono::duration<double>(Clock::now() - start).count();
  std::vector<int> columns(static_cast<size_t>(source.channel_count()));
  for (int k = 0; k < source.channel_count(); ++k) columns[static_cast<size_t>(k)] = k;
  start = Clock::now();
  const tactile::RestScale scale = tactile::rest_scale(source, columns);
  parts.scale = std::chrono::duration<double>(Clock::now() - start).count();
  start = Clock::now();
  const std::vector<float> values = source.values_at(0);
  parts.instant = std::chrono::duration<double>(Clock::now() - start).count();
  return parts;
}

double median_of(const std::vector<Opened>& runs, double (*part)(const Opened&)) {
  std::vector<double> values;
  for (const Opened& run : runs) values.push_back(part(run));
  return tactile::bench::percentile(values, 0.5);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: open_bench DIR\n");
    return 2;
  }
  const std::string folder = argv[1];
  std::filesystem::create_directories(folder);
  const std::string minute = folder + "/robovie-1min.h5", hour = folder + "/robovie-60min.h5";
  make(minute, 60.0);
  make(hour, 3600.0);
  tactile::bench::PacedFrames frames(1600, 900);
  open_once(frames, minute, folder);  // warm up: fonts, the layout, the file system's cache
  open_once(frames, hour, folder);
  std::vector<Opened> minutes, hours;
  // OPEN_BENCH_ONLY=minute or hour: that file alone, to profile it.
  const std::string only = std::getenv("OPEN_BENCH_ONLY") ? std::getenv("OPEN_BENCH_ONLY") : "";
  for (int run = 0; run < kRuns; ++run) {
    if (only != "hour") minutes.push_back(open_once(frames, minute, folder));
    if (only != "minute") hours.push_back(open_once(frames, hour, folder));
  }
  std::vector<Parts> minute_parts, hour_parts;
  for (int run = 0; run < 5 && !std::getenv("OPEN_BENCH_NO_PARTS"); ++run) {
    minute_parts.push_back(parts_of(minute));
    hour_parts.push_back(parts_of(hour));
  }
  const auto part_median = [](const std::vector<Parts>& runs, double Parts::*part) {
    std::vector<double> values;
    for (const Parts& run : runs) values.push_back(run.*part);
    return tactile::bench::percentile(values, 0.5);
  };
  std::printf(
      "{\"parts\": \"minute / hour, s\", \"source\": [%.4f, %.4f], \"colour_scale\": [%.4f, %.4f], "
      "\"instant\": [%.4f, %.4f]}\n",
      part_median(minute_parts, &Parts::source), part_median(hour_parts, &Parts::source),
      part_median(minute_parts, &Parts::scale), part_median(hour_parts, &Parts::scale),
      part_median(minute_parts, &Parts::instant), part_median(hour_parts, &Parts::instant));
  const auto total = [](const Opened& run) { return run.total(); };
  const auto open = [](const Opened& run) { return run.open; };
  const auto drawn = [](const Opened& run) { return run.frames; };
  const auto first = [](const Opened& run) { return run.frame[0]; };
  const auto second = [](const Opened& run) { return run.frame[1]; };
  const auto third = [](const Opened& run) { return run.frame[2]; };
  std::printf("{\"frames_minute_s\": [%.3f, %.3f, %.3f], \"frames_hour_s\": [%.3f, %.3f, %.3f]}\n",
              median_of(minutes, first), median_of(minutes, second), median_of(minutes, third),
              median_of(hours, first), median_of(hours, second), median_of(hours, third));
  std::printf(
      "{\"minute_s\": %.3f, \"hour_s\": %.3f, \"hour_over_minute\": %.2f, "
      "\"open_minute_s\": %.3f, \"open_hour_s\": %.3f, "
      "\"three_frames_minute_s\": %.3f, \"three_frames_hour_s\": %.3f, \"peak_mb\": %.0f}\n",
      median_of(minutes, total), median_of(hours, total),
      median_of(hours, total) / median_of(minutes, total), median_of(minutes, open),
      median_of(hours, open), median_of(minutes, drawn), median_of(hours, drawn),
      tactile::bench::peak_memory_mb());
  return 0;
}

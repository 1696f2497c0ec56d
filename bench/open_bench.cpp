// Opening a recording costs the same whatever its length (issue 41): the whole workbench,
// headless, opens a minute and an hour of Robovie's 274 films (named as its layout names them,
// so the skin view reads them) and draws until the skin and the plot have been drawn; five
// runs of each, alternated, the median of each and their ratio. The files are made once in
// DIR (rest with 8-bit noise, a touch on a few films every 20 s).
//   open_bench DIR
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_support.h"
#include "process_memory.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/layout/skin_layout.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kRate = 105.0;  // Robovie's films as the simulator records them

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
  double total() const { return open + frames; }
};

Opened open_once(tactile::bench::PacedFrames& frames, const std::string& path,
                 const std::string& folder) {
  tactile::WorkbenchOptions options;
  options.open_path = path;
  options.settings_path = folder + "/settings.json";
  options.labels_path = folder + "/open-bench-labels.db";
  options.annotator = "bench";
  Opened opened;
  const auto start = Clock::now();
  tactile::Workbench workbench(options);
  const auto open = Clock::now();
  opened.open = std::chrono::duration<double>(open - start).count();
  for (int k = 0; k < 3; ++k) {
    frames.renderer.new_frame();
    workbench.frame(1.0 / 60.0);
    frames.renderer.render();
  }
  opened.frames = std::chrono::duration<double>(Clock::now() - open).count();
  if (!workbench.state().error.empty())
    std::fprintf(stderr, "open_bench: %s\n", workbench.state().error.c_str());
  return opened;
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
  for (int run = 0; run < 5; ++run) {
    minutes.push_back(open_once(frames, minute, folder));
    hours.push_back(open_once(frames, hour, folder));
  }
  const auto total = [](const Opened& run) { return run.total(); };
  const auto open = [](const Opened& run) { return run.open; };
  const auto drawn = [](const Opened& run) { return run.frames; };
  std::printf("{\"minute_s\": %.3f, \"hour_s\": %.3f, \"hour_over_minute\": %.2f, "
              "\"open_minute_s\": %.3f, \"open_hour_s\": %.3f, "
              "\"three_frames_minute_s\": %.3f, \"three_frames_hour_s\": %.3f, \"peak_mb\": %.0f}\n",
              median_of(minutes, total), median_of(hours, total),
              median_of(hours, total) / median_of(minutes, total), median_of(minutes, open),
              median_of(hours, open), median_of(minutes, drawn), median_of(hours, drawn),
              tactile::bench::peak_memory_mb());
  return 0;
}

// The workbench on long recordings, for bench/workbench_bench.sh:
//   workbench_bench make DIR            writes DIR/minute.h5, hour.h5, ten-hours.h5 (274 ch, 100
//   Hz) workbench_bench browse FILE [SPAN]  zooms and pans the signal plot over FILE (views up to
//                                       SPAN seconds wide, default all of it) through a
//                                       file-backed SampleSource, moves the skin cursor, and
//                                       prints frame times, vertices per column and peak memory
// Browsing runs in its own process so that its peak resident memory is its own.
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "osmesa_renderer.h"
#include "process_memory.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/signal/sample_source.h"
#include "tactile/widgets/signal_plot.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kChannels = 274;
constexpr double kRate = 100.0;
constexpr int kPlotted = 8;
constexpr int kWidth = 1200, kHeight = 500;

// Piezo-like: quiet rest with 8-bit noise, a touch on a few channels every ~20 s.
void make(const std::string& path, double seconds) {
  if (std::filesystem::exists(path)) return;
  const auto samples = static_cast<int64_t>(seconds * kRate);
  tactile::Stream stream;
  stream.name = "skin";
  stream.rate_hz = kRate;
  for (int channel = 0; channel < kChannels; ++channel)
    stream.channels.push_back("film" + std::to_string(channel));
  stream.samples.resize(samples, kChannels);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> noise(-2, 2);
  for (int channel = 0; channel < kChannels; ++channel) {
    float* column = stream.samples.col(channel).data();
    for (int64_t index = 0; index < samples; ++index) {
      const int64_t phase = (index + channel * 37) % 2000;
      const float touch = phase < 150 && channel % 9 == 0 ? 60.0f * std::sin(phase * 0.02f) : 0.0f;
      column[index] = 512.0f + static_cast<float>(noise(random)) + std::round(touch);
    }
  }
  tactile::Recording recording;
  recording.id = std::filesystem::path(path).stem().string();
  recording.layout_id = "robovie";
  recording.streams = {std::move(stream)};
  tactile::write_recording(path, recording);
}

int browse(const std::string& path, double max_span) {
  tactile::OffscreenRenderer renderer(kWidth, kHeight);
  const tactile::FileSampleSource source(path);
  std::vector<tactile::PlotChannel> channels;
  for (int k = 0; k < kPlotted; ++k)
    channels.push_back({source.info().channels[k * 9], &source, k * 9, 0});
  const double start = source.start_time(), end = source.end_time();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // A user's path: from the whole recording, zoom in about a point down to 2 s (wheel
  // notches of 0.8), pan right in steps of a fifth of the view, then zoom out again.
  std::vector<std::pair<double, double>> views;
  const double widest = std::min(end - start, max_span);
  double centre = start + unit(random) * (end - start - widest) + widest / 2, span = widest;
  while (span > 2.0) {
    views.emplace_back(centre - span / 2, centre + span / 2);
    span *= 0.8;
  }
  for (int k = 0; k < 40; ++k) {
    centre = std::min(centre + span / 5, end - span / 2);
    views.emplace_back(centre - span / 2, centre + span / 2);
  }
  while (span < widest) {
    span = std::min(widest, span / 0.8);
    views.emplace_back(centre - span / 2, centre + span / 2);
  }
  const double cursor = centre;  // the skin shows the cursor, which panning does not move
  std::vector<double> frame_ms, build_ms;
  double worst_vertices_per_column = 0.0;
  for (int round = 0; round < 2; ++round)  // the first round warms caches and the font atlas
    for (const auto& [t0, t1] : views) {
      const auto begin = Clock::now();
      renderer.new_frame();
      ImGui::SetNextWindowPos(ImVec2(0, 0));
      ImGui::SetNextWindowSize(ImVec2(kWidth, kHeight));
      ImGui::Begin("bench", nullptr, ImGuiWindowFlags_NoDecoration);
      tactile::SignalPlotState state{.view_t0 = t0, .view_t1 = t1, .fitted = true};
      // The skin follows the cursor: values of all 274 channels at the view's centre.
      const std::vector<float> skin = source.values_at_time(cursor);
      const auto result = tactile::draw_signal_plot("plot", channels, {}, state, cursor,
                                                    ImVec2(kWidth - 20, kHeight - 20));
      ImGui::End();
      // The workbench's own work ends here (data through the source, the draw list); the
      // rest is rasterisation, by llvmpipe on this machine, whose cost is the pixels the
      // bars fill, not the length of the recording.
      const double built = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
      renderer.render();
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
      if (round == 1) frame_ms.push_back(ms), build_ms.push_back(built);
      // Data vertices only: ticks, labels and legend add a fixed few thousand.
      const double columns = result.area_max.x - result.area_min.x;
      worst_vertices_per_column =
          std::max(worst_vertices_per_column, (result.vertices - 4000) / (columns * kPlotted));
      if (skin.empty()) return 1;
    }
  std::sort(frame_ms.begin(), frame_ms.end());
  std::sort(build_ms.begin(), build_ms.end());
  const double median = frame_ms[frame_ms.size() / 2];
  const double p90 = frame_ms[frame_ms.size() * 9 / 10];
  const double build_median = build_ms[build_ms.size() / 2];
  const double build_p90 = build_ms[build_ms.size() * 9 / 10];
  std::printf(
      "{\"file\": \"%s\", \"seconds\": %.0f, \"frame_ms_median\": %.3f, \"frame_ms_p90\": %.3f, "
      "\"build_ms_median\": %.3f, \"build_ms_p90\": %.3f, "
      "\"vertices_per_column_per_channel_max\": %.2f, \"peak_rss_mb\": %.1f, "
      "\"source_memory_mb\": %.1f, \"chunks_read\": %lld}\n",
      path.c_str(), end - start, median, p90, build_median, build_p90, worst_vertices_per_column,
      tactile::bench::peak_memory_mb(), source.memory_bytes() / 1048576.0,
      static_cast<long long>(source.chunks_read()));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "make" && argc == 3) {
      const std::string folder = argv[2];
      std::filesystem::create_directories(folder);
      make(folder + "/minute.h5", 60.0);
      make(folder + "/hour.h5", 3600.0);
      make(folder + "/ten-hours.h5", 36000.0);
      return 0;
    }
    if (mode == "browse" && (argc == 3 || argc == 4))
      return browse(argv[2], argc == 4 ? std::stod(argv[3]) : 1e300);
    std::cerr << "usage: workbench_bench make DIR | browse FILE.h5 [WIDEST_SPAN_SECONDS]\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "workbench_bench: " << error.what() << "\n";
    return 1;
  }
}

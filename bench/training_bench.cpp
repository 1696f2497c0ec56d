// Training in the background (issue "Classifiers in the workbench"): the whole workbench
// drawn headless over a simulated fur workspace, frame times while idle against frame
// times while "Train all" runs on the model panel's worker (every preset, 5-fold, on the
// skin's own features); one run, so the figures are ratios.
//   training_bench DIR   (the workspace is simulated into DIR once)
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "jobs.h"
#include "model_panel.h"
#include "tactile/skins/workspace.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
using tactile::bench::percentile;

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: training_bench DIR\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  if (!std::filesystem::exists(folder / "labels.db")) {
    tactile::SimulationOptions options;
    options.subjects = 10;
    options.trials = 2;
    tactile::write_simulation(folder.string(), "fur", options);
  }
  tactile::bench::PacedFrames frames(1400, 800);
  tactile::WorkbenchOptions options;
  options.open_path = (folder / "fur-s01-t01.h5").string();
  options.settings_path = (folder / "settings.json").string();
  tactile::Workbench workbench(options);
  tactile::WorkbenchState& state = workbench.state();
  // Frames as a user sees them: the recording replaying at 1x, 60 frames a second (a
  // window's swap waits for the display; here a sleep until the next sixtieth).
  state.clock.play();
  const auto draw = [&] { return frames.draw(workbench); };
  for (int k = 0; k < 30; ++k) draw();  // warm up: font atlas, caches
  std::vector<double> idle, training;
  for (int k = 0; k < 300; ++k) idle.push_back(draw());
  const auto start = Clock::now();
  if (!tactile::start_training(state, "all")) {
    std::fprintf(stderr, "training_bench: %s\n", state.error.c_str());
    return 1;
  }
  while (tactile::find_job(state, "training")) training.push_back(draw());
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const size_t presets = state.analysis.results.rows.size();
  // The same run with no window drawing: what the training costs on its own.
  const auto alone_start = Clock::now();
  tactile::start_training_job(state.analysis.panel.last_request)->wait();
  const double alone_seconds = std::chrono::duration<double>(Clock::now() - alone_start).count();
  const double rows = state.analysis.results.dataset
                          ? static_cast<double>(state.analysis.results.dataset->rows())
                          : 0;
  std::printf(
      "{\"rows\": %.0f, \"presets\": %zu, \"train_all_seconds\": %.2f, "
      "\"train_all_seconds_without_window\": %.2f, \"frames_while_training\": %zu,\n"
      " \"idle_ms_median\": %.2f, \"idle_ms_p90\": %.2f, \"training_ms_median\": %.2f, "
      "\"training_ms_p90\": %.2f, \"median_ratio\": %.3f, \"p90_ratio\": %.3f}\n",
      rows, presets, seconds, alone_seconds, training.size(), percentile(idle, 0.5),
      percentile(idle, 0.9), percentile(training, 0.5), percentile(training, 0.9),
      percentile(training, 0.5) / percentile(idle, 0.5),
      percentile(training, 0.9) / percentile(idle, 0.9));
  if (!state.error.empty()) std::fprintf(stderr, "training_bench: %s\n", state.error.c_str());
  return 0;
}

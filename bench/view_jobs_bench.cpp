// The views' jobs (issue "The workbench on commands and jobs"): the whole workbench drawn
// headless at 60 frames a second, frame times while idle against frame times while the
// scatter's PCA and the SOM map's fit run on their workers, on a table of the size
// (454 segments x 1692 features, six classes; made once in DIR, random features). One run,
// so the figures are ratios; before these were jobs, each ran inside one frame.
//   view_jobs_bench DIR
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <thread>
#include <vector>

#include "analysis.h"
#include "bench_support.h"
#include "tactile/features/dataset.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
using tactile::bench::percentile;

// Six classes whose features differ in their mean, so the map and the scatter have structure.
void write_table(const std::string& path) {
  constexpr int kRows = 454, kFeatures = 1692, kClasses = 6;
  tactile::Dataset table;
  std::mt19937_64 random(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  table.features.resize(kRows, kFeatures);
  for (int feature = 0; feature < kFeatures; ++feature)
    table.columns.push_back({"f" + std::to_string(feature), "random, mean by class"});
  for (int row = 0; row < kRows; ++row) {
    const int label = row % kClasses;
    for (int feature = 0; feature < kFeatures; ++feature)
      table.features(row, feature) = 0.3 * label + noise(random);
    table.classes.push_back("class" + std::to_string(label + 1));
    table.subjects.push_back("s" + std::to_string(row % 10 + 1));
    table.recordings.push_back("r" + std::to_string(row / 20));
    table.segment_ids.push_back(row + 1);
    table.metadata.push_back({});
  }
  tactile::write_dataset_csv(path, table);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: view_jobs_bench DIR\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  const std::string table = (folder / "table-454x1692.csv").string();
  if (!std::filesystem::exists(table)) write_table(table);
  tactile::bench::PacedFrames frames(1600, 900);
  tactile::WorkbenchOptions options;
  options.features_path = table;
  options.only_view = "confusion";  // idle: no job of its own
  options.settings_path = (folder / "settings.json").string();
  tactile::Workbench workbench(options);
  tactile::WorkbenchState& state = workbench.state();
  const auto draw = [&] { return frames.draw(workbench); };
  for (int k = 0; k < 30; ++k) draw();  // warm up: font atlas, caches
  std::vector<double> idle;
  for (int k = 0; k < 300; ++k) idle.push_back(draw());
  std::printf("{\"rows\": %lld, \"features\": %lld, \"idle_ms_median\": %.2f, \"idle_ms_max\": %.2f",
              static_cast<long long>(state.analysis.dataset->rows()),
              static_cast<long long>(state.analysis.dataset->features.cols()),
              percentile(idle, 0.5), percentile(idle, 1.0));
  // Each view's job: started by drawing the view, frames drawn until its result is applied.
  for (const char* view : {"scatter", "som"}) {
    state.options.only_view = view;
    std::vector<double> job_frames;
    const auto start = Clock::now();
    job_frames.push_back(draw());
    while (workbench.jobs_running()) job_frames.push_back(draw());
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const size_t longest = static_cast<size_t>(
        std::max_element(job_frames.begin(), job_frames.end()) - job_frames.begin());
    std::printf(
        ",\n \"%s\": {\"seconds\": %.2f, \"frames\": %zu, \"ms_median\": %.2f, "
        "\"ms_p99\": %.2f, \"ms_max\": %.2f, \"longest_frame\": %zu, "
        "\"max_over_idle_median\": %.2f}",
        view, seconds, job_frames.size(), percentile(job_frames, 0.5), percentile(job_frames, 0.99),
        percentile(job_frames, 1.0), longest, percentile(job_frames, 1.0) / percentile(idle, 0.5));
  }
  std::printf("}\n");
  if (!state.error.empty()) std::fprintf(stderr, "view_jobs_bench: %s\n", state.error.c_str());
  return state.error.empty() ? 0 : 1;
}

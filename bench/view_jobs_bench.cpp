// The workbench's jobs (issue "The workbench on commands and jobs"): the workbench drawn
// headless at 60 frames a second, frame times while idle against frame times while each job
// runs on its worker, and how long Cancel takes to end it:
//  - the scatter's PCA and the SOM map's fit on a table of the size (454 segments x
//    1692 features, six classes, random features);
//  - the segmenter run (G), training one classifier, Predict and the somatosensory map on 30
//    minutes of Robovie's 274 films (13 simulated trials end to end).
// Both are made once in DIR. One run, so the figures are ratios; before these were jobs, each
// ran inside one frame (the table: 18-20 s, 7.8 s, 2.9 s, 2.6-3.3 s, 8.3 s).
//   view_jobs_bench DIR [JOB...]   (scatter som segmenter predict somatosensory_map; all by
//                                   default; predict trains first)
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "jobs.h"
#include "labelling.h"
#include "long_robovie.h"
#include "model_panel.h"
#include "process_memory.h"
#include "tactile/features/dataset.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/ml/somatosensory.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"
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

struct Measured {
  std::vector<double> frames;
  double seconds = 0.0;
  double after_median = 0.0;  // the same view's frames once the result is shown (60 frames)
  double resident_mb = 0.0;   // resident memory before the job
  double peak_mb = 0.0;       // the process's peak while the job ran and its result was applied
};

// Frames drawn from `start` until no job is pending.
template <typename Draw>
Measured until_done(tactile::Workbench& workbench, Draw draw, const std::function<void()>& start) {
  Measured measured;
  tactile::bench::reset_peak_memory();
  measured.resident_mb = tactile::bench::peak_memory_mb();
  const auto begin = Clock::now();
  start();
  measured.frames.push_back(draw());
  while (workbench.jobs_running()) measured.frames.push_back(draw());
  measured.frames.push_back(draw());  // the frame that applies a training result
  measured.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  measured.peak_mb = tactile::bench::peak_memory_mb();
  std::vector<double> after;
  for (int k = 0; k < 60; ++k) after.push_back(draw());
  measured.after_median = percentile(after, 0.5);
  return measured;
}

// Starts the job again, lets it run `frames` frames, cancels it through its handle and draws
// until it is gone: seconds from Cancel to the end of its worker.
template <typename Draw>
double cancel_after(tactile::Workbench& workbench, Draw draw, const std::function<void()>& start,
                    int frames) {
  start();
  for (int k = 0; k < frames; ++k) draw();
  std::vector<tactile::AnyJob*> jobs = tactile::pending_jobs(workbench.state());
  if (jobs.empty()) return -1.0;  // ended before the cancel
  const auto cancelled = Clock::now();
  for (tactile::AnyJob* job : jobs) job->cancel();
  while (workbench.jobs_running()) draw();
  return std::chrono::duration<double>(Clock::now() - cancelled).count();
}

void print_job(const char* name, const Measured& job, double idle_median, double cancel_seconds) {
  const size_t longest = static_cast<size_t>(
      std::max_element(job.frames.begin(), job.frames.end()) - job.frames.begin());
  std::printf(
      ",\n \"%s\": {\"seconds\": %.2f, \"frames\": %zu, \"ms_median\": %.2f, \"ms_p99\": %.2f, "
      "\"ms_max\": %.2f, \"longest_frame\": %zu, \"max_over_idle_median\": %.2f, "
      "\"after_ms_median\": %.2f, \"max_over_after_median\": %.2f, \"cancel_seconds\": %.3f, "
      "\"resident_mb_before\": %.0f, \"peak_mb\": %.0f}",
      name, job.seconds, job.frames.size(), percentile(job.frames, 0.5),
      percentile(job.frames, 0.99), percentile(job.frames, 1.0), longest,
      percentile(job.frames, 1.0) / idle_median, job.after_median,
      percentile(job.frames, 1.0) / job.after_median, cancel_seconds, job.resident_mb, job.peak_mb);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: view_jobs_bench DIR [JOB...]\n");
    return 2;
  }
  const std::vector<std::string> asked(argv + 2, argv + argc);
  const auto wants = [&](const std::string& job) {
    return asked.empty() || std::find(asked.begin(), asked.end(), job) != asked.end();
  };
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  const std::string table = (folder / "table-454x1692.csv").string();
  if (!std::filesystem::exists(table)) write_table(table);
  tactile::bench::PacedFrames frames(1600, 900);
  bool table_failed = false;
  tactile::WorkbenchOptions options;
  options.settings_path = (folder / "settings.json").string();
  {  // one workbench at a time: each has its own ImGui context on the one renderer
    options.features_path = table;
    options.only_view = "confusion";  // idle: no job of its own
    tactile::Workbench workbench(options);
    tactile::WorkbenchState& state = workbench.state();
    const auto draw = [&] { return frames.draw(workbench); };
    for (int k = 0; k < 30; ++k) draw();  // warm up: font atlas, caches
    std::vector<double> idle;
    for (int k = 0; k < 300; ++k) idle.push_back(draw());
    std::printf(
        "{\"rows\": %lld, \"features\": %lld, \"idle_ms_median\": %.2f, \"idle_ms_max\": %.2f",
        static_cast<long long>(state.analysis.results.dataset->rows()),
        static_cast<long long>(state.analysis.results.dataset->features.cols()),
        percentile(idle, 0.5), percentile(idle, 1.0));
    // Each view's job: started by drawing the view, frames drawn until its result is applied.
    for (const char* view : {"scatter", "som"}) {
      if (!wants(view)) continue;
      state.options.only_view = view;
      const Measured job = until_done(workbench, draw, [] {});
      // Cancel: the view's result dropped, the job started again by drawing it.
      const double cancel = cancel_after(
          workbench, draw,
          [&] {
            if (std::string(view) == "scatter")
              state.analysis.scatter.table = nullptr;
            else
              state.analysis.som.model.reset();
          },
          5);
      print_job(view, job, percentile(idle, 0.5), cancel);
    }
    if (!state.error.empty()) std::fprintf(stderr, "view_jobs_bench: %s\n", state.error.c_str());
    table_failed = !state.error.empty();
  }

  // The recording's jobs, in the whole window on 30 minutes of Robovie.
  const std::filesystem::path robovie = folder / "robovie-30min.h5";
  if (!std::filesystem::exists(robovie)) tactile::bench::write_long_robovie(folder);
  tactile::WorkbenchOptions whole;
  whole.open_path = robovie.string();
  whole.settings_path = options.settings_path;
  whole.annotator = "bench";
  tactile::Workbench window(whole);
  tactile::WorkbenchState& at = window.state();
  const auto frame = [&] { return frames.draw(window); };
  for (int k = 0; k < 30; ++k) frame();
  std::vector<double> window_idle;
  for (int k = 0; k < 300; ++k) window_idle.push_back(frame());
  const double median = percentile(window_idle, 0.5);
  std::printf(",\n \"window_idle_ms_median\": %.2f, \"window_idle_ms_max\": %.2f", median,
              percentile(window_idle, 1.0));
  tactile::LabelStore& store = at.document->label_store();
  const auto labels_now = [&] { return store.count(at.document->recording_id()); };
  const int64_t before = labels_now();
  const auto segment = [&] { tactile::run_segmenter(at, "adaptive"); };
  bool segment_unchanged = true, predict_unchanged = true;
  if (wants("segmenter")) {
    const double segment_cancel = cancel_after(window, frame, segment, 3);
    segment_unchanged = labels_now() == before;
    print_job("segmenter", until_done(window, frame, segment), median, segment_cancel);
    tactile::undo_edit(at, false);  // Predict takes the ground truth when there are no suggestions
  }
  if (wants("predict")) {
    at.analysis.panel.segments = tactile::LabelSource::kGroundTruth;
    std::snprintf(at.analysis.panel.protocol.data(), at.analysis.panel.protocol.size(), "kfold:3");
    const auto train = [&] { tactile::start_training(at, "linear-svm"); };
    const double train_cancel = cancel_after(window, frame, train, 30);
    print_job("train", until_done(window, frame, train), median, train_cancel);
    const int64_t trained = labels_now();
    const auto predict = [&] { tactile::predict_open_recording(at); };
    const double predict_cancel = cancel_after(window, frame, predict, 3);
    predict_unchanged = labels_now() == trained;
    print_job("predict", until_done(window, frame, predict), median, predict_cancel);
  }
  const auto map = [&] {
    std::filesystem::remove(tactile::somatosensory_cache_path(
        robovie.string(),
        at.document->layout.modalities.empty() ? "" : at.document->layout.modalities[0]));
    at.analysis.somatosensory.shown = true;
    at.analysis.somatosensory.key.clear();
  };
  if (wants("somatosensory_map")) {
    const double map_cancel = cancel_after(window, frame, map, 3);
    print_job("somatosensory_map", until_done(window, frame, map), median, map_cancel);
  }
  std::printf(",\n \"cancel_left_the_store_as_it_was\": %s}\n",
              segment_unchanged && predict_unchanged ? "true" : "false");
  if (!at.error.empty()) std::fprintf(stderr, "view_jobs_bench: %s\n", at.error.c_str());
  return at.error.empty() && !table_failed ? 0 : 1;
}

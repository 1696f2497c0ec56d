#include "tactile/skins/workspace.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <thread>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"
#include "tactile/sim/sensor_faults.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr const char* kSimulatedLabelTime = "1970-01-01T00:00:00.000Z";

struct TrialJob {
  int subject = 0;
  int trial = 0;
};

void create_folder(const std::string& folder) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw Error(folder, "cannot create the folder: " + error.message());
}

}  // namespace

SimulationSummary write_simulation(const std::string& folder, const std::string& skin,
                                   const SimulationOptions& options,
                                   const SimulationProgress& progress) {
  if (options.subjects < 1) throw Error("--subjects", "must be at least 1");
  if (options.trials < 1) throw Error("--trials", "must be at least 1");
  if (options.repetitions < 0) throw Error("--repetitions", "must not be negative");
  // A registered skin's own simulator; any grid:RxC layout that is no skin, the pressure grid's.
  const SkinRecord* record = find_skin(skin);
  const bool grid = record == nullptr && skin.rfind("grid:", 0) == 0;
  if (!grid) record = &skin_record(skin, "--skin " + skin);
  if (!grid && !record->simulate)
    throw Error("--skin " + skin, "has no simulator (simulated skins: " +
                                      joined(simulated_skin_ids()) + ", grid:RxC)");
  const TrialGenerator generate = grid ? TrialGenerator(simulate_grid_trial) : record->simulate;
  const SkinLayout layout = load_layout(skin);
  const SensorFaults faults = parse_sensor_faults(options.faults, "--faults");
  create_folder(folder);

  std::vector<TrialJob> jobs;
  for (int subject = 0; subject < options.subjects; ++subject)
    for (int trial = 0; trial < options.trials; ++trial) jobs.push_back({subject, trial});
  const int total = static_cast<int>(jobs.size());

  SimulationSummary summary;
  summary.files.resize(jobs.size());
  std::vector<std::vector<Label>> labels(jobs.size());
  std::vector<double> durations(jobs.size(), 0.0);
  std::atomic<size_t> next{0};
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  std::exception_ptr failure;
  std::mutex failure_mutex;

  // Each worker generates and writes whole trials; a trial's bytes depend only on its
  // own seeds, so the thread count never changes the output.
  auto work = [&] {
    for (size_t index = next++; index < jobs.size(); index = next++) {
      try {
        SimulatedTrial result = generate(layout, options, jobs[index].subject, jobs[index].trial);
        apply_sensor_faults(result, layout, faults, options.seed, jobs[index].subject,
                            jobs[index].trial);
        const std::string path = (fs::path(folder) / (result.recording.id + ".h5")).string();
        write_recording(path, result.recording);
        summary.files[index] = path;
        durations[index] = result.recording.duration();
        labels[index] = std::move(result.labels);
        const int finished = ++done;
        if (progress) {
          std::lock_guard lock(progress_mutex);
          progress(finished, total);
        }
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = jobs.size();
      }
    }
  };
  const unsigned threads =
      std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(), total));
  std::vector<std::thread> workers;
  for (unsigned k = 0; k < threads; ++k) workers.emplace_back(work);
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);

  LabelStore store((fs::path(folder) / "labels.db").string());
  // Simulated ground truth carries no wall-clock time: the same seed writes the same bytes.
  store.use_fixed_time(kSimulatedLabelTime);
  store.set_classes(skin, grid ? grid_gesture_classes() : skin_classes(skin));
  for (size_t index = 0; index < jobs.size(); ++index) {
    if (labels[index].empty()) continue;
    LabelFilter previous;
    previous.recording = labels[index].front().recording;
    previous.source = LabelSource::kGroundTruth;
    store.remove_where(previous);
    store.add_many(labels[index]);
    summary.labels += static_cast<int64_t>(labels[index].size());
  }
  for (double seconds : durations) summary.seconds_recorded += seconds;
  return summary;
}

SimulationSummary write_demo_workspace(const std::string& folder, uint64_t seed,
                                       const SimulationProgress& progress) {
  // Each skin's share (its record's), enough to see every class, small enough to make in
  // seconds.
  std::vector<const SkinRecord*> parts;
  for (const std::string& id : skin_ids())
    if (const SkinRecord* record = find_skin(id); record->simulate && record->demo_subjects > 0)
      parts.push_back(record);
  SimulationSummary summary;
  int total = 0;
  for (const SkinRecord* part : parts) total += part->demo_subjects;
  int done = 0;
  for (const SkinRecord* part : parts) {
    SimulationOptions options;
    options.seed = seed;
    options.subjects = part->demo_subjects;
    options.trials = 1;
    options.repetitions = part->demo_repetitions;
    const SimulationSummary written =
        write_simulation(folder, part->id, options, [&](int finished, int) {
          if (progress) progress(done + finished, total);
        });
    done += part->demo_subjects;
    summary.files.insert(summary.files.end(), written.files.begin(), written.files.end());
    summary.labels += written.labels;
    summary.seconds_recorded += written.seconds_recorded;
  }
  return summary;
}

}  // namespace tactile

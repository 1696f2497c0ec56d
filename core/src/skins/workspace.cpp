#include "tactile/skins/workspace.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/sim/sensor_faults.h"
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

// A grid:RxC layout that is no registered skin: the pressure grid's simulator and classes.
bool is_pressure_grid(const std::string& skin) {
  return find_skin(skin) == nullptr && skin.rfind("grid:", 0) == 0;
}

void create_folder(const std::string& folder) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw Error(folder, "cannot create the folder: " + error.message());
}

}  // namespace

SimulatedTrials simulate_trials(const std::string& folder, const std::string& skin,
                                const SimulationOptions& options, const Shard& shard,
                                const SimulationProgress& progress) {
  if (options.subjects < 1) throw Error("--subjects", "must be at least 1");
  if (options.trials < 1) throw Error("--trials", "must be at least 1");
  if (options.repetitions < 0) throw Error("--repetitions", "must not be negative");
  // A registered skin's own simulator; any grid:RxC layout that is no skin, the pressure grid's.
  const SkinRecord* record = find_skin(skin);
  const bool grid = is_pressure_grid(skin);
  if (!grid) record = &skin_record(skin, "--skin " + skin);
  if (!grid && !record->simulate)
    throw Error("--skin " + skin, "has no simulator (simulated skins: " +
                                      joined(simulated_skin_ids()) + ", grid:RxC)");
  const TrialGenerator generate = grid ? TrialGenerator(simulate_grid_trial) : record->simulate;
  const SkinLayout layout = load_layout(skin);
  const SensorFaults faults = parse_sensor_faults(options.faults, "--faults");
  create_folder(folder);

  std::vector<TrialJob> jobs;
  SimulatedTrials trials;
  for (int subject = 0; subject < options.subjects; ++subject)
    for (int trial = 0; trial < options.trials; ++trial) {
      jobs.push_back({subject, trial});
      trials.plan.push_back(std::to_string(subject) + "/" + std::to_string(trial));
    }
  trials.done = shard.items_of(jobs.size());
  trials.files.resize(jobs.size());
  trials.labels.resize(jobs.size());
  trials.seconds.assign(jobs.size(), 0.0);
  const int total = static_cast<int>(trials.done.size());
  std::atomic<size_t> next{0};
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  std::exception_ptr failure;
  std::mutex failure_mutex;

  // Each worker generates and writes whole trials; a trial's bytes depend only on its
  // own seeds, so the thread count never changes the output.
  auto work = [&] {
    for (size_t at = next++; at < trials.done.size(); at = next++) {
      const size_t index = trials.done[at];
      try {
        SimulatedTrial result = generate(layout, options, jobs[index].subject, jobs[index].trial);
        apply_sensor_faults(result, layout, faults, options.seed, jobs[index].subject,
                            jobs[index].trial);
        const std::string path = (fs::path(folder) / (result.recording.id + ".h5")).string();
        write_recording(path, result.recording);
        trials.files[index] = path;
        trials.seconds[index] = result.recording.duration();
        trials.labels[index] = std::move(result.labels);
        const int finished = ++done;
        if (progress) {
          std::lock_guard lock(progress_mutex);
          progress(finished, total);
        }
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = trials.done.size();
      }
    }
  };
  const unsigned threads =
      std::max(1u, std::min<unsigned>(std::thread::hardware_concurrency(),
                                      static_cast<unsigned>(std::max(total, 1))));
  std::vector<std::thread> workers;
  for (unsigned k = 0; k < threads; ++k) workers.emplace_back(work);
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return trials;
}

SimulationSummary store_simulated_labels(const std::string& folder, const std::string& skin,
                                         const SimulatedTrials& trials) {
  SimulationSummary summary;
  summary.files = trials.files;
  LabelStore store((fs::path(folder) / "labels.db").string());
  // Simulated ground truth carries no wall-clock time: the same seed writes the same bytes.
  store.use_fixed_time(kSimulatedLabelTime);
  store.set_classes(skin, is_pressure_grid(skin) ? grid_gesture_classes() : skin_classes(skin));
  for (const std::vector<Label>& labels : trials.labels) {
    if (labels.empty()) continue;
    LabelFilter previous;
    previous.recording = labels.front().recording;
    previous.source = LabelSource::kGroundTruth;
    store.remove_where(previous);
    store.add_many(labels);
    summary.labels += static_cast<int64_t>(labels.size());
  }
  for (double seconds : trials.seconds) summary.seconds_recorded += seconds;
  return summary;
}

SimulationSummary write_simulation(const std::string& folder, const std::string& skin,
                                   const SimulationOptions& options,
                                   const SimulationProgress& progress) {
  return store_simulated_labels(folder, skin, simulate_trials(folder, skin, options, {}, progress));
}

namespace {

nlohmann::json simulation_inputs(const std::string& skin, const SimulationOptions& options) {
  return {{"--skin", skin},
          {"--subjects", options.subjects},
          {"--trials", options.trials},
          {"--repetitions", options.repetitions},
          {"--seed", options.seed},
          {"--condition", options.condition},
          {"--multi-touch", options.multi_touch},
          {"--side", options.side},
          {"--faults", options.faults}};
}

}  // namespace

Part simulation_part(const SimulatedTrials& trials, const std::string& folder,
                     const std::string& skin, const SimulationOptions& options,
                     const Shard& shard) {
  Part part;
  part.command = "simulate";
  part.shard = shard;
  part.inputs = simulation_inputs(skin, options);
  part.result = folder;
  part.items = static_cast<int64_t>(trials.plan.size());
  part.plan = plan_digest(trials.plan);
  part.shared = nlohmann::json::object();
  part.done = nlohmann::json::array();
  for (size_t index : trials.done) {
    std::error_code error;
    const auto bytes = fs::file_size(trials.files[index], error);
    if (error) throw Error(trials.files[index], "cannot read its size: " + error.message());
    nlohmann::json labels = nlohmann::json::array();
    for (const Label& label : trials.labels[index]) labels.push_back(label_json(label));
    part.done.push_back({{"index", index},
                         {"file", fs::path(trials.files[index]).filename().string()},
                         {"bytes", static_cast<uint64_t>(bytes)},
                         {"seconds", trials.seconds[index]},
                         {"labels", labels}});
  }
  return part;
}

SimulationSummary merge_simulation_parts(const std::vector<Part>& parts,
                                         const std::string& folder) {
  SimulatedTrials trials;
  const std::vector<nlohmann::json> items = items_in_order(parts);
  // Which part did each item, to name it when its recording is not where it says.
  std::vector<std::string> made_by(items.size());
  for (const Part& part : parts)
    for (const nlohmann::json& item : part.done)
      made_by.at(item.at("index").get<size_t>()) = part.path;
  for (size_t index = 0; index < items.size(); ++index) {
    const nlohmann::json& item = items[index];
    const std::string path = (fs::path(folder) / item.at("file").get<std::string>()).string();
    const auto expected = item.at("bytes").get<uint64_t>();
    std::error_code error;
    const auto bytes = fs::file_size(path, error);
    if (error)
      throw Error(path, "the recording " + made_by[index] + " wrote is missing (" +
                            error.message() + "); run that shard again");
    if (bytes != expected)
      throw Error(path, std::to_string(bytes) + " bytes, but " + made_by[index] + " wrote " +
                            std::to_string(expected) + "; run that shard again");
    trials.plan.push_back(std::to_string(index));
    trials.done.push_back(index);
    trials.files.push_back(path);
    trials.seconds.push_back(item.at("seconds").get<double>());
    std::vector<Label> labels;
    const std::string where = made_by[index] + " item " + std::to_string(index);
    for (const nlohmann::json& label : item.at("labels"))
      labels.push_back(label_from_json(label, where));
    trials.labels.push_back(std::move(labels));
  }
  const std::string skin = parts.front().inputs.at("--skin").get<std::string>();
  return store_simulated_labels(folder, skin, trials);
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

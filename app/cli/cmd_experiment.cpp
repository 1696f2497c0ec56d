// `tactile experiment NAME`: rerun one paper's experiment end to end on simulated skins (or
// on recorded data with --data) and print the paper-shaped tables, ours beside the paper's.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/experiments/experiment.h"

namespace tactile::cli {

namespace {

struct ExperimentArgs {
  std::string name;
  std::string data;
  std::string work;
  uint64_t seed = 1;
  bool quick = false;
  bool json = false;
  bool keep = false;
};

// Removes the folder when it goes out of scope (the run ended, or failed), unless released.
class RemoveWhenDone {
 public:
  explicit RemoveWhenDone(std::string folder) : folder_(std::move(folder)) {}
  ~RemoveWhenDone() {
    if (folder_.empty()) return;
    std::error_code error;  // a folder that cannot be removed is left, never a crash
    std::filesystem::remove_all(folder_, error);
  }
  RemoveWhenDone(const RemoveWhenDone&) = delete;
  RemoveWhenDone& operator=(const RemoveWhenDone&) = delete;

 private:
  std::string folder_;
};

// A fresh folder under the system temp dir, so repeated runs never mix their simulations.
std::string default_work_dir(const std::string& name) {
  std::random_device device;
  const auto base = std::filesystem::temp_directory_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    std::ostringstream folder;
    folder << "tactile-experiment-" << name << "-" << std::hex << device();
    const auto path = base / folder.str();
    std::error_code error;
    if (std::filesystem::create_directory(path, error)) return path.string();
  }
  throw Error(base.string(), "cannot create a work folder for the experiment");
}

void run(const ExperimentArgs& args) {
  experiments::ExperimentOptions options;
  options.data_dir = args.data;
  options.seed = args.seed;
  options.quick = args.quick;
  if (!args.data.empty() && !std::filesystem::is_directory(args.data))
    throw Error("--data", args.data + " is not a folder");
  const std::vector<std::string> names = experiments::experiment_names();
  if (std::find(names.begin(), names.end(), args.name) == names.end())
    experiments::run_experiment(args.name, options);  // throws, listing the known names
  // A run simulates hundreds of MB; in a folder of its own choosing it cleans up after
  // itself unless asked to keep it (--keep), so repeated runs do not fill the disk.
  std::unique_ptr<RemoveWhenDone> cleanup;
  if (args.work.empty()) {
    options.work_dir = default_work_dir(args.name);
    std::cerr << "work folder: " << options.work_dir
              << (args.keep ? "" : " (removed when done; --keep or --work DIR keeps it)") << "\n";
    if (!args.keep) cleanup = std::make_unique<RemoveWhenDone>(options.work_dir);
  } else {
    std::error_code error;
    std::filesystem::create_directories(args.work, error);
    if (error) throw Error("--work", "cannot create " + args.work + ": " + error.message());
    options.work_dir = args.work;
  }
  std::unique_ptr<ProgressBar> bar;
  std::string current_stage;
  options.progress = [&](const std::string& stage, int done, int total) {
    if (stage != current_stage) {
      if (bar) bar->finish();
      bar = std::make_unique<ProgressBar>(args.name + ": " + stage);
      current_stage = stage;
    }
    bar->update(done, total);
  };
  const experiments::ExperimentReport report = experiments::run_experiment(args.name, options);
  if (bar) bar->finish();
  if (args.json) {
    nlohmann::json document = report.json;
    document["name"] = report.name;
    document["paper"] = report.paper;
    if (!cleanup) document["work_dir"] = options.work_dir;  // only a folder that stays
    std::cout << document.dump(2) << "\n";
  } else {
    std::cout << experiments::format_report(report);
  }
}

}  // namespace

void register_experiment(CLI::App& app) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* command = app.add_subcommand(
      "experiment", "rerun a paper's experiment end to end and compare with its figures");
  command->add_option("name", args->name, "experiment name (see the error for the list)")
      ->required();
  command->add_option("--data", args->data,
                      "recordings and labels.db of the skin (default: simulate)");
  command->add_option("--work", args->work,
                      "folder for simulated data, kept (default: a new folder under the temp "
                      "dir, removed when done)");
  command->add_option("--seed", args->seed, "seed for simulation, folds and training");
  command->add_flag("--quick", args->quick, "a much smaller corpus, for smoke runs");
  command->add_flag("--json", args->json, "print the report as JSON");
  command->add_flag("--keep", args->keep,
                    "keep the default work folder (its simulated recordings and labels)");
  command->callback([args] { run(*args); });
}

}  // namespace tactile::cli

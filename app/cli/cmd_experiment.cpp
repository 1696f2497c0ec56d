// `tactile experiment NAME`: rerun one paper's experiment end to end on simulated skins (or
// on recorded data with --data) and print the paper-shaped tables, ours beside the paper's;
// --repeats R runs it over R consecutive seeds and summarises the figures (--shard I/N: some
// of the seeds, merged by `tactile merge`).
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
#include "tactile/experiments/repeats.h"
#include "tactile/io/atomic_file.h"

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
  int repeats = 1;
  std::string out;
  ShardArgs shard;
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

// The job the arguments (or a part's inputs) describe.
experiments::RepeatsJob repeats_job(const nlohmann::json& inputs) {
  experiments::RepeatsJob job;
  job.name = inputs.at("name").get<std::string>();
  job.first_seed = inputs.at("--seed").get<uint64_t>();
  job.repeats = inputs.at("--repeats").get<int>();
  job.quick = inputs.at("--quick").get<bool>();
  return job;
}

nlohmann::json repeats_inputs(const ExperimentArgs& args) {
  return {{"name", args.name},
          {"--seed", args.seed},
          {"--repeats", args.repeats},
          {"--quick", args.quick},
          {"--data", args.data}};
}

// One run prints as it always has; more print each run's tables and the summary.
void print_repeats(const experiments::RepeatsJob& job,
                   const std::vector<experiments::RepeatRun>& runs, bool json,
                   const std::string& kept_work_dir, const std::string& out) {
  if (json) {
    nlohmann::json document;
    if (runs.size() == 1 && job.repeats == 1) {
      document = runs.front().report.json;
      document["name"] = runs.front().report.name;
      document["paper"] = runs.front().report.paper;
    } else {
      document = experiments::repeats_document(job, runs);
    }
    if (!kept_work_dir.empty()) document["work_dir"] = kept_work_dir;
    std::cout << document.dump(2) << "\n";
    return;
  }
  std::cout << (job.repeats == 1 && runs.size() == 1
                    ? experiments::format_report(runs.front().report)
                    : experiments::format_repeats(job, runs));
  if (!out.empty()) std::cout << "result      " << out << "\n";
}

void run(const ExperimentArgs& args) {
  experiments::ExperimentOptions options;
  options.data_dir = args.data;
  options.seed = args.seed;
  options.quick = args.quick;
  if (!args.data.empty() && !std::filesystem::is_directory(args.data))
    throw Error("--data", args.data + " is not a folder");
  const std::vector<std::string> names = experiments::experiment_names();
  const bool all = args.name == "all";
  if (!all && std::find(names.begin(), names.end(), args.name) == names.end())
    experiments::run_experiment(args.name, options);  // throws, listing the known names
  if (args.repeats < 1)
    throw Error("--repeats", "must be 1 or more, not " + std::to_string(args.repeats));
  if (!args.out.empty() && std::filesystem::path(args.out).extension() != ".json")
    throw Error("--out", "'" + args.out + "': the file name must end in .json");
  const bool sharded = !args.shard.shard.empty() || !args.shard.part.empty();
  if (sharded && args.out.empty())
    throw Error("--shard", "needs --out (the result the merge writes; parts go beside it)");
  if (sharded && args.json)
    throw Error("--json", "not with --shard: `tactile merge` prints the result");
  if (all && sharded)
    throw Error("--shard", "not with all: shard one experiment at a time (docs/CLUSTER.md)");
  const ShardPlan plan = shard_plan(args.shard, args.out);
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
  const std::string kept_work_dir = cleanup ? "" : options.work_dir;  // only a folder that stays
  if (all) {
    // Every experiment over the same seeds, each in WORK/NAME; one table of the paper's figures.
    std::vector<experiments::PaperRow> rows;
    const std::string work = options.work_dir;
    for (const std::string& name : names) {
      options.work_dir = (std::filesystem::path(work) / name).string();
      current_stage.clear();
      const experiments::RepeatsJob job{name, args.seed, args.repeats, args.quick};
      const std::vector<experiments::RepeatRun> runs =
          experiments::run_repeats(job, options, {}, cleanup != nullptr);
      if (bar) bar->finish();
      bar.reset();
      for (experiments::PaperRow& row : experiments::paper_rows(name, runs))
        rows.push_back(std::move(row));
    }
    const nlohmann::json document = experiments::paper_rows_json(rows, args.repeats);
    if (!args.out.empty()) write_file_atomically(args.out, document.dump(2) + "\n");
    std::cout << (args.json ? document.dump(2) + "\n"
                            : experiments::format_paper_rows(rows, args.repeats));
    return;
  }
  if (args.repeats == 1 && args.out.empty() && !sharded) {
    // One run, as before --repeats: simulated straight into the work folder.
    const experiments::ExperimentReport report = experiments::run_experiment(args.name, options);
    if (bar) bar->finish();
    print_repeats({args.name, args.seed, 1, args.quick}, {{args.seed, report}}, args.json,
                  kept_work_dir, "");
    return;
  }
  // Repeats (or one run kept in --out): each seed in WORK/seed-S, removed after its run
  // when the work folder goes.
  Part part;
  part.inputs = repeats_inputs(args);
  const experiments::RepeatsJob job = repeats_job(part.inputs);
  const std::vector<experiments::RepeatRun> runs =
      experiments::run_repeats(job, options, plan.shard, cleanup != nullptr);
  if (bar) bar->finish();
  if (sharded) {
    part.command = "experiment";
    part.shard = plan.shard;
    part.result = args.out;
    const std::vector<std::string> keys = experiments::repeats_plan(job);
    part.items = static_cast<int64_t>(keys.size());
    part.plan = plan_digest(keys);
    part.done = nlohmann::json::array();
    const std::vector<size_t> items = plan.shard.items_of(keys.size());
    for (size_t run = 0; run < runs.size(); ++run)
      part.done.push_back(experiments::repeat_item(items[run], runs[run]));
    write_shard_part(plan, part);
    return;
  }
  if (!args.out.empty())
    experiments::write_repeats_file(args.out, experiments::repeats_document(job, runs));
  print_repeats(job, runs, args.json, kept_work_dir, args.out);
}

}  // namespace

void register_experiment(CLI::App& app) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* command = app.add_subcommand(
      "experiment", "rerun a paper's experiment end to end and compare with its figures");
  command
      ->add_option("name", args->name,
                   "experiment name (see the error for the list), or all: every experiment, "
                   "one table of the figures the papers report")
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
  command
      ->add_option("--repeats", args->repeats,
                   "run R times with the seeds S, S+1, ..., S+R-1 (each in WORK/seed-S) and "
                   "summarise the figures: mean, sd, min, max beside the paper's")
      ->capture_default_str();
  command->add_option("--out", args->out,
                      "write the runs and their summary as JSON (no times, no paths: the same "
                      "seeds give the same bytes)");
  add_shard_options(command, args->shard);
  command->callback([args] { run(*args); });
}

void merge_experiment(const std::vector<Part>& parts, const std::string& out) {
  const experiments::RepeatsJob job = repeats_job(parts.front().inputs);
  std::vector<experiments::RepeatRun> runs;
  for (const nlohmann::json& item : items_in_order(parts))
    runs.push_back(experiments::repeat_from_item(item));
  experiments::write_repeats_file(out, experiments::repeats_document(job, runs));
  print_repeats(job, runs, false, "", out);
}

}  // namespace tactile::cli

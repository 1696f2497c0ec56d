// `tactile cluster slurm --command "tactile CMD ... --out RESULT" --shards N --out DIR
//  [--partition P] [--time T] [--submit]`: a sharded command as plain sbatch files a user can
// read and edit (a job array of its shards, a merge job after them, a submit script), and
// with --submit their submission. `tactile cluster status DIR` and `tactile cluster resubmit
// DIR --shard I` are in cluster_jobs.cpp. docs/CLUSTER.md.
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.h"
#include "tactile/cluster/slurm.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::cli {

void register_cluster_jobs(CLI::App* cluster);  // cluster_jobs.cpp

namespace {

using cluster::JobFolder;
using cluster::shell_quoted;

// The running program, so that the jobs run the same build (/proc/self/exe).
std::string cluster_this_program() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string("tactile") : path.string();
}

struct SlurmArgs {
  std::string command, out;
  cluster::SlurmOptions options;
  bool submit = false;
};

void run_slurm(const SlurmArgs& args) {
  const int shards = args.options.shards;
  if (shards < 1) throw Error("--shards", "give the number of shards, 1 or more");
  const std::string chdir = std::filesystem::current_path().string();
  const cluster::ShardedCommand command =
      cluster::parse_sharded_command(args.command, chdir, cluster_this_program());
  const JobFolder folder{std::filesystem::absolute(args.out).lexically_normal().string()};
  if (std::filesystem::exists(folder.jobs()))
    throw Error(folder.jobs(),
                "exists: this folder's jobs were submitted; use `tactile cluster "
                "status` or another --out");
  if (args.submit && !cluster::on_path("sbatch"))
    throw Error("--submit",
                "sbatch is not on PATH: run on a Slurm login node (the scripts are "
                "written without --submit; submit them there with submit.sh)");
  std::filesystem::create_directories(folder.dir + "/parts");
  std::filesystem::create_directories(folder.dir + "/logs");
  cluster::write_script(folder.shards_script(),
                        cluster::shards_script(args.options, command, folder, chdir));
  cluster::write_script(folder.merge_script(),
                        cluster::merge_script(args.options, command, folder, chdir));
  cluster::write_script(folder.submit_script(), cluster::submit_script(folder));
  std::cout << "wrote " << folder.shards_script() << " (" << shards << " shards), "
            << folder.merge_script() << " and " << folder.submit_script() << "\n";
  if (!args.submit) {
    std::cout << "submit with: bash " << shell_quoted(folder.submit_script()) << "\n";
    return;
  }
  const std::string array = cluster::parsable_job_id(
      cluster::run_captured({"sbatch", "--parsable", folder.shards_script()}));
  const std::string merge = cluster::parsable_job_id(cluster::run_captured(
      {"sbatch", "--parsable", "--dependency=afterok:" + array, folder.merge_script()}));
  nlohmann::json tasks = nlohmann::json::array();
  for (int shard = 1; shard <= shards; ++shard) tasks.push_back(shard);
  nlohmann::json jobs = {{"command", cluster::shell_line(command.words)},
                         {"shards", shards},
                         {"result", command.result},
                         {"submissions", nlohmann::json::array()}};
  jobs["submissions"].push_back({{"array", array}, {"tasks", tasks}, {"merge", merge}});
  cluster::write_jobs(folder, jobs);
  std::cout << "shards: job " << array << " (array 1-" << shards << ")\nmerge: job " << merge
            << " (after the shards succeed)\nrecorded in " << folder.jobs() << "\n";
}

}  // namespace

void register_cluster(CLI::App& app) {
  CLI::App* group = app.add_subcommand(
      "cluster", "Run a sharded command on a cluster: Slurm job files, submission, status");
  group->require_subcommand(1);
  auto args = std::make_shared<SlurmArgs>();
  CLI::App* slurm = group->add_subcommand(
      "slurm", "Write the sbatch files of a sharded command into a folder (and submit them)");
  slurm
      ->add_option("--command", args->command,
                   "The tactile command, quoted as one argument: \"tactile features ... --out "
                   "table.csv\" (one of " +
                       joined(cluster::sharded_command_names()) + ")")
      ->required();
  slurm->add_option("--shards", args->options.shards, "Number of shards (array tasks)")->required();
  slurm->add_option("--out", args->out, "Folder for the scripts, parts, logs and jobs.json")
      ->required();
  slurm->add_option("--partition", args->options.partition, "Slurm partition of every job");
  slurm->add_option("--time", args->options.time, "Time limit of each job (sbatch --time)");
  slurm->add_flag("--submit", args->submit,
                  "Submit the shards and the merge with sbatch; ids go into DIR/jobs.json");
  slurm->callback([args] { run_slurm(*args); });
  register_cluster_jobs(group);
}

}  // namespace tactile::cli

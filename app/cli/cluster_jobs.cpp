// `tactile cluster status DIR` and `tactile cluster resubmit DIR --shard I [--shard J]`: the
// jobs that `tactile cluster slurm --submit` recorded in DIR/jobs.json, as Slurm sees them now,
// and a new array of only the failed shards with a new merge after it. docs/CLUSTER.md.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "commands.h"
#include "tactile/cluster/slurm.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

using cluster::CurrentJobs;
using cluster::JobFolder;
using cluster::JobState;
using cluster::SlurmView;

std::string jobs_lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

void run_status(const std::string& dir) {
  const JobFolder folder{std::filesystem::absolute(dir).lexically_normal().string()};
  const nlohmann::json jobs = cluster::read_jobs(folder);
  const int count = jobs.at("shards").get<int>();
  const CurrentJobs current = cluster::current_jobs(jobs);
  std::vector<std::string> ids;
  for (const nlohmann::json& submission : jobs.at("submissions")) {
    ids.push_back(submission.at("array").get<std::string>());
    ids.push_back(submission.at("merge").get<std::string>());
  }
  const SlurmView view = cluster::ask_slurm(ids);
  std::cout << jobs.at("command").get<std::string>() << "\n";
  std::vector<std::string> missing;
  for (int shard = 1; shard <= count; ++shard) {
    const std::string id = current.shard_jobs.count(shard) ? current.shard_jobs.at(shard) : "";
    JobState state;
    if (const auto found = view.jobs.find(id); found != view.jobs.end()) state = found->second;
    const std::string exit_file = cluster::read_exit_file(folder, shard);
    if (state.exit.empty() && !exit_file.empty()) state.exit = exit_file;
    if (state.state.empty() || state.state == "COMPLETING") {
      // Gone from squeue and no accounting: what the job itself left.
      state.state = exit_file.empty() ? "" : (exit_file == "0" ? "COMPLETED" : "FAILED");
      state.source = "exit file";
    }
    const bool part = std::filesystem::is_regular_file(folder.part(shard, count));
    if (!part) missing.push_back(std::to_string(shard));
    std::cout << "shard " << shard << "/" << count << "  job " << id << "  "
              << (state.state.empty() ? "unknown (not in squeue, no exit file: killed or "
                                        "cancelled?)"
                                      : jobs_lower(state.state))
              << (state.exit.empty() ? "" : "  exit " + state.exit)
              << (state.reason.empty() ? "" : "  (" + state.reason + ")") << "  part "
              << (part ? "present" : "missing") << "\n";
  }
  JobState merge;
  if (const auto found = view.jobs.find(current.merge); found != view.jobs.end())
    merge = found->second;
  const std::string result = jobs.at("result").get<std::string>();
  std::cout << "merge  job " << current.merge << "  "
            << (merge.state.empty() ? "unknown (not in squeue)" : jobs_lower(merge.state))
            << (merge.exit.empty() ? "" : "  exit " + merge.exit)
            << (merge.reason.empty() ? "" : "  (" + merge.reason + ")") << "  result "
            << (std::filesystem::exists(result) ? "present" : "missing") << ": " << result << "\n";
  std::cout << "parts: " << count - static_cast<int>(missing.size()) << " of " << count
            << " present" << (missing.empty() ? "" : " (missing: shard " + joined(missing) + ")")
            << "\n";
  if (!view.accounting_note.empty())
    std::cout << "note: " << view.accounting_note
              << " - sacct needs slurmdbd; finished shards are read from the job completion log "
                 "(sacct --completion) if kept, else from squeue while slurmctld holds them and "
                 "from their exit files in "
              << folder.dir << "/logs\n";
}

//---- Resubmission ---------------------------------------------------------------------------

struct ResubmitArgs {
  std::string dir;
  std::vector<int> shards;
};

void run_resubmit(const ResubmitArgs& args) {
  const JobFolder folder{std::filesystem::absolute(args.dir).lexically_normal().string()};
  nlohmann::json jobs = cluster::read_jobs(folder);
  const int count = jobs.at("shards").get<int>();
  const std::set<int> shards(args.shards.begin(), args.shards.end());
  for (const int shard : shards)
    if (shard < 1 || shard > count)
      throw Error("--shard", std::to_string(shard) + " is not a shard of this job (1 to " +
                                 std::to_string(count) + ")");
  if (!cluster::on_path("sbatch"))
    throw Error("resubmit", "sbatch is not on PATH: run on a Slurm login node");
  const CurrentJobs current = cluster::current_jobs(jobs);
  // The old merge waits on an array that will never all succeed: cancel it unless it ran.
  const SlurmView view = cluster::ask_slurm({current.merge});
  const auto old_merge = view.jobs.find(current.merge);
  if (old_merge == view.jobs.end() || old_merge->second.state == "PENDING") {
    const cluster::ProgramOutput scancel = cluster::run_captured({"scancel", current.merge});
    if (scancel.exit_code == 0)
      std::cout << "cancelled the old merge, job " << current.merge << "\n";
  }
  std::vector<std::string> tasks;
  nlohmann::json task_list = nlohmann::json::array();
  for (const int shard : shards) {
    tasks.push_back(std::to_string(shard));
    task_list.push_back(shard);
    std::filesystem::remove(folder.dir + "/logs/shard-" + std::to_string(shard) + ".exit");
  }
  const std::string array = cluster::parsable_job_id(cluster::run_captured(
      {"sbatch", "--parsable", "--array=" + joined(tasks, ","), folder.shards_script()}));
  const std::string merge = cluster::parsable_job_id(cluster::run_captured(
      {"sbatch", "--parsable", "--dependency=afterok:" + array, folder.merge_script()}));
  jobs["submissions"].push_back({{"array", array}, {"tasks", task_list}, {"merge", merge}});
  cluster::write_jobs(folder, jobs);
  std::cout << "shards " << joined(tasks) << ": job " << array << "\nmerge: job " << merge
            << " (after them)\nrecorded in " << folder.jobs() << "\n";
}

}  // namespace

void register_cluster_jobs(CLI::App* cluster) {
  auto status_dir = std::make_shared<std::string>();
  CLI::App* status = cluster->add_subcommand(
      "status", "Each shard's job (pending, running, completed, failed) and part, and the merge");
  status->add_option("DIR", *status_dir, "The folder of `tactile cluster slurm --submit`")
      ->required();
  status->callback([status_dir] { run_status(*status_dir); });

  auto args = std::make_shared<ResubmitArgs>();
  CLI::App* resubmit = cluster->add_subcommand(
      "resubmit", "Submit some shards again (an array of only those) and a new merge after them");
  resubmit->add_option("DIR", args->dir, "The folder of `tactile cluster slurm --submit`")
      ->required();
  resubmit->add_option("--shard", args->shards, "A shard to run again (1..N); repeat for more")
      ->required();
  resubmit->callback([args] { run_resubmit(*args); });
}

}  // namespace tactile::cli

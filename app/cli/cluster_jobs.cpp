// `tactile cluster status DIR` and `tactile cluster resubmit DIR --shard I [--shard J]`: the
// jobs that `tactile cluster slurm --submit` recorded in DIR/jobs.json, as Slurm sees them now,
// and a new array of only the failed shards with a new merge after it. docs/CLUSTER.md.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "cluster.h"
#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

extern char** environ;

namespace tactile::cli {

namespace cluster {

//---- Programs, job ids, jobs.json -----------------------------------------------------------

ProgramOutput run_captured(const std::vector<std::string>& words) {
  ProgramOutput result;
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return result;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  char buffer[4096];
  for (ssize_t got; (got = read(pipe_ends[0], buffer, sizeof buffer)) > 0;)
    result.out.append(buffer, static_cast<size_t>(got));
  close(pipe_ends[0]);
  if (spawned != 0) return result;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');)
    if (!folder.empty() && access((folder + "/" + program).c_str(), X_OK) == 0) return true;
  return false;
}

std::string parsable_job_id(const ProgramOutput& sbatch) {
  std::string last;
  std::stringstream lines(sbatch.out);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) last = line;
  last = last.substr(0, last.find(';'));
  if (sbatch.exit_code != 0 || last.empty() ||
      last.find_first_not_of("0123456789") != std::string::npos)
    throw Error("sbatch",
                sbatch.exit_code < 0
                    ? std::string("could not start (not on PATH?)")
                    : "refused (exit " + std::to_string(sbatch.exit_code) + "): " + sbatch.out);
  return last;
}

nlohmann::json read_jobs(const JobFolder& folder) {
  std::ifstream in(folder.jobs());
  if (!in)
    throw Error(folder.jobs(),
                "cannot open: was `tactile cluster slurm --submit --out " + folder.dir + "` run?");
  try {
    nlohmann::json jobs = nlohmann::json::parse(in);
    if (!jobs.at("shards").is_number_integer() || !jobs.at("submissions").is_array())
      throw Error(folder.jobs(), "not a jobs file of `tactile cluster`");
    return jobs;
  } catch (const nlohmann::json::exception& error) {
    throw Error(folder.jobs(),
                std::string("not a jobs file of `tactile cluster`: ") + error.what());
  }
}

void write_jobs(const JobFolder& folder, const nlohmann::json& jobs) {
  write_file_atomically(folder.jobs(), jobs.dump(2) + "\n", "jobs file");
}

}  // namespace cluster

namespace {

using cluster::JobFolder;

//---- What Slurm says about a job ------------------------------------------------------------

struct JobState {
  std::string state;   // "PENDING", "RUNNING", "COMPLETED", "FAILED", "CANCELLED", ...
  std::string exit;    // "0", "1", ... ("" unknown)
  std::string reason;  // why it waits ("Dependency", "DependencyNeverSatisfied")
  std::string source;  // "squeue", "sacct", "exit file"
};

// Lines "ID|STATE|X|Y" of a Slurm client, by id.
std::map<std::string, std::vector<std::string>> jobs_parse_table(const std::string& out) {
  std::map<std::string, std::vector<std::string>> rows;
  std::stringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '|');) fields.push_back(cell);
    if (fields.size() >= 3) rows[fields[0]] = fields;
  }
  return rows;
}

// "1:0" (code:signal) -> "1"; a signal -> "signal 9".
std::string jobs_exit_text(const std::string& code_and_signal) {
  const size_t colon = code_and_signal.find(':');
  if (colon == std::string::npos) return code_and_signal;
  const std::string signal = code_and_signal.substr(colon + 1);
  if (signal != "0" && !signal.empty()) return "signal " + signal;
  return code_and_signal.substr(0, colon);
}

// Every job id's state that slurmctld still holds (squeue --states=all, array tasks one by one)
// or the accounting keeps (sacct; without slurmdbd, the job completion log: sacct --completion).
struct SlurmView {
  std::map<std::string, JobState> jobs;
  std::string accounting_note;  // why sacct had nothing ("" when it answered)
};

SlurmView jobs_ask_slurm(const std::vector<std::string>& ids) {
  SlurmView view;
  const std::string id_list = joined(ids, ",");
  // %i: "ARRAY_TASK" for array tasks; %T: the state; %r: the reason it waits.
  for (const std::string& id : ids) {
    const cluster::ProgramOutput squeue = cluster::run_captured(
        {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + id, "--format=%i|%T|%r"});
    if (squeue.exit_code != 0) continue;  // gone from slurmctld (MinJobAge) or no Slurm here
    for (const auto& [job, row] : jobs_parse_table(squeue.out))
      view.jobs[job] = {row[1], "", row[2] == "None" ? "" : row[2], "squeue"};
  }
  // Finished jobs' exit codes: squeue has none, so ask the accounting for every id.
  cluster::ProgramOutput sacct =
      cluster::run_captured({"sacct", "--noheader", "--parsable2", "--allocations",
                             "--jobs=" + id_list, "--format=JobID,State,ExitCode"});
  if (sacct.exit_code != 0 ||
      sacct.out.find("accounting storage is disabled") != std::string::npos) {
    view.accounting_note =
        "sacct: " + (sacct.exit_code < 0 ? std::string("not on PATH")
                                         : sacct.out.substr(0, sacct.out.find('\n')));
    sacct = cluster::run_captured({"sacct", "--completion", "--noheader", "--parsable2",
                                   "--jobs=" + id_list, "--format=JobID,State,ExitCode"});
    if (sacct.exit_code != 0) sacct.out.clear();
  }
  for (const auto& [job, row] : jobs_parse_table(sacct.out)) {
    std::string state = row[1].substr(0, row[1].find(' '));  // "CANCELLED by 0"
    JobState& known = view.jobs[job];
    // squeue is current for jobs still queued; the accounting for the rest.
    if (known.source.empty() || (known.state != "PENDING" && known.state != "RUNNING")) {
      known.state = state;
      known.source = "sacct";
    }
    known.exit = jobs_exit_text(row[2]);
  }
  return view;
}

std::string jobs_lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// A shard's current job id ("ARRAY_TASK") and the merge's: the last submission naming each.
struct CurrentJobs {
  std::map<int, std::string> shard_jobs;
  std::string merge;
};

CurrentJobs jobs_current(const nlohmann::json& jobs) {
  CurrentJobs current;
  for (const nlohmann::json& submission : jobs.at("submissions")) {
    const std::string array = submission.at("array").get<std::string>();
    for (const nlohmann::json& task : submission.at("tasks"))
      current.shard_jobs[task.get<int>()] = array + "_" + std::to_string(task.get<int>());
    current.merge = submission.at("merge").get<std::string>();
  }
  return current;
}

std::string jobs_read_exit_file(const JobFolder& folder, int shard) {
  std::ifstream in(folder.dir + "/logs/shard-" + std::to_string(shard) + ".exit");
  std::string code;
  in >> code;
  return code;
}

void run_status(const std::string& dir) {
  const JobFolder folder{std::filesystem::absolute(dir).lexically_normal().string()};
  const nlohmann::json jobs = cluster::read_jobs(folder);
  const int count = jobs.at("shards").get<int>();
  const CurrentJobs current = jobs_current(jobs);
  std::vector<std::string> ids;
  for (const nlohmann::json& submission : jobs.at("submissions")) {
    ids.push_back(submission.at("array").get<std::string>());
    ids.push_back(submission.at("merge").get<std::string>());
  }
  const SlurmView view = jobs_ask_slurm(ids);
  std::cout << jobs.at("command").get<std::string>() << "\n";
  std::vector<std::string> missing;
  for (int shard = 1; shard <= count; ++shard) {
    const std::string id = current.shard_jobs.count(shard) ? current.shard_jobs.at(shard) : "";
    JobState state;
    if (const auto found = view.jobs.find(id); found != view.jobs.end()) state = found->second;
    const std::string exit_file = jobs_read_exit_file(folder, shard);
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
  const CurrentJobs current = jobs_current(jobs);
  // The old merge waits on an array that will never all succeed: cancel it unless it ran.
  const SlurmView view = jobs_ask_slurm({current.merge});
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

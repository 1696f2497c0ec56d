// Slurm's programs run and read: sbatch's job ids, squeue and sacct's states, jobs.json.
#include "tactile/cluster/slurm.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

extern char** environ;

namespace tactile::cluster {

namespace {

// Lines "ID|STATE|X|Y" of a Slurm client, by id.
std::map<std::string, std::vector<std::string>> parse_table(const std::string& out) {
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
std::string exit_text(const std::string& code_and_signal) {
  const size_t colon = code_and_signal.find(':');
  if (colon == std::string::npos) return code_and_signal;
  const std::string signal = code_and_signal.substr(colon + 1);
  if (signal != "0" && !signal.empty()) return "signal " + signal;
  return code_and_signal.substr(0, colon);
}

}  // namespace

SlurmView ask_slurm(const std::vector<std::string>& ids) {
  SlurmView view;
  const std::string id_list = joined(ids, ",");
  // %i: "ARRAY_TASK" for array tasks; %T: the state; %r: the reason it waits.
  for (const std::string& id : ids) {
    const ProgramOutput squeue = run_captured(
        {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + id, "--format=%i|%T|%r"});
    if (squeue.exit_code != 0) continue;  // gone from slurmctld (MinJobAge) or no Slurm here
    for (const auto& [job, row] : parse_table(squeue.out))
      view.jobs[job] = {row[1], "", row[2] == "None" ? "" : row[2], "squeue"};
  }
  // Finished jobs' exit codes: squeue has none, so ask the accounting for every id.
  ProgramOutput sacct = run_captured({"sacct", "--noheader", "--parsable2", "--allocations",
                                      "--jobs=" + id_list, "--format=JobID,State,ExitCode"});
  if (sacct.exit_code != 0 ||
      sacct.out.find("accounting storage is disabled") != std::string::npos) {
    view.accounting_note =
        "sacct: " + (sacct.exit_code < 0 ? std::string("not on PATH")
                                         : sacct.out.substr(0, sacct.out.find('\n')));
    sacct = run_captured({"sacct", "--completion", "--noheader", "--parsable2", "--jobs=" + id_list,
                          "--format=JobID,State,ExitCode"});
    if (sacct.exit_code != 0) sacct.out.clear();
  }
  for (const auto& [job, row] : parse_table(sacct.out)) {
    std::string state = row[1].substr(0, row[1].find(' '));  // "CANCELLED by 0"
    JobState& known = view.jobs[job];
    // squeue is current for jobs still queued; the accounting for the rest.
    if (known.source.empty() || (known.state != "PENDING" && known.state != "RUNNING")) {
      known.state = state;
      known.source = "sacct";
    }
    known.exit = exit_text(row[2]);
  }
  return view;
}

CurrentJobs current_jobs(const nlohmann::json& jobs) {
  CurrentJobs current;
  for (const nlohmann::json& submission : jobs.at("submissions")) {
    const std::string array = submission.at("array").get<std::string>();
    for (const nlohmann::json& task : submission.at("tasks"))
      current.shard_jobs[task.get<int>()] = array + "_" + std::to_string(task.get<int>());
    current.merge = submission.at("merge").get<std::string>();
  }
  return current;
}

std::string read_exit_file(const JobFolder& folder, int shard) {
  std::ifstream in(folder.dir + "/logs/shard-" + std::to_string(shard) + ".exit");
  std::string code;
  in >> code;
  return code;
}

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

std::string program_beside_this_one(const std::string& program) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path beside = self.parent_path() / program;
  if (error || access(beside.c_str(), X_OK) != 0)
    throw Error(program, "not found beside this program (" + beside.string() + ")");
  return beside.string();
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

}  // namespace tactile::cluster

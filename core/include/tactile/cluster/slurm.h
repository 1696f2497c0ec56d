#pragma once
// A sharded command on a Slurm cluster (docs/CLUSTER.md): the command split as a shell splits
// it, the plain sbatch files `tactile cluster slurm` writes (a job array of the shards, a
// merge job after them, a submit script), the job folder and its jobs.json, and what Slurm's
// own programs (sbatch, squeue, sacct) say about the jobs. No scheduler of our own.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tactile::cluster {

//---- Words, programs, the job folder --------------------------------------------------------

// `text` split into words as a POSIX shell splits a simple command: blanks separate words;
// '...' keeps everything; "..." keeps everything but \" \\ \$ \` (escaped); a backslash
// outside quotes keeps the next character. Throws tactile::Error on `where` naming an
// unbalanced quote, a trailing backslash, or an unquoted character a shell would act on
// instead of passing it (; | & < > ( ) $ ` * ? [ ] { } ~ #) - the command must be a plain list
// of words.
std::vector<std::string> split_command(const std::string& text, const std::string& where);

// `word` as a shell reads it back unchanged: as is when it is plain, else in single quotes.
std::string shell_quoted(const std::string& word);
// The words quoted and joined by spaces.
std::string shell_line(const std::vector<std::string>& words);

// Runs `words` (no shell), stdout and stderr captured together; the exit code is -1 when the
// program could not start.
struct ProgramOutput {
  int exit_code = -1;
  std::string out;
};
ProgramOutput run_captured(const std::vector<std::string>& words);

// Whether `program` is an executable file on PATH.
bool on_path(const std::string& program);
// `program` in the folder of the running program (tactile beside tactile-workbench, ...).
// Throws tactile::Error naming where it looked when it is not there.
std::string program_beside_this_one(const std::string& program);

// The job id that `sbatch --parsable` printed ("1234" of "1234" or "1234;cluster"), from its
// last non-empty line. Throws tactile::Error naming sbatch and its output otherwise.
std::string parsable_job_id(const ProgramOutput& sbatch);

// The files a job folder holds.
struct JobFolder {
  std::string dir;  // absolute
  std::string jobs() const { return dir + "/jobs.json"; }
  std::string shards_script() const { return dir + "/shards.sbatch"; }
  std::string merge_script() const { return dir + "/merge.sbatch"; }
  std::string submit_script() const { return dir + "/submit.sh"; }
  std::string part(int shard, int count) const {
    return dir + "/parts/part-" + std::to_string(shard) + "-of-" + std::to_string(count);
  }
};

// DIR/jobs.json: what was submitted. {"command", "shards", "result", "submissions": [{"array":
// ID, "tasks": [I...], "merge": ID}]}; a shard's current job is the last submission holding it.
nlohmann::json read_jobs(const JobFolder& folder);
void write_jobs(const JobFolder& folder, const nlohmann::json& jobs);

//---- The commands that shard and their sbatch files ------------------------------------------

// Each command that shards, by name, with the option that names its result.
const std::map<std::string, std::string>& sharded_result_options();
std::vector<std::string> sharded_command_names();

// The command as checked words: the program (absolute), the sharding subcommand and its
// arguments; and the result it names.
struct ShardedCommand {
  std::vector<std::string> words;
  std::string name;    // "features"
  std::string result;  // absolute
};
// `text` ("tactile features ... --out table.csv") split and checked: a tactile command that
// shards, names its result, and has no --shard/--part of its own. A leading `tactile` becomes
// `program_path` (the running build). Throws tactile::Error naming --command.
ShardedCommand parse_sharded_command(const std::string& text, const std::string& chdir,
                                     const std::string& program_path);

struct SlurmOptions {
  int shards = 0;
  std::string partition, time;  // "" = the cluster's default
};
// The job array of the shards, the merge job, and the script that submits both (afterok).
std::string shards_script(const SlurmOptions& args, const ShardedCommand& command,
                          const JobFolder& folder, const std::string& chdir);
std::string merge_script(const SlurmOptions& args, const ShardedCommand& command,
                         const JobFolder& folder, const std::string& chdir);
std::string submit_script(const JobFolder& folder);
// Written whole, executable.
void write_script(const std::string& path, const std::string& text);

//---- What Slurm says about the jobs -----------------------------------------------------------

struct JobState {
  std::string state;   // "PENDING", "RUNNING", "COMPLETED", "FAILED", "CANCELLED", ...
  std::string exit;    // "0", "1", ... ("" unknown)
  std::string reason;  // why it waits ("Dependency", "DependencyNeverSatisfied")
  std::string source;  // "squeue", "sacct", "exit file"
};

// Every job id's state that slurmctld still holds (squeue --states=all, array tasks one by one)
// or the accounting keeps (sacct; without slurmdbd, the job completion log: sacct --completion).
struct SlurmView {
  std::map<std::string, JobState> jobs;
  std::string accounting_note;  // why sacct had nothing ("" when it answered)
};

SlurmView ask_slurm(const std::vector<std::string>& ids);

// A shard's current job id ("ARRAY_TASK") and the merge's: the last submission naming each.
struct CurrentJobs {
  std::map<int, std::string> shard_jobs;
  std::string merge;
};

CurrentJobs current_jobs(const nlohmann::json& jobs);
// The exit code a shard wrote into DIR/logs/shard-I.exit ("" without one).
std::string read_exit_file(const JobFolder& folder, int shard);

}  // namespace tactile::cluster

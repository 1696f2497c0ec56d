#pragma once
// `tactile cluster`: shared by cmd_cluster.cpp (the sbatch files and their submission) and
// cluster_jobs.cpp (status and resubmission of what was submitted). docs/CLUSTER.md.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tactile::cli::cluster {

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

}  // namespace tactile::cli::cluster

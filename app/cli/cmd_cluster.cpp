// `tactile cluster slurm --command "tactile CMD ... --out RESULT" --shards N --out DIR
//  [--partition P] [--time T] [--submit]`: a sharded command as plain sbatch files a user can
// read and edit (a job array of its shards, a merge job after them, a submit script), and
// with --submit their submission. `tactile cluster status DIR` and `tactile cluster resubmit
// DIR --shard I` are in cluster_jobs.cpp. docs/CLUSTER.md.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include "cluster.h"
#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

namespace tactile::cli {

void register_cluster_jobs(CLI::App* cluster);  // cluster_jobs.cpp

namespace cluster {

//---- Words as a shell splits and quotes them ------------------------------------------------

std::vector<std::string> split_command(const std::string& text, const std::string& where) {
  // Characters an unquoted shell word would act on (operators, expansions, globs, comments).
  static const std::string active = ";|&<>()$`*?[]{}~#";  // ~ and # only where a word starts
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else if (c == '\'') {
      const size_t close = text.find('\'', at + 1);
      if (close == std::string::npos)
        throw Error(where, "unbalanced single quote at character " + std::to_string(at + 1));
      word += text.substr(at + 1, close - at - 1);
      at = close;
      in_word = true;
    } else if (c == '"') {
      size_t close = at + 1;
      for (; close < text.size() && text[close] != '"'; ++close) {
        const char inner = text[close];
        if (inner == '\\' && close + 1 < text.size() &&
            std::string("\"\\$`\n").find(text[close + 1]) != std::string::npos) {
          ++close;
          if (text[close] != '\n') word += text[close];  // backslash-newline joins lines
        } else if (inner == '$' || inner == '`') {
          throw Error(where, std::string("`") + inner + "` inside double quotes at character " +
                                 std::to_string(close + 1) +
                                 ": a shell would expand it; give the value itself");
        } else {
          word += inner;
        }
      }
      if (close >= text.size())
        throw Error(where, "unbalanced double quote at character " + std::to_string(at + 1));
      at = close;
      in_word = true;
    } else if (c == '\\') {
      if (at + 1 >= text.size())
        throw Error(where, "a backslash at the end with nothing to escape");
      ++at;
      if (text[at] != '\n') word += text[at];
      in_word = in_word || text[at] != '\n';
    } else if (active.find(c) != std::string::npos && !((c == '#' || c == '~') && in_word)) {
      throw Error(where, std::string("unquoted `") + c + "` at character " +
                             std::to_string(at + 1) +
                             ": a shell would act on it; quote it or give a plain command");
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

std::string shell_quoted(const std::string& word) {
  static const std::string plain =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=/.,:@%";
  if (!word.empty() && word.find_first_not_of(plain) == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_line(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    line += shell_quoted(word);
  }
  return line;
}

}  // namespace cluster

namespace {

using cluster::JobFolder;
using cluster::shell_quoted;

//---- The commands that shard ----------------------------------------------------------------

// Each command that shards, by name, with the option that names its result (what one process
// writes; the merge writes it again).
const std::map<std::string, std::string>& cluster_result_options() {
  static const std::map<std::string, std::string> table = {
      {"simulate", "--out"}, {"segment", "--labels"}, {"features", "--out"},
      {"evaluate", "--out"}, {"predict", "--labels"}, {"experiment", "--out"},
      {"verify", "--out"},
  };
  return table;
}

std::vector<std::string> cluster_command_names() {
  std::vector<std::string> names;
  for (const auto& [name, option] : cluster_result_options()) names.push_back(name);
  return names;
}

// The value of `option` in `words` ("--out X" or "--out=X"); "" when absent.
std::string cluster_option_value(const std::vector<std::string>& words, const std::string& option) {
  std::string value;
  for (size_t at = 0; at < words.size(); ++at) {
    if (words[at] == option && at + 1 < words.size()) value = words[at + 1];
    if (words[at].rfind(option + "=", 0) == 0) value = words[at].substr(option.size() + 1);
  }
  return value;
}

// The running program, so that the jobs run the same build (/proc/self/exe).
std::string cluster_this_program() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string("tactile") : path.string();
}

struct SlurmArgs {
  std::string command, out, partition, time;
  int shards = 0;
  bool submit = false;
};

// The command as checked words: the program (absolute), the sharding subcommand and its
// arguments; and the result it names.
struct ShardedCommand {
  std::vector<std::string> words;
  std::string name;    // "features"
  std::string result;  // absolute
};

ShardedCommand cluster_parse_command(const std::string& text, const std::string& chdir) {
  ShardedCommand command;
  command.words = cluster::split_command(text, "--command");
  if (command.words.size() < 2)
    throw Error("--command",
                "give a whole tactile command, e.g. \"tactile features ... --out "
                "table.csv\"");
  const std::string program = command.words[0];
  if (program != "tactile" && std::filesystem::path(program).filename() != "tactile")
    throw Error("--command", "'" + program + "' is not tactile: only tactile commands shard");
  if (program == "tactile") command.words[0] = cluster_this_program();
  command.name = command.words[1];
  const auto option = cluster_result_options().find(command.name);
  if (option == cluster_result_options().end())
    throw Error("--command", "`tactile " + command.name + "` does not shard (these do: " +
                                 joined(cluster_command_names()) + ")");
  for (const std::string& word : command.words)
    if (word == "--shard" || word == "--part" || word.rfind("--shard=", 0) == 0 ||
        word.rfind("--part=", 0) == 0)
      throw Error("--command", "has " + word + " already: the job array gives each shard its own");
  const std::string result = cluster_option_value(command.words, option->second);
  if (result.empty())
    throw Error("--command", "`tactile " + command.name + "` names its result with " +
                                 option->second + ", which the command does not give");
  command.result = (std::filesystem::path(chdir) / result).lexically_normal().string();
  return command;
}

//---- The sbatch files -----------------------------------------------------------------------

// The #SBATCH lines every job of the folder shares: where it runs and what the user asked for,
// then the usual settings to edit, commented out.
std::string cluster_common_options(const SlurmArgs& args, const std::string& chdir) {
  std::string text = "#SBATCH --chdir=" + shell_quoted(chdir) + "\n";
  if (!args.partition.empty()) text += "#SBATCH --partition=" + shell_quoted(args.partition) + "\n";
  if (!args.time.empty()) text += "#SBATCH --time=" + shell_quoted(args.time) + "\n";
  text += "# Edit for your cluster (remove one '#' to use a line):\n" +
          std::string(args.partition.empty() ? "##SBATCH --partition=batch\n" : "") +
          (args.time.empty() ? "##SBATCH --time=01:00:00\n" : "") +
          "##SBATCH --mem=4G\n"
          "##SBATCH --cpus-per-task=1\n"
          "##SBATCH --account=myproject\n";
  return text;
}

std::string cluster_modules_note() {
  return "\n# Load what tactile needs on the compute nodes if it is not there already, e.g.:\n"
         "# module load gcc hdf5\n\n";
}

std::string cluster_shards_script(const SlurmArgs& args, const ShardedCommand& command,
                                  const JobFolder& folder, const std::string& chdir) {
  const std::string count = std::to_string(args.shards);
  std::string text = "#!/bin/bash\n";
  text += "# Shard ${SLURM_ARRAY_TASK_ID} of " + count +
          " of this command, one array task each:\n#   " + cluster::shell_line(command.words) +
          "\n";
  text += "# Each task writes its part into " + folder.dir +
          "/parts; merge.sbatch combines them into\n#   " + command.result + "\n";
  text +=
      "# Written by `tactile cluster slurm` (docs/CLUSTER.md). Run one shard by hand with\n"
      "#   SLURM_ARRAY_TASK_ID=I bash " +
      shell_quoted(folder.shards_script()) + "\n";
  text += "#SBATCH --job-name=tactile-" + command.name + "\n";
  text += "#SBATCH --array=1-" + count + "\n";
  text += "#SBATCH --output=" + shell_quoted(folder.dir + "/logs/shard-%a.job-%A.out") + "\n";
  text += "#SBATCH --error=" + shell_quoted(folder.dir + "/logs/shard-%a.job-%A.err") + "\n";
  text += cluster_common_options(args, chdir);
  text += cluster_modules_note();
  text += "shard=${SLURM_ARRAY_TASK_ID:?run by sbatch --array, or set SLURM_ARRAY_TASK_ID}\n";
  text += "cd " + shell_quoted(chdir) + " || exit 1\n";
  text += cluster::shell_line(command.words) + " \\\n  --shard \"${shard}/" + count + "\" --part " +
          shell_quoted(folder.dir + "/parts/part-") + "\"${shard}\"" +
          shell_quoted("-of-" + count) + "\n";
  text += "code=$?\n";
  text += "# Its exit code, for `tactile cluster status` where sacct keeps no history.\n";
  text += "echo \"${code}\" > " + shell_quoted(folder.dir + "/logs/shard-") + "\"${shard}\"" +
          shell_quoted(".exit") + "\n";
  text += "exit \"${code}\"\n";
  return text;
}

std::string cluster_merge_script(const SlurmArgs& args, const ShardedCommand& command,
                                 const JobFolder& folder, const std::string& chdir) {
  std::string line = shell_quoted(command.words[0]) + " merge";
  for (int shard = 1; shard <= args.shards; ++shard)
    line += " \\\n  " + shell_quoted(folder.part(shard, args.shards));
  line += " \\\n  --out " + shell_quoted(command.result);
  std::string text = "#!/bin/bash\n";
  text += "# The " + std::to_string(args.shards) + " parts of shards.sbatch combined into\n#   " +
          command.result + "\n";
  text += "# exactly as one process writes it. `tactile merge` names any part that is missing.\n";
  text +=
      "# Written by `tactile cluster slurm` (docs/CLUSTER.md); submitted after the shards\n"
      "# with --dependency=afterok (submit.sh). Run it by hand with: bash " +
      shell_quoted(folder.merge_script()) + "\n";
  text += "#SBATCH --job-name=tactile-" + command.name + "-merge\n";
  text += "#SBATCH --output=" + shell_quoted(folder.dir + "/logs/merge.job-%j.out") + "\n";
  text += "#SBATCH --error=" + shell_quoted(folder.dir + "/logs/merge.job-%j.err") + "\n";
  text += cluster_common_options(args, chdir);
  text += cluster_modules_note();
  text += "cd " + shell_quoted(chdir) + " || exit 1\n";
  text += line + "\n";
  return text;
}

std::string cluster_submit_script(const JobFolder& folder) {
  return "#!/bin/bash\n"
         "# Submits the shards as one job array, then the merge to run when every shard has\n"
         "# succeeded. Written by `tactile cluster slurm` (docs/CLUSTER.md).\n"
         "set -euo pipefail\n"
         "array=$(sbatch --parsable " +
         shell_quoted(folder.shards_script()) +
         ")\n"
         "array=${array%%;*}  # \"ID;cluster\" on a federation\n"
         "merge=$(sbatch --parsable --dependency=afterok:\"${array}\" " +
         shell_quoted(folder.merge_script()) +
         ")\n"
         "merge=${merge%%;*}\n"
         "echo \"shards: job ${array}\"\n"
         "echo \"merge: job ${merge}\"\n";
}

void cluster_write_script(const std::string& path, const std::string& text) {
  write_file_atomically(path, text, "script");
  std::filesystem::permissions(path,
                               std::filesystem::perms::owner_exec |
                                   std::filesystem::perms::group_exec |
                                   std::filesystem::perms::others_exec,
                               std::filesystem::perm_options::add);
}

void run_slurm(const SlurmArgs& args) {
  if (args.shards < 1) throw Error("--shards", "give the number of shards, 1 or more");
  const std::string chdir = std::filesystem::current_path().string();
  const ShardedCommand command = cluster_parse_command(args.command, chdir);
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
  cluster_write_script(folder.shards_script(), cluster_shards_script(args, command, folder, chdir));
  cluster_write_script(folder.merge_script(), cluster_merge_script(args, command, folder, chdir));
  cluster_write_script(folder.submit_script(), cluster_submit_script(folder));
  std::cout << "wrote " << folder.shards_script() << " (" << args.shards << " shards), "
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
  for (int shard = 1; shard <= args.shards; ++shard) tasks.push_back(shard);
  nlohmann::json jobs = {{"command", cluster::shell_line(command.words)},
                         {"shards", args.shards},
                         {"result", command.result},
                         {"submissions", nlohmann::json::array()}};
  jobs["submissions"].push_back({{"array", array}, {"tasks", tasks}, {"merge", merge}});
  cluster::write_jobs(folder, jobs);
  std::cout << "shards: job " << array << " (array 1-" << args.shards << ")\nmerge: job " << merge
            << " (after the shards succeed)\nrecorded in " << folder.jobs() << "\n";
}

}  // namespace

void register_cluster(CLI::App& app) {
  CLI::App* cluster = app.add_subcommand(
      "cluster", "Run a sharded command on a cluster: Slurm job files, submission, status");
  cluster->require_subcommand(1);
  auto args = std::make_shared<SlurmArgs>();
  CLI::App* slurm = cluster->add_subcommand(
      "slurm", "Write the sbatch files of a sharded command into a folder (and submit them)");
  slurm
      ->add_option("--command", args->command,
                   "The tactile command, quoted as one argument: \"tactile features ... --out "
                   "table.csv\" (one of " +
                       joined(cluster_command_names()) + ")")
      ->required();
  slurm->add_option("--shards", args->shards, "Number of shards (array tasks)")->required();
  slurm->add_option("--out", args->out, "Folder for the scripts, parts, logs and jobs.json")
      ->required();
  slurm->add_option("--partition", args->partition, "Slurm partition of every job");
  slurm->add_option("--time", args->time, "Time limit of each job (sbatch --time)");
  slurm->add_flag("--submit", args->submit,
                  "Submit the shards and the merge with sbatch; ids go into DIR/jobs.json");
  slurm->callback([args] { run_slurm(*args); });
  register_cluster_jobs(cluster);
}

}  // namespace tactile::cli

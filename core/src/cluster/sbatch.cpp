// The sbatch files of a sharded command: the job array of its shards, the merge after them.
#include <filesystem>
#include <map>

#include "tactile/cluster/slurm.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/text.h"

namespace tactile::cluster {

namespace {

// The value of `option` in `words` ("--out X" or "--out=X"); "" when absent.
std::string option_value(const std::vector<std::string>& words, const std::string& option) {
  std::string value;
  for (size_t at = 0; at < words.size(); ++at) {
    if (words[at] == option && at + 1 < words.size()) value = words[at + 1];
    if (words[at].rfind(option + "=", 0) == 0) value = words[at].substr(option.size() + 1);
  }
  return value;
}

// The #SBATCH lines every job of the folder shares: where it runs and what the user asked for,
// then the usual settings to edit, commented out.
std::string common_options(const SlurmOptions& args, const std::string& chdir) {
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

std::string modules_note() {
  return "\n# Load what tactile needs on the compute nodes if it is not there already, e.g.:\n"
         "# module load gcc hdf5\n\n";
}

}  // namespace

// Each command that shards, by name, with the option that names its result (what one process
// writes; the merge writes it again).
const std::map<std::string, std::string>& sharded_result_options() {
  static const std::map<std::string, std::string> table = {
      {"simulate", "--out"}, {"segment", "--labels"}, {"features", "--out"},
      {"evaluate", "--out"}, {"predict", "--labels"}, {"experiment", "--out"},
      {"verify", "--out"},
  };
  return table;
}

std::vector<std::string> sharded_command_names() {
  std::vector<std::string> names;
  for (const auto& [name, option] : sharded_result_options()) names.push_back(name);
  return names;
}

ShardedCommand parse_sharded_command(const std::string& text, const std::string& chdir,
                                     const std::string& program_path) {
  ShardedCommand command;
  command.words = split_command(text, "--command");
  if (command.words.size() < 2)
    throw Error("--command",
                "give a whole tactile command, e.g. \"tactile features ... --out "
                "table.csv\"");
  const std::string program = command.words[0];
  if (program != "tactile" && std::filesystem::path(program).filename() != "tactile")
    throw Error("--command", "'" + program + "' is not tactile: only tactile commands shard");
  if (program == "tactile") command.words[0] = program_path;
  command.name = command.words[1];
  const auto option = sharded_result_options().find(command.name);
  if (option == sharded_result_options().end())
    throw Error("--command", "`tactile " + command.name + "` does not shard (these do: " +
                                 joined(sharded_command_names()) + ")");
  for (const std::string& word : command.words)
    if (word == "--shard" || word == "--part" || word.rfind("--shard=", 0) == 0 ||
        word.rfind("--part=", 0) == 0)
      throw Error("--command", "has " + word + " already: the job array gives each shard its own");
  const std::string result = option_value(command.words, option->second);
  if (result.empty())
    throw Error("--command", "`tactile " + command.name + "` names its result with " +
                                 option->second + ", which the command does not give");
  command.result = (std::filesystem::path(chdir) / result).lexically_normal().string();
  return command;
}

std::string shards_script(const SlurmOptions& args, const ShardedCommand& command,
                          const JobFolder& folder, const std::string& chdir) {
  const std::string count = std::to_string(args.shards);
  std::string text = "#!/bin/bash\n";
  text += "# Shard ${SLURM_ARRAY_TASK_ID} of " + count +
          " of this command, one array task each:\n#   " + shell_line(command.words) + "\n";
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
  text += common_options(args, chdir);
  text += modules_note();
  text += "shard=${SLURM_ARRAY_TASK_ID:?run by sbatch --array, or set SLURM_ARRAY_TASK_ID}\n";
  text += "cd " + shell_quoted(chdir) + " || exit 1\n";
  text += shell_line(command.words) + " \\\n  --shard \"${shard}/" + count + "\" --part " +
          shell_quoted(folder.dir + "/parts/part-") + "\"${shard}\"" +
          shell_quoted("-of-" + count) + "\n";
  text += "code=$?\n";
  text += "# Its exit code, for `tactile cluster status` where sacct keeps no history.\n";
  text += "echo \"${code}\" > " + shell_quoted(folder.dir + "/logs/shard-") + "\"${shard}\"" +
          shell_quoted(".exit") + "\n";
  text += "exit \"${code}\"\n";
  return text;
}

std::string merge_script(const SlurmOptions& args, const ShardedCommand& command,
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
  text += common_options(args, chdir);
  text += modules_note();
  text += "cd " + shell_quoted(chdir) + " || exit 1\n";
  text += line + "\n";
  return text;
}

std::string submit_script(const JobFolder& folder) {
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

void write_script(const std::string& path, const std::string& text) {
  write_file_atomically(path, text, "script");
  std::filesystem::permissions(path,
                               std::filesystem::perms::owner_exec |
                                   std::filesystem::perms::group_exec |
                                   std::filesystem::perms::others_exec,
                               std::filesystem::perm_options::add);
}

}  // namespace tactile::cluster

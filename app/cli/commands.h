#pragma once
// Each `tactile` subcommand lives in its own file and registers itself here.
// A command's callback throws tactile::Error on bad input; main() prints it as
// one line on stderr and exits non-zero.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "tactile/shards/shard.h"

namespace tactile::cli {

// The command line: parses, runs the command, prints a refusal; the exit code (run.cpp).
int run(int argc, char** argv);

void register_info(CLI::App& app);
void register_import(CLI::App& app);
void register_export(CLI::App& app);
void register_labels(CLI::App& app);
void register_segment(CLI::App& app);
void register_features(CLI::App& app);
void register_simulate(CLI::App& app);
void register_stream_sim(CLI::App& app);
void register_stream_listen(CLI::App& app);
void register_evaluate(CLI::App& app);
void register_experiment(CLI::App& app);
void register_verify(CLI::App& app);
void register_predict(CLI::App& app);
void register_merge(CLI::App& app);
void register_cluster(CLI::App& app);
void register_video(CLI::App& app);
// `tactile video sync` (cmd_video_sync.cpp), added to the `video` command by register_video.
void register_video_sync(CLI::App& video);
void register_clip(CLI::App& app);

// Files as given; folders expanded to their .h5 files, sorted, so runs are repeatable.
// Throws tactile::Error naming an input that is neither, or a folder with no recording.
std::vector<std::string> recording_files(const std::vector<std::string>& inputs);

//---- Shards (docs/CLUSTER.md) -------------------------------------------------------------

// --shard I/N and --part FILE, as every command that shards takes them.
struct ShardArgs {
  std::string shard;  // "I/N"; "" = the whole job
  std::string part;   // "" = RESULT.part-I-of-N
};
void add_shard_options(CLI::App* command, ShardArgs& args);
// The shard asked for and the file its part goes to (`result`: what one process writes).
// Throws tactile::Error naming --shard, or --part given without --shard.
struct ShardPlan {
  Shard shard;
  std::string part;
};
ShardPlan shard_plan(const ShardArgs& args, const std::string& result);
// Writes the part and says so on stdout: "shard 2/4: 13 of 50 items -> FILE".
void write_shard_part(const ShardPlan& plan, const Part& part);

// `tactile merge`: each sharded command's merge of its parts (gathered: checked against
// each other, in shard order) into `out`, which one process would have written.
void merge_features(const std::vector<Part>& parts, const std::string& out);
void merge_evaluate(const std::vector<Part>& parts, const std::string& out);
void merge_experiment(const std::vector<Part>& parts, const std::string& out);
void merge_simulate(const std::vector<Part>& parts, const std::string& out);
void merge_segment(const std::vector<Part>& parts, const std::string& out);
void merge_predict(const std::vector<Part>& parts, const std::string& out);
void merge_verify(const std::vector<Part>& parts, const std::string& out);

}  // namespace tactile::cli

// `tactile merge PART... [--out RESULT]`: combines the part files of a sharded command
// (`--shard I/N`) into exactly what one process would have written. Every part is checked
// first: a missing, duplicated or mismatched shard is refused by name and nothing is written.
// Also the shared flags --shard/--part of the commands that shard.
#include <iostream>
#include <map>
#include <memory>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

using PartMerger = void (*)(const std::vector<Part>& parts, const std::string& out);

// Every command whose parts merge, by the name its parts carry.
const std::map<std::string, PartMerger>& mergers() {
  static const std::map<std::string, PartMerger> table = {
      {"features", merge_features}, {"evaluate", merge_evaluate}, {"experiment", merge_experiment},
      {"simulate", merge_simulate}, {"segment", merge_segment},   {"predict", merge_predict},
      {"verify", merge_verify},
  };
  return table;
}

struct MergeArgs {
  std::vector<std::string> parts;
  std::string out;
};

void run_merge(const MergeArgs& args) {
  if (args.parts.empty()) throw Error("merge", "give the part files to merge");
  // The command comes from the first part; gather_parts holds the others to it.
  const std::string command = read_part(args.parts.front()).command;
  const auto merger = mergers().find(command);
  if (merger == mergers().end())
    throw Error(args.parts.front(), "parts of `tactile " + command +
                                        "` do not merge (known: " + joined([] {
                                          std::vector<std::string> names;
                                          for (const auto& [name, merge] : mergers())
                                            names.push_back(name);
                                          return names;
                                        }()) +
                                        ")");
  const std::vector<Part> parts = gather_parts(args.parts, command);
  merger->second(parts, args.out.empty() ? parts.front().result : args.out);
}

}  // namespace

void add_shard_options(CLI::App* command, ShardArgs& args) {
  command->add_option("--shard", args.shard,
                      "I/N: do only shard I of N (1 <= I <= N) and write a part file for "
                      "`tactile merge` (docs/CLUSTER.md)");
  command->add_option(
      "--part", args.part,
      "With --shard: the part file (default: RESULT.part-I-of-N beside the result)");
}

ShardPlan shard_plan(const ShardArgs& args, const std::string& result) {
  ShardPlan plan;
  plan.shard = Shard::parse(args.shard);
  if (!plan.shard.active() && !args.part.empty())
    throw Error("--part", "belongs to a shard: give --shard I/N too");
  if (plan.shard.active())
    plan.part = args.part.empty() ? default_part_path(result, plan.shard) : args.part;
  return plan;
}

void write_shard_part(const ShardPlan& plan, const Part& part) {
  write_part(plan.part, part);
  std::cout << "shard " << plan.shard.to_string() << ": " << part.done.size() << " of "
            << part.items << " items -> " << plan.part << "\n";
}

void register_merge(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* command = app.add_subcommand(
      "merge", "Combine the part files of a sharded command (--shard I/N) into its one result");
  command->add_option("PARTS", args->parts, "Part files, one per shard, in any order")->required();
  command->add_option("--out", args->out,
                      "The result (default: the one the parts name, as one process writes it)");
  command->callback([args] { run_merge(*args); });
}

}  // namespace tactile::cli

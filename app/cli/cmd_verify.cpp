// `tactile verify PATH... [--json]`: reads every chunk, attribute and row of the
// recordings and label stores given (folders walked), prints one line per problem
// and exits non-zero if there is any. `tactile upgrade FILE...`: rewrites files of
// earlier versions in the current, checked format. `tactile repair FILE...`: mends what
// a failed write left (docs/FILE_FORMAT.md, "Repair").
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/verify/repair.h"
#include "tactile/verify/verify.h"

namespace tactile::cli {

namespace {

struct VerifyOptions {
  std::vector<std::string> paths;
  bool json = false;
  std::string out;
  ShardArgs shard;
};

// Problems found are the command's result, not an error of the command: exit 1
// without the "tactile:" error line.
[[noreturn]] void exit_with_problems() {
  std::cout.flush();
  std::exit(1);
}

// What verify says of a report: --json's document, or a line per problem and the summary;
// REPORT.json written when asked; exit 1 when there are problems.
void finish_verify(const VerifyReport& report, bool json, const std::string& out) {
  if (!out.empty()) write_file_atomically(out, verify_report_json(report), "verify report");
  if (json) {
    std::cout << verify_report_json(report);
  } else {
    for (const FileProblem& problem : report.problems) std::cout << problem.message << "\n";
    std::cerr << verify_summary_line(report) << "\n";
  }
  if (!report.problems.empty()) exit_with_problems();
}

nlohmann::json problems_json(const std::vector<FileProblem>& problems) {
  nlohmann::json list = nlohmann::json::array();
  for (const FileProblem& problem : problems)
    list.push_back({{"file", problem.file}, {"problem", problem.message}});
  return list;
}

std::vector<FileProblem> problems_of(const nlohmann::json& list) {
  std::vector<FileProblem> problems;
  for (const nlohmann::json& problem : list)
    problems.push_back(
        {problem.at("file").get<std::string>(), problem.at("problem").get<std::string>()});
  return problems;
}

void run_verify(const VerifyOptions& options) {
  const ShardPlan plan = shard_plan(options.shard, options.out);
  if (plan.shard.active() && options.out.empty())
    throw Error("--shard", "give --out REPORT.json too: the report merge writes");
  const VerifyPlan files = verify_plan(options.paths);
  if (!plan.shard.active()) {
    finish_verify(verify_report(files, verify_items(files)), options.json, options.out);
    return;
  }
  // Its files' problems only: the report is merge's to write.
  Part part;
  part.command = "verify";
  part.shard = plan.shard;
  part.inputs = {{"paths", options.paths}};
  part.result = options.out;
  part.items = static_cast<int64_t>(files.files.size());
  part.plan = plan_digest(files.files);
  part.shared = {{"walk_problems", problems_json(files.walk_problems)}};
  part.done = nlohmann::json::array();
  for (const VerifiedItem& item : verify_items(files, plan.shard))
    part.done.push_back({{"index", item.index},
                         {"path", item.file.path},
                         {"kind", file_kind_name(item.file.kind)},
                         {"problems", problems_json(item.problems)}});
  write_shard_part(plan, part);
}

void run_upgrade(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) std::cout << upgrade_line(path, upgrade_file(path)) << "\n";
}

// Every file is tried; the command fails (after the others) when one could not be repaired.
void run_repair(const std::vector<std::string>& paths) {
  std::string failure;
  for (const std::string& path : paths) {
    try {
      for (const std::string& line : repair_lines(path, repair_recording(path)))
        std::cout << line << "\n";
    } catch (const Error& error) {
      std::cout.flush();
      std::cerr << "tactile: " << error.what() << "\n";
      failure = error.what();
    }
  }
  if (!failure.empty()) exit_with_problems();
}

}  // namespace

void merge_verify(const std::vector<Part>& parts, const std::string& out) {
  VerifyPlan plan;
  plan.walk_problems = problems_of(parts.front().shared.at("walk_problems"));
  std::vector<VerifiedItem> items;
  for (const nlohmann::json& entry : items_in_order(parts)) {
    VerifiedItem item;
    item.index = entry.at("index").get<size_t>();
    item.problems = problems_of(entry.at("problems"));
    item.file = {entry.at("path").get<std::string>(),
                 parse_file_kind(entry.at("kind").get<std::string>()), item.problems.size()};
    items.push_back(std::move(item));
  }
  finish_verify(verify_report(plan, items), false, out);
}

void register_verify(CLI::App& app) {
  auto options = std::make_shared<VerifyOptions>();
  CLI::App* command = app.add_subcommand(
      "verify", "Read every chunk, attribute and label row; one line per problem, exit 1 if any");
  command->add_option("paths", options->paths, "Recordings, label stores or folders")->required();
  command->add_flag("--json", options->json, "Print a machine-readable report");
  command->add_option("--out", options->out,
                      "Also write the --json report to this file (atomically)");
  add_shard_options(command, options->shard);
  command->callback([options] { run_verify(*options); });

  auto paths = std::make_shared<std::vector<std::string>>();
  CLI::App* upgrade = app.add_subcommand(
      "upgrade", "Rewrite recordings and label stores of earlier versions in the checked format");
  upgrade->add_option("files", *paths, "Recordings (.h5) and label stores")->required();
  upgrade->callback([paths] { run_upgrade(*paths); });

  auto damaged = std::make_shared<std::vector<std::string>>();
  CLI::App* repair = app.add_subcommand("repair",
                                        "Mend recordings a failed write left (full disk): rebuild "
                                        "the overview and count, name what was lost");
  repair->add_option("files", *damaged, "Recordings (.h5)")->required();
  repair->callback([damaged] { run_repair(*damaged); });
}

}  // namespace tactile::cli

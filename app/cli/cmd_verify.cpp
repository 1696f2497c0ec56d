// `tactile verify PATH... [--json]`: reads every chunk, attribute and row of the
// recordings and label stores given (folders walked), prints one line per problem
// and exits non-zero if there is any. `tactile upgrade FILE...`: rewrites files of
// earlier versions in the current, checked format. `tactile repair FILE...`: mends what
// a failed write left (docs/FILE_FORMAT.md, "Repair").
#include <iostream>
#include <memory>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/repair.h"
#include "tactile/io/verify.h"

namespace tactile::cli {

namespace {

struct VerifyOptions {
  std::vector<std::string> paths;
  bool json = false;
};

// Problems found are the command's result, not an error of the command: exit 1
// without the "tactile:" error line.
[[noreturn]] void exit_with_problems() {
  std::cout.flush();
  std::exit(1);
}

void run_verify(const VerifyOptions& options) {
  const VerifyReport report = verify_paths(options.paths);
  if (options.json) {
    std::cout << verify_report_json(report);
  } else {
    for (const FileProblem& problem : report.problems) std::cout << problem.message << "\n";
    std::cerr << verify_summary_line(report) << "\n";
  }
  if (!report.problems.empty()) exit_with_problems();
}

void run_upgrade(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) std::cout << upgrade_line(path, upgrade_file(path)) << "\n";
}

// Every file is tried; the command fails (after the others) when one could not be repaired.
void run_repair(const std::vector<std::string>& paths) {
  std::string failure;
  for (const std::string& path : paths) {
    try {
      for (const std::string& line : repair_lines(path, repair_recording(path))) std::cout << line << "\n";
    } catch (const Error& error) {
      std::cout.flush();
      std::cerr << "tactile: " << error.what() << "\n";
      failure = error.what();
    }
  }
  if (!failure.empty()) exit_with_problems();
}

}  // namespace

void register_verify(CLI::App& app) {
  auto options = std::make_shared<VerifyOptions>();
  CLI::App* command = app.add_subcommand(
      "verify", "Read every chunk, attribute and label row; one line per problem, exit 1 if any");
  command->add_option("paths", options->paths, "Recordings, label stores or folders")
      ->required();
  command->add_flag("--json", options->json, "Print a machine-readable report");
  command->callback([options] { run_verify(*options); });

  auto paths = std::make_shared<std::vector<std::string>>();
  CLI::App* upgrade = app.add_subcommand(
      "upgrade", "Rewrite recordings and label stores of earlier versions in the checked format");
  upgrade->add_option("files", *paths, "Recordings (.h5) and label stores")->required();
  upgrade->callback([paths] { run_upgrade(*paths); });

  auto damaged = std::make_shared<std::vector<std::string>>();
  CLI::App* repair = app.add_subcommand(
      "repair", "Mend recordings a failed write left (full disk): rebuild the overview and count, name what was lost");
  repair->add_option("files", *damaged, "Recordings (.h5)")->required();
  repair->callback([damaged] { run_repair(*damaged); });
}

}  // namespace tactile::cli

// `tactile verify PATH... [--json]`: reads every chunk, attribute and row of the
// recordings and label stores given (folders walked), prints one line per problem
// and exits non-zero if there is any. `tactile upgrade FILE...`: rewrites files of
// earlier versions in the current, checked format.
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/verify.h"

namespace tactile::cli {

namespace {

struct VerifyOptions {
  std::vector<std::string> paths;
  bool json = false;
};

const char* kind_name(FileKind kind) {
  switch (kind) {
    case FileKind::kRecording:
      return "recording";
    case FileKind::kLabelStore:
      return "labels";
    case FileKind::kUnknown:
      break;
  }
  return "unknown";
}

// Problems found are the command's result, not an error of the command: exit 1
// without the "tactile:" error line.
[[noreturn]] void exit_with_problems() {
  std::cout.flush();
  std::exit(1);
}

void run_verify(const VerifyOptions& options) {
  const VerifyReport report = verify_paths(options.paths);
  if (options.json) {
    nlohmann::json files = nlohmann::json::array();
    for (const VerifiedFile& file : report.files)
      files.push_back({{"path", file.path}, {"kind", kind_name(file.kind)}, {"problems", file.problems}});
    nlohmann::json problems = nlohmann::json::array();
    for (const FileProblem& problem : report.problems)
      problems.push_back({{"file", problem.file}, {"problem", problem.message}});
    std::cout << nlohmann::json{{"files", files}, {"problems", problems}, {"ok", report.problems.empty()}}
                     .dump(2)
              << "\n";
  } else {
    for (const FileProblem& problem : report.problems) std::cout << problem.message << "\n";
    size_t recordings = 0, stores = 0;
    for (const VerifiedFile& file : report.files) {
      recordings += file.kind == FileKind::kRecording;
      stores += file.kind == FileKind::kLabelStore;
    }
    std::cerr << "verified " << recordings << " recording(s) and " << stores
              << " label store(s): "
              << (report.problems.empty() ? "no problems"
                                          : std::to_string(report.problems.size()) + " problem(s)")
              << "\n";
  }
  if (!report.problems.empty()) exit_with_problems();
}

void run_upgrade(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    const UpgradeResult result = upgrade_file(path);
    const char* what = result.kind == FileKind::kRecording ? "format" : "schema";
    if (result.rewritten())
      std::cout << path << ": " << what << " " << result.from_version << " -> "
                << result.to_version << "\n";
    else
      std::cout << path << ": already " << what << " " << result.to_version << "\n";
  }
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
}

}  // namespace tactile::cli

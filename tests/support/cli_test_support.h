#pragma once
// Shared by the command-line end-to-end tests: a temporary folder per test and a way
// to run a built program with its output captured.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "temp_folder.h"
#include "test_paths.h"

namespace tactile::test {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A workbench script (docs/SCRIPTING.md) written into `folder` as `name`, or by default as
// script-N.txt (the first N not taken), each `@` of `text` replaced by the folder's path and a
// slash; returns its path.
inline std::string write_script(const TempFolder& folder, std::string text,
                                const std::string& name = "") {
  for (size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at))
    text.replace(at, 1, folder.path().string() + "/");
  std::string path = name.empty() ? "" : folder.file(name);
  for (int n = 1; path.empty() || (name.empty() && std::filesystem::exists(path)); ++n)
    path = folder.file("script-" + std::to_string(n) + ".txt");
  std::ofstream(path) << text;
  return path;
}

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `<bin dir>/<program> <arguments>` through the shell, stdout and stderr captured
// in files of `folder`.
// `environment`: "NAME=value ..." set for the program alone.
inline CommandResult run_program(const std::string& program, const std::string& arguments,
                                 const TempFolder& folder, const std::string& environment = "") {
  const std::string out = folder.file(".stdout.txt");
  const std::string err = folder.file(".stderr.txt");
  const std::string command = environment + (environment.empty() ? "" : " ") +
                              tactile::test::bin_dir() + "/" + program + " " + arguments + " >'" +
                              out + "' 2>'" + err + "' </dev/null";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_text(out);
  result.err = read_text(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return result;
}

// `tactile import ARGUMENTS --out OUT` refused for each case: a non-zero exit, `expected` in
// what it says, and OUT never written.
struct RefusedImport {
  std::string arguments, expected;
};
inline void expect_imports_refused(const std::vector<RefusedImport>& cases, const std::string& out,
                                   const TempFolder& folder) {
  for (const RefusedImport& bad : cases) {
    const CommandResult result =
        run_program("tactile", "import " + bad.arguments + " --out " + out, folder);
    EXPECT_NE(result.exit_code, 0) << bad.arguments;
    EXPECT_NE(result.err.find(bad.expected), std::string::npos)
        << bad.arguments << ": " << result.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad.arguments;
  }
}

}  // namespace tactile::test

#pragma once
// A workbench test on the demo workspace (`tactile simulate --demo`) in a temporary folder of
// its own, with the headless workbench run on it by a script.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"

namespace tactile::test {

class DemoWorkspace : public ::testing::Test {
 protected:
  explicit DemoWorkspace(const std::string& prefix) : folder(prefix) {}
  void SetUp() override {
    const CommandResult made =
        run_program("tactile", "simulate --demo " + folder.file("demo"), folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
  }
  // A file of the demo workspace.
  std::string demo(const std::string& name) const { return folder.file("demo/" + name); }
  // The headless workbench on `open` (a file, a folder, or nothing and other options) at
  // `size`, as annotator ana, with settings of the test's own and the script `text` (its `@`
  // stand for the test's folder; none when empty).
  CommandResult workbench(const std::string& open, const std::string& text,
                          const std::string& size = "1280x720") const {
    std::string arguments =
        open + " --annotator ana --size " + size + " --settings " + folder.file("settings.json");
    if (!text.empty()) arguments += " --script " + write_script(folder, text);
    return run_program("tactile-workbench-headless", arguments, folder);
  }
  // A state JSON a script wrote (`state @NAME`).
  nlohmann::json state(const std::string& name) const {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  TempFolder folder;
};

}  // namespace tactile::test

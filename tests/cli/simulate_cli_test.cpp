// `tactile simulate` twice with one seed: the same bytes, recordings and label database.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_test_support.h"

namespace tactile {
namespace {

TEST(SimulateCommand, TheSameSeedWritesTheSameBytes) {
  test::TempFolder folder{"tactile-simulate-bytes"};
  for (const char* run : {"first", "second"}) {
    const auto result = test::run_program(
        "tactile", "simulate --skin fur --subjects 2 --trials 1 --seed 5 --out " + folder.file(run),
        folder);
    ASSERT_EQ(result.exit_code, 0) << result.err;
  }
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder.file("first"))) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(test::read_text(entry.path()), test::read_text(folder.file("second") + "/" + name))
        << name << " differs between two runs with the same seed";
    ++compared;
  }
  EXPECT_EQ(compared, 3);  // two recordings and labels.db
  const auto other = test::run_program(
      "tactile",
      "simulate --skin fur --subjects 2 --trials 1 --seed 6 --out " + folder.file("third"), folder);
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(test::read_text(folder.file("first") + "/fur-s01-t01.h5"),
            test::read_text(folder.file("third") + "/fur-s01-t01.h5"));
}

TEST(SimulateCommand, TheDemoEndsBySayingHowToOpenIt) {
  test::TempFolder folder{"tactile-simulate-demo"};
  const auto result =
      test::run_program("tactile", "simulate --demo " + folder.file("demo"), folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string last = "open it: tactile-workbench " + folder.file("demo") + "\n";
  ASSERT_GE(result.out.size(), last.size());
  EXPECT_EQ(result.out.substr(result.out.size() - last.size()), last) << result.out;
  // Only the demo, which is made to be looked at, says it.
  const auto skin = test::run_program(
      "tactile", "simulate --skin fur --subjects 1 --out " + folder.file("one"), folder);
  EXPECT_EQ(skin.out.find("open it"), std::string::npos) << skin.out;
}

// --faults lays sensor faults over each trial (docs/SIMULATION.md): other bytes than the clean
// trial, the same labels; an unknown fault is refused by name.
TEST(SimulateCommand, FaultsChangeTheSamplesAndNotTheLabels) {
  test::TempFolder folder{"tactile-simulate-faults"};
  const std::string common = "simulate --skin fur --subjects 1 --repetitions 1 --seed 3 --out ";
  ASSERT_EQ(test::run_program("tactile", common + folder.file("clean"), folder).exit_code, 0);
  const auto faulty = test::run_program(
      "tactile", common + folder.file("faulty") + " --faults realistic,stuck=1", folder);
  ASSERT_EQ(faulty.exit_code, 0) << faulty.err;
  EXPECT_NE(test::read_text(folder.file("clean") + "/fur-s01-t01.h5"),
            test::read_text(folder.file("faulty") + "/fur-s01-t01.h5"));
  EXPECT_EQ(test::read_text(folder.file("clean") + "/labels.db"),
            test::read_text(folder.file("faulty") + "/labels.db"));
  const auto refused =
      test::run_program("tactile", common + folder.file("refused") + " --faults wobble=1", folder);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("wobble"), std::string::npos) << refused.err;
}

}  // namespace
}  // namespace tactile

// The headless workbench as a user runs it: a recording imported from CSV, rendered to
// PNG at a chosen time, and the skin lit where the recording says it was touched.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>

#include "cli_test_support.h"
#include "png_test_support.h"

namespace tactile {
namespace {

class WorkbenchScreenshot : public ::testing::Test {
 protected:
  // grid:2x2, 4 s at 10 Hz; taxel ch3 is fully pressed from 1 s to 2 s, the rest idle.
  void SetUp() override {
    std::ofstream csv(folder.file("press.csv"));
    csv << "t,ch0,ch1,ch2,ch3\n";
    for (int k = 0; k < 40; ++k)
      csv << k / 10.0 << ",0,0.1,0.2," << (k >= 10 && k < 20 ? 1.0 : 0.0) << "\n";
    csv.close();
    const test::CommandResult imported =
        test::run_program("tactile",
                          "import " + folder.file("press.csv") + " --layout grid:2x2 --out " +
                              folder.file("press.h5"),
                          folder);
    ASSERT_EQ(imported.exit_code, 0) << imported.err;
  }

  test::TempFolder folder{"tactile-workbench-cli"};
};

TEST_F(WorkbenchScreenshot, PressedTaxelLightsUpOnlyWhileTouched) {
  const std::string during = folder.file("during.png");
  const std::string after = folder.file("after.png");
  const auto run_during = test::run_program(
      "tactile-workbench-headless",
      folder.file("press.h5") + " --time 1.5 --width 1000 --height 700 --screenshot " + during,
      folder);
  ASSERT_EQ(run_during.exit_code, 0) << run_during.err;
  const auto run_after = test::run_program(
      "tactile-workbench-headless",
      folder.file("press.h5") + " --time 3.0 --width 1000 --height 700 --screenshot " + after,
      folder);
  ASSERT_EQ(run_after.exit_code, 0) << run_after.err;

  const Png lit = read_png(during);
  const Png idle = read_png(after);
  ASSERT_EQ(lit.width, 1000);
  ASSERT_EQ(lit.height, 700);
  // The legend's top end is yellow in both; the pressed taxel adds a large yellow area.
  EXPECT_GT(count_viridis_top(lit), count_viridis_top(idle) + 2000);
}

TEST_F(WorkbenchScreenshot, MissingRecordingIsNamedAndFails) {
  const auto run =
      test::run_program("tactile-workbench-headless",
                        folder.file("absent.h5") + " --screenshot " + folder.file("x.png"), folder);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("absent.h5"), std::string::npos) << run.err;
}

TEST_F(WorkbenchScreenshot, BadOptionValueIsRefused) {
  const auto run = test::run_program(
      "tactile-workbench-headless",
      folder.file("press.h5") + " --width 5 --screenshot " + folder.file("x.png"), folder);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("--width"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace tactile

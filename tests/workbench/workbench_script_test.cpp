// The workbench driven by scripts (docs/SCRIPTING.md) through ImGui's real input path,
// headless under OSMesa: clicks on named targets, keys, playback, menus, views as PNG.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_test_support.h"
#include "png_test_support.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

class WorkbenchScript : public ::testing::Test {
 protected:
  // grid:2x2, 4 s at 10 Hz; ch3 pressed from 1 s to 2 s.
  void SetUp() override {
    std::ofstream csv(folder.file("press.csv"));
    csv << "t,ch0,ch1,ch2,ch3\n";
    for (int k = 0; k < 40; ++k)
      csv << k / 10.0 << ",0,0.1,0.2," << (k >= 10 && k < 20 ? 1.0 : 0.0) << "\n";
    csv.close();
    const auto imported = test::run_program(
        "tactile", "import " + folder.file("press.csv") + " --layout grid:2x2 --out " + recording(),
        folder);
    ASSERT_EQ(imported.exit_code, 0) << imported.err;
  }
  std::string recording() const { return folder.file("press.h5"); }
  // Writes a script; "@" stands for this test's folder.
  std::string script(const std::string& text) {
    return test::write_script(folder, text, "script.txt");
  }
  test::CommandResult run(const std::string& arguments) {
    return test::run_program("tactile-workbench-headless",
                             arguments + " --settings " + folder.file("settings.json"), folder);
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  test::TempFolder folder{"tactile-workbench-script"};
};

TEST_F(WorkbenchScript, ClickingATaxelSelectsItAndTakesItsChannelOutOfThePlot) {
  const auto result =
      run(recording() + " --size 1000x700 --script " +
          script("wait 2\nclick taxel 3\nstate @one.json\nclick taxel 0\nkey Shift+A\n"
                 "state @two.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json one = state("one.json");
  EXPECT_EQ(one["selection"]["taxels"], nlohmann::json::array({3}));
  const auto plotted = one["plotted"].get<std::vector<std::string>>();
  EXPECT_EQ(std::count(plotted.begin(), plotted.end(), "ch3"), 0) << one["plotted"];
  EXPECT_EQ(std::count(plotted.begin(), plotted.end(), "ch0"), 1) << one["plotted"];
  EXPECT_EQ(state("two.json")["selection"]["taxels"], nlohmann::json::array({0}));
}

TEST_F(WorkbenchScript, ClickingATimeMovesTheCursorThereAndPlaybackAdvancesIt) {
  const auto result =
      run(recording() + " --size 1000x700 --script " +
          script("wait 2\nclick time 1.25\nstate @clicked.json\nclick time 0.5 in timeline\n"
                 "state @lane.json\nplay 1.5\nstate @played.json\nkey Space\nwait 3\n"
                 "state @toggled.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json clicked = state("clicked.json");
  const double pixel = 4.0 / clicked["views"]["signals"]["width"].get<double>();
  EXPECT_NEAR(clicked["time"].get<double>(), 1.25, 2 * pixel);
  EXPECT_NEAR(state("lane.json")["time"].get<double>(), 0.5, 2 * pixel);
  const nlohmann::json played = state("played.json");
  EXPECT_NEAR(played["time"].get<double>(), 2.0, 2 * pixel);
  EXPECT_FALSE(played["playing"].get<bool>());
  EXPECT_TRUE(state("toggled.json")["playing"].get<bool>());  // space plays
}

TEST_F(WorkbenchScript, MenusAreChosenByName) {
  const auto result =
      run(recording() + " --script " +
          script("wait 2\nmenu View/Stacked lanes\nstate @stacked.json\n"
                 "menu File/Export view as PNG/Skin\nwait jobs\nstate @exported.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(state("stacked.json")["plot"]["stacked"].get<bool>());
  const nlohmann::json exported = state("exported.json");
  const std::string notice = exported["notice"];
  ASSERT_EQ(notice.rfind("wrote ", 0), 0u) << exported.dump(2);
  const Png png = read_png(notice.substr(6));
  ASSERT_TRUE(png.pixels) << notice;
  EXPECT_NEAR(png.width, exported["views"]["skin"]["width"].get<double>(), 1.0);
  EXPECT_NEAR(png.height, exported["views"]["skin"]["height"].get<double>(), 1.0);
}

TEST_F(WorkbenchScript, EveryViewRendersAloneToAPngOfTheAskedSize) {
  for (const char* view : {"workspace", "info", "skin", "signals", "timeline"}) {
    const std::string png_path = folder.file(std::string(view) + ".png");
    const auto result = run(recording() + " --time 1.5 --view " + view +
                            " --size 640x360 --screenshot " + png_path);
    ASSERT_EQ(result.exit_code, 0) << view << ": " << result.err;
    const Png png = read_png(png_path);
    ASSERT_TRUE(png.pixels) << view;
    EXPECT_EQ(png.width, 640);
    EXPECT_EQ(png.height, 360);
    // A blank view is one or two colours (background, frame); text is anti-aliased.
    EXPECT_GT(colours_in(png), 4u) << view << " looks empty";
    if (std::string(view) == "signals") {
      EXPECT_GT(colours_in(png), 20u) << "no signal drawn";
    }
    if (std::string(view) == "skin") {
      EXPECT_GT(count_viridis_top(png), 500);  // ch3 pressed
    }
  }
  const auto wrong = run(recording() + " --view nowhere --screenshot " + folder.file("x.png"));
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.err.find("nowhere"), std::string::npos) << wrong.err;
}

TEST_F(WorkbenchScript, ADraggedMarkSnapsToTheSignalsOnset) {
  // ch3 is pressed from 1 s: a mark released at 1.03 s lands on the onset.
  const auto result = run(recording() + " --size 1000x700 --script " +
                          script("wait 2\ndrag time 0.5 1.03 in timeline\nstate @onset.json\n"
                                 "key S\ndrag time 0.5 1.03 in timeline\nstate @free.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NEAR(state("onset.json")["marks"]["end"].get<double>(), 1.0, 0.01);
  EXPECT_NEAR(state("free.json")["marks"]["end"].get<double>(), 1.03, 0.01);  // S: no snapping
}

TEST_F(WorkbenchScript, AScriptErrorNamesItsLineAndFails) {
  auto result = run(recording() + " --script " + script("wait 1\njump 3\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("script.txt:2"), std::string::npos) << result.err;
  result = run(recording() + " --script " + script("wait 1\n\nclick taxel 99\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("script.txt:3: no taxel 99"), std::string::npos) << result.err;
  result = run(recording() + " --script " + script("key Hyper+Q\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("Hyper"), std::string::npos) << result.err;
  // Found by the fuzzer (tests/fuzz/regressions/script): a long F-key number overflowed
  // std::stoi and ended the program instead of naming the line.
  result = run(recording() + " --script " + script("wait 1\nkey F1111111111111111111\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("script.txt:2: key F1111111111111111111: F1 to F12 only"),
            std::string::npos)
      << result.err;
  // `wait 0.5` drew no frame, so the next click found no taxel drawn yet and blamed the
  // taxel; a wait is counted in frames and says so.
  result = run(recording() + " --script " + script("wait 0.5\nclick taxel 1\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("script.txt:1: wait: 0.5 is not a whole number of frames"),
            std::string::npos)
      << result.err;
}

// A long recording opens on its first minute (an hour opens as fast as a minute), or on the
// minute of its first label; View > Fit time axis shows the whole; a short one opens whole.
TEST_F(WorkbenchScript, ALongRecordingOpensOnAMinuteWithItsFirstLabelAndFitShowsTheWhole) {
  {
    std::ofstream csv(folder.file("long.csv"));
    csv << "t,ch0,ch1,ch2,ch3\n";
    for (int k = 0; k < 3000; ++k)  // 300 s at 10 Hz, ch3 pressed from 200 s to 202 s
      csv << k / 10.0 << ",0,0.1,0.2," << (k >= 2000 && k < 2020 ? 1.0 : 0.0) << "\n";
  }
  const std::string long_recording = folder.file("long.h5");
  ASSERT_EQ(test::run_program(
                "tactile",
                "import " + folder.file("long.csv") + " --layout grid:2x2 --out " + long_recording,
                folder)
                .exit_code,
            0);
  auto result = run(long_recording + " --script " +
                    script("wait 2\nstate @open.json\nmenu View/Fit time axis\nstate @fit.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_DOUBLE_EQ(state("open.json")["plot"]["t0"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(state("open.json")["plot"]["t1"].get<double>(), 60.0);
  EXPECT_NEAR(state("fit.json")["plot"]["t1"].get<double>(), 300.0, 1e-9);
  {
    LabelStore store(folder.file("labels.db"));
    Label press;
    press.recording = "long";
    press.t0 = 200.0;
    press.t1 = 202.0;
    press.class_name = "press";
    press.annotator = "test";
    store.add(press);
  }
  // Opened again: the minute that holds the first label, the cursor inside it.
  result = run(long_recording + " --script " + script("wait 2\nstate @again.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json again = state("again.json");
  const double t0 = again["plot"]["t0"].get<double>(), t1 = again["plot"]["t1"].get<double>();
  EXPECT_NEAR(t1 - t0, 60.0, 1e-9);
  EXPECT_LT(t0, 200.0);
  EXPECT_GT(t1, 202.0);
  EXPECT_EQ(again["labels"].get<int>(), 1);
  EXPECT_GE(again["time"].get<double>(), 200.0);
  EXPECT_LE(again["time"].get<double>(), 202.0);
  // The four seconds of press.h5 open whole.
  result = run(recording() + " --script " + script("wait 2\nstate @short.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NEAR(state("short.json")["plot"]["t1"].get<double>(), 4.0, 1e-9);
}

TEST_F(WorkbenchScript, ArgumentsThatFitNoFormOfTheCommandNameTheFormsItHas) {
  const std::pair<std::string, std::string> cases[] = {
      {"wait 1\nclick taxel\n",
       "script.txt:2: click taxel: wrong number of arguments, expected 'click taxel ID'"},
      {"drag foo 1 2\n",
       "script.txt:1: drag: expected 'drag time T0 T1 [in VIEW]', 'drag taxel A B' or 'drag item "
       "NAME X0 Y0 X1 Y1'"},
      {"wait 1 2\n",
       "script.txt:1: wait: wrong number of arguments, expected 'wait N', 'wait training', "
       "'wait jobs', 'wait video', 'wait labels N' or 'wait results N'"}};
  for (const auto& [text, error] : cases) {
    const auto result = run("--script " + script(text));
    EXPECT_NE(result.exit_code, 0) << text;
    EXPECT_NE(result.err.find(error), std::string::npos) << result.err;
  }
}

// docs/SCRIPTING.md's table of commands: each row's usage and its description.
std::map<std::string, std::string> documented_script_commands() {
  std::ifstream in(test::test_data_dir() + "/../../docs/SCRIPTING.md");
  std::map<std::string, std::string> commands;
  bool in_section = false;
  for (std::string line; std::getline(in, line);) {
    if (line.starts_with("## ")) in_section = line == "## Commands";
    const size_t end = line.find("` | ");
    if (!in_section || !line.starts_with("| `") || end == std::string::npos) continue;
    commands[line.substr(3, end - 3)] = line.substr(end + 4, line.rfind(" |") - end - 4);
  }
  return commands;
}

TEST_F(WorkbenchScript, AnUnknownCommandListsEveryDocumentedCommandAndNoOther) {
  const auto result = run("--script " + script("wait 1\njump 3\n"));
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("script.txt:2: unknown command 'jump'"), std::string::npos)
      << result.err;
  // One line a command: "  USAGE   HELP", the usages in a column.
  std::map<std::string, std::string> listed;
  std::istringstream lines(result.err);
  for (std::string line; std::getline(lines, line);) {
    const size_t gap = line.find("  ", 2);
    if (!line.starts_with("  ") || gap == std::string::npos) continue;
    listed[line.substr(2, gap - 2)] = line.substr(line.find_first_not_of(' ', gap));
  }
  const auto documented = documented_script_commands();
  ASSERT_GE(documented.size(), 12u) << "no table of commands in docs/SCRIPTING.md";
  for (const auto& [usage, help] : listed) {
    const auto row = documented.find(usage);
    if (row == documented.end()) {
      ADD_FAILURE() << "'" << usage << "' is a command but not in docs/SCRIPTING.md";
      continue;
    }
    EXPECT_TRUE(row->second.starts_with(help))
        << usage << ": the help '" << help << "' does not begin the documentation's '"
        << row->second << "'";
  }
  for (const auto& [usage, description] : documented)
    EXPECT_TRUE(listed.contains(usage)) << "'" << usage << "' is documented but not a command:\n"
                                        << result.err;
}

TEST_F(WorkbenchScript, ARelativePathListsItsFolderAsTheWorkspace) {
  const std::string command =
      "cd '" + folder.path().string() + "' && " + tactile::test::bin_dir() +
      "/tactile-workbench-headless press.h5 --settings settings.json --script " +
      script("state @relative.json\n") + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const nlohmann::json relative = state("relative.json");
  EXPECT_EQ(relative["workspace_files"], nlohmann::json::array({"press.h5"}));
  EXPECT_EQ(relative["recording"], "press");
}

TEST_F(WorkbenchScript, PanelSizesPersistBetweenRuns) {
  std::ofstream(folder.file("settings.json"))
      << R"({"panels": {"sidebar_width": 333, "skin_fraction": 0.5, "timeline_height": 150}})";
  const auto result = run(recording() + " --script " + script("wait 1\nstate @sized.json\n"));
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json sized = state("sized.json");
  EXPECT_EQ(sized["panels"]["sidebar_width"].get<double>(), 333.0);
  EXPECT_NEAR(sized["views"]["timeline"]["height"].get<double>(), 150.0, 20.0);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// A workspace with damaged recordings: each is marked in the list with its reason,
// the workbench opens what it can and draws a damaged chunk as a gap, not numbers.
class WorkbenchDamage : public ::testing::Test {
 protected:
  void SetUp() override {
    // 30 s of noise on 4 channels: the compressed samples are most of each file.
    std::ofstream csv(folder.file("noise.csv"));
    csv << "t,ch0,ch1,ch2,ch3\n";
    uint32_t state = 12345;
    for (int k = 0; k < 3000; ++k) {
      csv << k / 100.0;
      for (int c = 0; c < 4; ++c) {
        state = state * 1664525u + 1013904223u;
        csv << "," << (state >> 8) % 10000 / 1000.0;
      }
      csv << "\n";
    }
    csv.close();
    std::filesystem::create_directories(folder.file("ws"));
    for (const char* name : {"a", "b", "c"}) {
      const auto imported = test::run_program(
          "tactile",
          "import " + folder.file("noise.csv") + " --layout grid:2x2 --recording-id " + name +
              " --out " + folder.file(std::string("ws/") + name + ".h5"),
          folder);
      ASSERT_EQ(imported.exit_code, 0) << imported.err;
    }
    flip(folder.file("ws/a.h5"), 20);  // the superblock: a.h5 does not open
    const std::string c = folder.file("ws/c.h5");
    flip(c, static_cast<std::streamoff>(std::filesystem::file_size(c) / 2));  // a sample chunk
  }
  static void flip(const std::string& path, std::streamoff offset) {
    std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
    file.seekg(offset);
    char byte = 0;
    file.get(byte);
    file.seekp(offset);
    file.put(static_cast<char>(byte ^ 0x04));
  }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  test::TempFolder folder{"tactile-workbench-damage"};
};

TEST_F(WorkbenchDamage, DamagedRecordingsAreMarkedWithTheirReasonAndTheRestOpens) {
  const std::string script = folder.file("script.txt");
  std::ofstream(script) << "wait 2\nstate " << folder.file("first.json")
                        << "\nclick recording a.h5\nwait 2\nstate " << folder.file("clicked_a.json")
                        << "\nclick recording c.h5\nwait 3\nstate " << folder.file("opened_c.json")
                        << "\nscreenshot " << folder.file("damaged.png") << "\n";
  const auto result = test::run_program("tactile-workbench-headless",
                                        folder.file("ws") + " --size 1000x700 --time 12 --script " +
                                            script + " --settings " + folder.file("settings.json"),
                                        folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // a.h5 is first but does not open: marked, and b.h5 opens instead.
  const nlohmann::json first = state("first.json");
  EXPECT_EQ(first["recording"], "b");
  ASSERT_TRUE(first["damaged"].contains("a.h5")) << first.dump(2);
  EXPECT_NE(first["damaged"]["a.h5"].get<std::string>().find("a.h5"), std::string::npos);
  // Clicking it keeps b open and says why.
  const nlohmann::json clicked = state("clicked_a.json");
  EXPECT_EQ(clicked["recording"], "b");
  EXPECT_NE(clicked["error"].get<std::string>().find("cannot open"), std::string::npos);
  // c.h5 opens (its metadata is intact); the damaged chunk is named, not shown as data.
  const nlohmann::json opened = state("opened_c.json");
  EXPECT_EQ(opened["recording"], "c");
  ASSERT_TRUE(opened["damaged"].contains("c.h5")) << opened.dump(2);
  const std::string reason = opened["damaged"]["c.h5"];
  EXPECT_NE(reason.find(":/streams/"), std::string::npos) << reason;
  EXPECT_NE(reason.find("checksum"), std::string::npos) << reason;
}

}  // namespace
}  // namespace tactile

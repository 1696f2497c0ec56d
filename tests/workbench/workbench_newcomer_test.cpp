// What a newcomer tripped on (issue 41), each driven through ImGui's real input path headless
// in the default 1280 x 720 window on the demo workspace: a row of the label table answers a
// click, a menu item is reached with its menu closed, the sheet of keys says which segmenter G
// runs, Robovie's parts are named once between its figures, the analysis views, the lanes'
// names and the live bar fit the window, no tooltip stays over what a click opened, an undo
// says what it takes back and goes to it, Ctrl+Z cancels a segmenter run still going, the
// somatosensory map fills its panel in colours apart, a touch on TSA's tiny pads shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"
#include "demo_workspace.h"
#include "png_test_support.h"
#include "test_paths.h"

namespace tactile {
namespace {

class Newcomer : public test::DemoWorkspace {
 protected:
  Newcomer() : DemoWorkspace("tactile-newcomer") {}
  // The recording's labels as `tactile labels list --json` gives them.
  nlohmann::json labels(const std::string& recording, const std::string& source = "") {
    const auto listed =
        test::run_program("tactile",
                          "labels list " + demo("labels.db") + " --recording " + recording +
                              (source.empty() ? "" : " --source " + source) + " --json",
                          folder);
    EXPECT_EQ(listed.exit_code, 0) << listed.err;
    return nlohmann::json::parse(listed.out)["labels"];
  }
};

TEST_F(Newcomer, AClickOnARowOfTheLabelTableSelectsItsLabelAndGoesToIt) {
  const nlohmann::json listed = labels("tsa-s01-t01");
  ASSERT_GE(listed.size(), 4u);
  // A row below the first, whose label starts away from where the recording opens.
  const nlohmann::json& wanted = listed[3];
  const std::string id = wanted["id"].dump();
  const auto result = workbench(
      demo("tsa-s01-t01.h5"), "wait 2\nclick item label-row:" + id + "\nwait 1\nstate @row.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json row = state("row.json");
  EXPECT_EQ(row["selection"]["labels"], nlohmann::json::array({wanted["id"]}));
  EXPECT_NEAR(row["time"].get<double>(), wanted["t0"].get<double>(), 1e-6);
}

TEST_F(Newcomer, AMenuItemIsClickedByNameWithItsMenuClosed) {
  const auto result =
      workbench(demo("fur-s01-t01.h5"),
                "click item menu:Help/Keys\nwait 1\nstate @keys.json\nkey Escape\nwait 1\n"
                "click item menu:Labels/Run segmenter/threshold\nwait jobs\nwait 1\n"
                "state @segmented.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(state("keys.json")["help"]["keys"].get<bool>());
  const nlohmann::json segmented = state("segmented.json");
  EXPECT_EQ(segmented["segmenter"]["method"], "threshold");
  ASSERT_FALSE(segmented["jobs"].empty());
  EXPECT_EQ(segmented["jobs"].back()["name"], "segmenter threshold");
  EXPECT_EQ(segmented["jobs"].back()["status"], "done");
}

// docs/SCRIPTING.md's sentence on G.
std::string documented_g() {
  std::ifstream in(test::test_data_dir() + "/../../docs/SCRIPTING.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("`G` runs");
  if (at == std::string::npos) return "";
  return text.substr(at, text.find(';', text.find(')', at)) - at);
}

TEST_F(Newcomer, TheSheetOfKeysAndTheDocumentationSayWhichSegmenterGRuns) {
  // TSA's own segmenter is frame-edge: G runs it on opening, the sheet says so, and so does
  // docs/SCRIPTING.md (which once said adaptive).
  const auto result = workbench(demo("tsa-s01-t01.h5"),
                                "wait 2\nkey F1\nwait 1\nstate @sheet.json\nkey Escape\nwait 1\n"
                                "key G\nwait jobs\nwait 1\nstate @ran.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string sheet = state("sheet.json")["help"]["sheet"]["G"];
  EXPECT_NE(sheet.find("the skin's own"), std::string::npos) << sheet;
  EXPECT_NE(sheet.find("now: frame-edge"), std::string::npos) << sheet;
  const nlohmann::json ran = state("ran.json");
  ASSERT_FALSE(ran["jobs"].empty());
  EXPECT_EQ(ran["jobs"].back()["name"], "segmenter frame-edge");
  const std::string documented = documented_g();
  EXPECT_NE(documented.find("skin's own"), std::string::npos) << documented;
  EXPECT_EQ(documented.find("`adaptive` at first"), std::string::npos) << documented;
}

TEST_F(Newcomer, RobovieNamesAPartBetweenItsTwoFiguresOnce) {
  const auto result = workbench(demo("robovie-s01-t01.h5") + " --time 12",
                                "wait 2\nwait jobs\nwait 1\nstate @robovie.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json names = state("robovie.json")["skin"]["names"];
  ASSERT_GE(names.size(), 10u);
  // Two boxes of the same name on one line, less than a name's width apart, read "left hand
  // left hand"; the front's and the back's patch share one name there (the same box).
  int shared = 0;
  for (size_t a = 0; a < names.size(); ++a)
    for (size_t b = a + 1; b < names.size(); ++b) {
      const nlohmann::json &first = names[a], &second = names[b];
      if (first["id"] != second["id"]) continue;
      const double ax = first["x"], ay = first["y"], aw = first["width"], ah = first["height"];
      const double bx = second["x"], by = second["y"], bw = second["width"], bh = second["height"];
      if (ax == bx && ay == by) {
        ++shared;
        continue;
      }
      const bool one_line = ay < by + bh && by < ay + ah;
      const double gap = std::max(bx - (ax + aw), ax - (bx + bw));
      EXPECT_FALSE(one_line && gap < aw) << first.dump() << " beside " << second.dump();
    }
  EXPECT_GE(shared, 1) << names.dump();
}

// Whether the box `name` of the state's `boxes` lies inside `outer` (a view, a cell), to a pixel.
::testing::AssertionResult inside(const nlohmann::json& at, const std::string& name,
                                  const nlohmann::json& outer) {
  if (!at["boxes"].contains(name)) return ::testing::AssertionFailure() << "no box " << name;
  const nlohmann::json& box = at["boxes"][name];
  const double x = box["x"], y = box["y"], w = box["width"], h = box["height"];
  const double ox = outer["x"], oy = outer["y"], ow = outer["width"], oh = outer["height"];
  if (x >= ox - 1 && y >= oy - 1 && x + w <= ox + ow + 1 && y + h <= oy + oh + 1)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << name << " " << box.dump() << " runs out of " << outer.dump();
}

TEST_F(Newcomer, TheAnalysisViewsAndLaneNamesFitTheDefaultWindowAndNoTooltipStaysAfterAClick) {
  const auto result = workbench(
      demo("nao-s01-t01.h5"),
      "wait 2\nkey G\nwait jobs\nclick item tab:model\nwait 2\nclick item button:Train all\n"
      "wait training\nwait 3\nstate @confusion.json\nclick item tab:model\nwait 3\n"
      "state @model.json\nclick item tab:som\nwait jobs\nwait 2\nstate @som.json\n"
      "click item tab:scatter\nwait jobs\nwait 3\nstate @scatter.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // Train all opens the confusion matrix under the resting mouse: no tooltip over it.
  const nlohmann::json confusion = state("confusion.json");
  for (const nlohmann::json& item : confusion["items"]) EXPECT_NE(item, "tooltip");
  // With the plot's tab hidden, each lane's name fits its header ("proximit" did not).
  size_t lanes = 0;
  for (const nlohmann::json& lane : confusion["lanes"]) {
    const std::string id = lane["id"];
    ++lanes;
    EXPECT_TRUE(inside(confusion, "lane-name:" + id, confusion["boxes"]["lane-header:" + id]));
  }
  EXPECT_GE(lanes, 2u);
  // The results table's classifier names fit their column.
  const nlohmann::json model = state("model.json");
  size_t names = 0;
  for (const auto& [name, box] : model["boxes"].items()) {
    if (!name.starts_with("result-name:")) continue;
    ++names;
    EXPECT_TRUE(inside(model, name, model["boxes"]["result-cell:" + name.substr(12)]));
  }
  EXPECT_GE(names, 10u);
  // The SOM's U-matrix box, the scatter's header and every row of its legend lie in their views.
  const nlohmann::json som = state("som.json");
  EXPECT_TRUE(inside(som, "U-matrix", som["views"]["som"]));
  const nlohmann::json scatter = state("scatter.json");
  EXPECT_TRUE(inside(scatter, "text:scatter-header", scatter["views"]["scatter"]));
  size_t rows = 0;
  for (const auto& [name, box] : scatter["boxes"].items())
    if (name.starts_with("legend-row:scatter:")) {
      ++rows;
      EXPECT_TRUE(inside(scatter, name, scatter["views"]["scatter"]));
    }
  EXPECT_GE(rows, 5u);
}

TEST_F(Newcomer, TheLiveBarsClassifyButtonFitsTheDefaultWindow) {
  const auto result =
      test::run_program("tactile-workbench-headless",
                        "--connect udp://127.0.0.1:0 --skin fur --size 1280x720 --settings " +
                            folder.file("settings.json") + " --script " +
                            test::write_script(folder, "wait 3\nstate @live.json\n"),
                        folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json live = state("live.json");
  for (const char* item :
       {"button:classify", "input:model", "checkbox:auto-record", "button:record"})
    EXPECT_TRUE(inside(live, item, live["views"]["timeline"]));
}

TEST_F(Newcomer, TheFirstUndoOfASessionSaysItTakesBackTheLastSessionsSegmenterRun) {
  ASSERT_EQ(workbench(demo("fur-s01-t01.h5"), "wait 2\nkey G\nwait jobs\nwait 1\n").exit_code, 0);
  const nlohmann::json suggestions = labels("fur-s01-t01", "segmenter");
  ASSERT_FALSE(suggestions.empty());
  double first = 1e9;
  for (const nlohmann::json& label : suggestions)
    first = std::min(first, label["t0"].get<double>());
  const auto result = workbench(demo("fur-s01-t01.h5"),
                                "wait 2\ntime 50\nkey Ctrl+Z\nwait 1\nstate @undone.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json undone = state("undone.json");
  const std::string notice = undone["notice"];
  EXPECT_NE(notice.find("threshold's segmenter run, which added " +
                        std::to_string(suggestions.size()) + " suggestions"),
            std::string::npos)
      << notice;
  EXPECT_NE(notice.find("earlier session"), std::string::npos) << notice;
  EXPECT_TRUE(labels("fur-s01-t01", "segmenter").empty());
  // The cursor went to what the undo changed.
  EXPECT_NEAR(undone["time"].get<double>(), first, 1e-6);
}

TEST_F(Newcomer, EveryUndoAndRedoMovesTheCursorToTheLabelItChanged) {
  const auto result =
      workbench(demo("fur-s01-t01.h5"),
                "wait 2\ntime 40\nkey [\ntime 42\nkey ]\nkey 1\nkey Enter\nwait 1\ntime 3\n"
                "key Ctrl+Z\nwait 1\nstate @undone.json\ntime 7\nkey Ctrl+Shift+Z\nwait 1\n"
                "state @redone.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json undone = state("undone.json"), redone = state("redone.json");
  EXPECT_NEAR(undone["time"].get<double>(), 40.0, 1e-6);
  EXPECT_NEAR(redone["time"].get<double>(), 40.0, 1e-6);
  for (const nlohmann::json* at : {&undone, &redone}) {
    EXPECT_LE((*at)["plot"]["t0"].get<double>(), 40.0);
    EXPECT_GE((*at)["plot"]["t1"].get<double>(), 42.0);
  }
  const std::string notice = undone["notice"];
  EXPECT_EQ(notice, "undone: an edit of ana, which added 1 label");
  EXPECT_EQ(redone["notice"], "redone: an edit of ana, which added 1 label");
}

TEST_F(Newcomer, CtrlZWhileASegmenterRunsCancelsTheRunNotTheLabelBefore) {
  // Robovie's 274 channels: the run takes long enough to be running when Ctrl+Z comes; if
  // it stored its suggestions just then, they are undone all the same.
  const auto result = workbench(demo("robovie-s01-t01.h5"),
                                "wait 2\ntime 40\nkey [\ntime 42\nkey ]\nkey 1\nkey Enter\n"
                                "wait 1\nkey G\nkey Ctrl+Z\nstate @pressed.json\nwait jobs\n"
                                "wait 2\nstate @after.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string notice = state("pressed.json")["notice"];
  EXPECT_NE(notice.find("cancelled (Ctrl+Z)"), std::string::npos) << notice;
  EXPECT_EQ(labels("robovie-s01-t01", "manual").size(), 1u);
  EXPECT_TRUE(labels("robovie-s01-t01", "segmenter").empty());
  const nlohmann::json jobs = state("after.json")["jobs"];
  ASSERT_FALSE(jobs.empty());
  EXPECT_EQ(jobs.back()["name"], "segmenter adaptive");
  EXPECT_NE(jobs.back()["status"], "running");
}

TEST_F(Newcomer, TheSomatosensoryMapFillsItsPanelWithDotsInColoursApart) {
  const auto result = workbench(demo("robovie-s01-t01.h5") + " --time 12",
                                "wait 2\nclick item map\nwait 1\nclick item map:somatosensory\n"
                                "wait jobs\nwait 2\nstate @map.json\nscreenshot @map.png\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json drawn = state("map.json");
  const Png png = read_png(folder.file("map.png"));
  ASSERT_TRUE(png.pixels);
  const nlohmann::json& view = drawn["views"]["skin"];
  const double view_x = view["x"], view_width = view["width"];
  // The dots: 274, each wide enough to show its colour, spread over the panel's middle rather
  // than its left 60 % (a legend of 21 regions beside them took the rest).
  double left = 1e9, right = -1e9;
  std::vector<double> widths;
  for (const auto& [id, box] : drawn["skin"]["taxels"].items()) {
    left = std::min(left, box["x"].get<double>());
    right = std::max(right, box["x"].get<double>() + box["width"].get<double>());
    widths.push_back(box["width"].get<double>());
  }
  ASSERT_EQ(widths.size(), 274u);
  // The view says how far the map keeps the body: the state's figures, which the caption shows.
  const nlohmann::json& agreement = drawn["analysis"]["somatosensory_agreement"];
  ASSERT_FALSE(agreement.is_null());
  EXPECT_EQ(agreement["neighbours"], 5);
  EXPECT_GT(agreement["same_part_share"].get<double>(), agreement["chance_share"].get<double>());
  EXPECT_TRUE(drawn["items"].dump().find("somatosensory:agreement") != std::string::npos);
  // And per body part, the demo's films on every part of Robovie's body map.
  EXPECT_EQ(agreement["part_share"].size(), 21u) << agreement.dump();
  // The caption's tooltip lists the parts, best gathered first.
  const std::string tip = drawn["tips"].value("somatosensory:agreement", "");
  EXPECT_NE(tip.find("By body part: "), std::string::npos) << tip;
  EXPECT_NE(tip.find("head "), std::string::npos) << tip;
  std::nth_element(widths.begin(), widths.begin() + 137, widths.end());
  EXPECT_GE(widths[137], 7.0);
  EXPECT_NEAR(0.5 * (left + right), view_x + 0.5 * view_width, 0.1 * view_width)
      << left << " to " << right << " in " << view.dump();
  // The regions' colours as drawn in the legend: no two within 50 of each other in RGB (the
  // class palette's came within 32).
  const nlohmann::json& legend = drawn["legends"]["somatosensory"];
  ASSERT_EQ(legend.size(), 21u);
  std::vector<std::array<int, 3>> colours;
  for (const auto& [name, swatch] : legend.items()) {
    const unsigned char* p = png.at(static_cast<int>(swatch["x"].get<double>() + 5),
                                    static_cast<int>(swatch["y"].get<double>() + 5));
    colours.push_back({p[0], p[1], p[2]});
    EXPECT_LE(swatch["x"].get<double>() + swatch["width"].get<double>(), view_x + view_width)
        << name;
    EXPECT_LE(swatch["y"].get<double>() + swatch["height"].get<double>(),
              view["y"].get<double>() + view["height"].get<double>())
        << name;
  }
  double closest = 1e9;
  for (size_t a = 0; a < colours.size(); ++a)
    for (size_t b = a + 1; b < colours.size(); ++b)
      closest =
          std::min(closest, std::hypot(colours[a][0] - colours[b][0], colours[a][1] - colours[b][1],
                                       colours[a][2] - colours[b][2]));
  EXPECT_GE(closest, 50.0);
}

TEST_F(Newcomer, ATouchOnTsaShowsAsABlotNotADotWhereTheRecordingOpens) {
  // TSA opens at its first labelled touch, one taxel on the back of the head: drawn enlarged
  // to 10 pixels it read as a dot among 4-pixel pads.
  const auto result =
      workbench(demo("tsa-s01-t01.h5"), "wait 2\nstate @tsa.json\nscreenshot @tsa.png\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json drawn = state("tsa.json");
  const Png png = read_png(folder.file("tsa.png"));
  ASSERT_TRUE(png.pixels);
  ASSERT_FALSE(drawn["skin"]["touched"].empty());
  int lit = 0;  // over half-way up viridis (green to yellow) inside the touched taxels' boxes
  for (const nlohmann::json& id : drawn["skin"]["touched"]) {
    const nlohmann::json& box = drawn["skin"]["taxels"][id.dump()];
    for (int y = static_cast<int>(box["y"].get<double>());
         y < static_cast<int>(box["y"].get<double>() + box["height"].get<double>()); ++y)
      for (int x = static_cast<int>(box["x"].get<double>());
           x < static_cast<int>(box["x"].get<double>() + box["width"].get<double>()); ++x) {
        const unsigned char* p = png.at(x, y);
        lit += p[1] > 140 && p[1] > p[2];
      }
  }
  EXPECT_GE(lit, 150) << drawn["skin"]["touched"].dump();
}

}  // namespace
}  // namespace tactile

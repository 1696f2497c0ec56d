// The first hour of a new user, driven through ImGui's real input path headless (scripts,
// docs/SCRIPTING.md) on the demo workspace: the empty window says what to do and makes the
// demo, F1 shows the sheet of keys, every class of a 15-class skin is reached by its key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_test_support.h"
#include "demo_workspace.h"
#include "test_paths.h"

namespace tactile {
namespace {

class FirstHour : public test::DemoWorkspace {
 protected:
  FirstHour() : DemoWorkspace("tactile-first-hour") {}
  static bool has_item(const nlohmann::json& state, const std::string& name) {
    for (const nlohmann::json& item : state["items"])
      if (item == name) return true;
    return false;
  }
};

TEST_F(FirstHour, AnEmptyWindowSaysWhatToDoAndMakesTheDemoWorkspace) {
  const auto result =
      workbench("",
                "wait 2\nstate @empty.json\nclick item input:demo-folder\n"
                "key Ctrl+A\ntype @made-here\nclick item button:Make the demo workspace\n"
                "wait jobs\nwait 2\nstate @made.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json empty = state("empty.json");
  EXPECT_TRUE(empty["recording"].is_null());
  for (const char* item :
       {"button:Open a recording", "button:Make the demo workspace", "menu:Help"})
    EXPECT_TRUE(has_item(empty, item)) << item;
  const nlohmann::json made = state("made.json");
  EXPECT_EQ(made["error"], "");
  EXPECT_EQ(made["workspace"], folder.file("made-here"));
  EXPECT_GE(made["workspace_files"].size(), 5u);
  EXPECT_FALSE(made["recording"].is_null());
  EXPECT_TRUE(std::filesystem::exists(folder.file("made-here/labels.db")));
}

TEST_F(FirstHour, F1AndTheHelpMenuShowTheSheetOfKeysAndEscapeClosesIt) {
  const auto result =
      workbench(demo("fur-s01-t01.h5"),
                "wait 2\nkey F1\nwait 1\nstate @f1.json\nscreenshot @keys.png\n"
                "key Escape\nwait 1\nstate @closed.json\n"
                "click item menu:Help\nclick item menu:Help/Keys\nwait 1\nstate @menu.json\n"
                "key F1\nwait 1\nclick item menu:Help\nclick item menu:Help/Getting started\n"
                "wait 1\nstate @started.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json f1 = state("f1.json");
  EXPECT_TRUE(f1["help"]["keys"].get<bool>());
  EXPECT_TRUE(has_item(f1, "window:keys"));
  EXPECT_FALSE(state("closed.json")["help"]["keys"].get<bool>());
  EXPECT_FALSE(has_item(state("closed.json"), "window:keys"));
  EXPECT_TRUE(state("menu.json")["help"]["keys"].get<bool>());
  const nlohmann::json started = state("started.json");
  EXPECT_FALSE(started["help"]["keys"].get<bool>());
  EXPECT_TRUE(started["help"]["getting_started"].get<bool>());
  EXPECT_TRUE(has_item(started, "window:getting-started"));
}

// Every control drawn (buttons, fields, check boxes, combos, sliders) shows a tooltip: held to
// it on the welcome panel, the main window, the Model tab, an open menu and the file dialogs.
TEST_F(FirstHour, EveryControlHasATooltip) {
  ASSERT_EQ(workbench("", "wait 2\nstate @welcome.json\n").exit_code, 0);
  const auto result =
      workbench(demo("fur-s01-t01.h5"),
                "wait 2\nstate @main.json\nclick item tab:model\nwait 2\nstate @model.json\n"
                "click item menu:Labels\nclick item menu:Labels/Run segmenter\nwait 1\n"
                "state @menu.json\nkey Escape\nwait 1\n"
                "click item menu:File\nclick item menu:File/Import...\nwait 2\n"
                "state @import.json\nkey Escape\nwait 1\n"
                "click item menu:File\nclick item menu:File/Export features...\nwait 2\n"
                "state @features.json\nkey Escape\nwait 1\n"
                "click item menu:Labels\nclick item menu:Labels/Agreement report...\nwait 2\n"
                "state @agreement.json\nkey Escape\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  size_t controls = 0;
  for (const char* name : {"welcome.json", "main.json", "model.json", "menu.json", "import.json",
                           "features.json", "agreement.json"}) {
    const nlohmann::json at = state(name);
    for (const nlohmann::json& item : at["items"]) {
      const std::string id = item.get<std::string>();
      const bool control = id.starts_with("button:") || id.starts_with("input:") ||
                           id.starts_with("checkbox:") || id.starts_with("combo:") ||
                           id.starts_with("slider:");
      if (!control) continue;
      ++controls;
      EXPECT_TRUE(at["tips"].contains(id) && !at["tips"][id].get<std::string>().empty())
          << id << " in " << name << " has no tooltip";
    }
  }
  EXPECT_GE(controls, 30u);
}

TEST_F(FirstHour, AScriptsFirstClickOnAMenuWaitsForTheFirstFrame) {
  const auto result =
      workbench(demo("fur-s01-t01.h5"), "click item menu:File\nwait 1\nstate @menu.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(has_item(state("menu.json"), "menu:File/Open..."));
}

TEST_F(FirstHour, TheLabelTableShowsManyRowsAndFollowsTheSelection) {
  // In a short window only part of Robovie's 15 labels fit; selecting the last one in its lane
  // (the whole trial shown: it opens on its first minute) scrolls its row into view.
  const auto result = workbench(demo("robovie-s01-t01.h5"),
                                "wait 2\nmenu View/Fit time axis\nstate @before.json\nclick time "
                                "135 in lane:ground-truth\nwait 2\n"
                                "state @after.json\n",
                                "1280x480");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto rows = [](const nlohmann::json& at) {
    std::set<std::string> shown;
    for (const nlohmann::json& item : at["items"])
      if (item.get<std::string>().starts_with("label-row:")) shown.insert(item.get<std::string>());
    return shown;
  };
  const nlohmann::json after = state("after.json");
  ASSERT_EQ(after["selection"]["labels"].size(), 1u);
  const std::string selected = "label-row:" + after["selection"]["labels"][0].dump();
  EXPECT_FALSE(rows(state("before.json")).count(selected))
      << "the last label was in view from the start";
  EXPECT_TRUE(rows(after).count(selected)) << "the selected label's row was not scrolled into view";
  EXPECT_GE(rows(after).size(), 5u);
}

TEST_F(FirstHour, EachOfFifteenClassesIsLabelledByItsOwnKey) {
  // Robovie's vocabulary has 15 classes: 1-9, 0, then Shift+1 ... Shift+5.
  const auto listed =
      test::run_program("tactile", "labels classes " + demo("labels.db") + " robovie", folder);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  std::vector<std::string> vocabulary;
  std::istringstream lines(listed.out);
  for (std::string line; std::getline(lines, line);) vocabulary.push_back(line);
  ASSERT_EQ(vocabulary.size(), 15u);
  std::string script = "wait 2\n";
  for (int k = 1; k <= 15; ++k) {
    const std::string key = k <= 10 ? std::to_string(k % 10) : "Shift+" + std::to_string(k - 10);
    script += "time " + std::to_string(2 * k) + "\nkey [\ntime " + std::to_string(2 * k + 1) +
              "\nkey ]\nkey " + key + "\nkey Enter\nwait 1\n";
  }
  script += "state @labelled.json\n";
  const auto result = workbench(demo("robovie-s01-t01.h5"), script);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(state("labelled.json")["error"], "");
  // Every class's swatch is in the legend, none cut off.
  const nlohmann::json legend = state("labelled.json")["legends"]["lanes"];
  EXPECT_EQ(legend.size(), 15u);
  const auto manual = test::run_program(
      "tactile", "labels list " + demo("labels.db") + " --source manual --json", folder);
  ASSERT_EQ(manual.exit_code, 0) << manual.err;
  const nlohmann::json labels = nlohmann::json::parse(manual.out)["labels"];
  ASSERT_EQ(labels.size(), 15u);
  for (const nlohmann::json& label : labels) {
    const int k = static_cast<int>(std::lround(label["t0"].get<double>() / 2.0));
    ASSERT_GE(k, 1);
    ASSERT_LE(k, 15);
    EXPECT_EQ(label["class"], vocabulary[static_cast<size_t>(k - 1)]) << "key of class " << k;
  }
}

TEST_F(FirstHour, TrainAllThenPredictUsesTheRowShownAndUGoesToTheSmallestMargin) {
  const auto result = workbench(
      demo("fur-s01-t01.h5"),
      "wait 2\nclick item tab:model\nwait 2\nclick item button:Train all\nwait training\nwait 3\n"
      "state @trained.json\nclick item tab:model\nwait 2\nclick item button:Predict\nwait jobs\n"
      "wait 2\nstate @predicted.json\nkey U\nwait 2\nstate @least-sure.json\n");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json trained = state("trained.json")["analysis"];
  ASSERT_TRUE(trained["current"].is_string());
  // The classifier box names the row the table and the confusion show.
  EXPECT_EQ(trained["classifier_box"], trained["current"]);
  const nlohmann::json predicted = state("predicted.json");
  EXPECT_EQ(predicted["error"], "");
  EXPECT_NE(predicted["notice"].get<std::string>().find("predictions by"), std::string::npos)
      << predicted["notice"];
  EXPECT_NE(
      predicted["analysis"]["model"].get<std::string>().find(trained["current"].get<std::string>()),
      std::string::npos);
  const auto listed = test::run_program(
      "tactile", "labels list " + demo("labels.db") + " --source model --json", folder);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  const nlohmann::json predictions = nlohmann::json::parse(listed.out)["labels"];
  ASSERT_FALSE(predictions.empty());
  // U selects the prediction of the smallest margin (the note's "margin=M").
  const auto margin_of = [](const nlohmann::json& label) {
    const std::string note = label["note"];
    return std::stod(note.substr(note.find("margin=") + 7));
  };
  double smallest = 2.0;
  for (const nlohmann::json& label : predictions) smallest = std::min(smallest, margin_of(label));
  const nlohmann::json selected = state("least-sure.json")["selection"]["labels"];
  ASSERT_EQ(selected.size(), 1u);
  bool found = false;
  for (const nlohmann::json& label : predictions)
    if (label["id"] == selected[0]) {
      found = true;
      EXPECT_DOUBLE_EQ(margin_of(label), smallest);
    }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace tactile

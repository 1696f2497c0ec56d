// Every skin legible in the default 1280 x 720 window (issue 25): a touch on TSA's right thigh
// covers at least 50 lit pixels, the somatosensory map names its body regions in a legend and
// its caption fits, a strip of 64 fills its panel, Robovie names every body part. Read off
// the screenshots, at the places the state JSON says the view drew things.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli_test_support.h"
#include "demo_workspace.h"
#include "png_test_support.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {
namespace {

class WorkbenchSkins : public test::DemoWorkspace {
 protected:
  WorkbenchSkins() : DemoWorkspace("tactile-workbench-skins") {}
  // Runs the headless workbench at 1280 x 720 on `arguments` with a script that waits for
  // its jobs, then writes NAME.json and NAME.png.
  void snapshot(const std::string& arguments, const std::string& name,
                const std::string& before = "") {
    const std::string script = folder.file(name + ".txt");
    std::ofstream(script) << before << "wait 2\nwait jobs\nwait 2\nstate "
                          << folder.file(name + ".json") << "\nscreenshot "
                          << folder.file(name + ".png") << "\n";
    const auto run = test::run_program("tactile-workbench-headless",
                                       arguments + " --size 1280x720 --settings " +
                                           folder.file("settings.json") + " --script " + script,
                                       folder);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  // What snapshot NAME wrote of the state.
  nlohmann::json state(const std::string& name) const {
    return DemoWorkspace::state(name + ".json");
  }
  // How many times the skin view wrote the name of group (or taxel) `id`.
  static int times_named(const nlohmann::json& drawn, const std::string& id) {
    int times = 0;
    for (const nlohmann::json& name : drawn["skin"]["names"]) times += name["id"] == id;
    return times;
  }
};

// Pixels of the ellipse inscribed in a drawn box whose colour passes `lit`.
template <typename Lit>
int pixels_in_shape(const Png& png, const nlohmann::json& box, Lit lit) {
  const double x = box["x"].get<double>(), y = box["y"].get<double>();
  const double half_width = box["width"].get<double>() / 2,
               half_height = box["height"].get<double>() / 2;
  int count = 0;
  for (int row = static_cast<int>(y); row <= static_cast<int>(y + 2 * half_height); ++row)
    for (int column = static_cast<int>(x); column <= static_cast<int>(x + 2 * half_width);
         ++column) {
      const double u = (column + 0.5 - x - half_width) / half_width;
      const double v = (row + 0.5 - y - half_height) / half_height;
      if (u * u + v * v <= 1.0 && lit(png.at(column, row))) ++count;
    }
  return count;
}

TEST_F(WorkbenchSkins, ATouchOnTsasRightThighCoversFiftyLitPixelsInTheDefaultWindow) {
  // The first touch on the right thigh, by the simulator's ground truth.
  const auto listed = test::run_program(
      "tactile", "labels list " + demo("labels.db") + " --recording tsa-s01-t01 --json", folder);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  double time = -1.0;
  const nlohmann::json labels = nlohmann::json::parse(listed.out);
  for (const nlohmann::json& label : labels["labels"])
    if (label["region"] == "thigh-right") {
      time = 0.5 * (label["t0"].get<double>() + label["t1"].get<double>());
      break;
    }
  ASSERT_GE(time, 0.0) << listed.out.substr(0, 400);
  snapshot(demo("tsa-s01-t01.h5") + " --time " + std::to_string(time), "tsa");
  const nlohmann::json drawn = state("tsa");
  const Png png = read_png(folder.file("tsa.png"));
  ASSERT_TRUE(png.pixels);
  const SkinLayout layout = load_layout("tsa");
  const std::vector<int64_t>& thigh = layout.find_group("thigh-right")->taxels;
  const std::set<int64_t> on_thigh(thigh.begin(), thigh.end());
  // The touched taxel drawn largest on the right thigh: lit pixels (over half-way up viridis:
  // green to yellow) inside its drawn circle.
  int most_lit = 0;
  for (const nlohmann::json& id : drawn["skin"]["touched"]) {
    if (!on_thigh.count(id.get<int64_t>())) continue;
    const nlohmann::json& box = drawn["skin"]["taxels"][std::to_string(id.get<int64_t>())];
    most_lit = std::max(most_lit, pixels_in_shape(png, box, [](const unsigned char* p) {
                          return p[1] > 140 && p[1] > p[2];
                        }));
  }
  EXPECT_GE(most_lit, 50) << drawn["skin"]["touched"].dump();
  // The body's parts are named on the map, beside their pads.
  for (const char* part : {"head-back", "arm-right", "thigh-right"})
    EXPECT_EQ(times_named(drawn, part), 1) << part << ": " << drawn["skin"]["names"].dump();
}

TEST_F(WorkbenchSkins, TheSomatosensoryMapColoursRegionsAndItsLegendAndCaptionFit) {
  snapshot(demo("robovie-s01-t01.h5") + " --time 12 --view somatosensory", "map");
  const nlohmann::json drawn = state("map");
  const Png png = read_png(folder.file("map.png"));
  ASSERT_TRUE(png.pixels);
  const SkinLayout layout = load_layout("robovie");
  const nlohmann::json& legend = drawn["legends"]["somatosensory"];
  const auto colour_at = [&png](double x, double y) {
    const unsigned char* p = png.at(static_cast<int>(x), static_cast<int>(y));
    return p[0] << 16 | p[1] << 8 | p[2];
  };
  std::set<int> swatches;
  size_t parts = 0;
  for (const Group& group : layout.groups) {
    if (group.kind != "body-part") continue;
    ++parts;
    // Each region in the legend, in a colour of its own that its taxels are drawn in (the
    // middle of one of them at least: the map's dots may cover each other).
    ASSERT_TRUE(legend.contains(group.name)) << group.name << ": " << legend.dump();
    const nlohmann::json& swatch = legend[group.name];
    const int colour = colour_at(swatch["x"].get<double>() + 5, swatch["y"].get<double>() + 5);
    swatches.insert(colour);
    int drawn_in_it = 0;
    for (int64_t id : group.taxels) {
      const nlohmann::json& box = drawn["skin"]["taxels"][std::to_string(id)];
      drawn_in_it += colour_at(box["x"].get<double>() + box["width"].get<double>() / 2,
                               box["y"].get<double>() + box["height"].get<double>() / 2) == colour;
    }
    EXPECT_GT(drawn_in_it, 0) << group.name;
  }
  EXPECT_EQ(legend.size(), parts);
  EXPECT_EQ(swatches.size(), parts);
  // The caption wraps inside the view instead of running off its edge.
  const nlohmann::json& caption = drawn["skin"]["caption"];
  const nlohmann::json& view = drawn["views"]["somatosensory"];
  ASSERT_FALSE(caption.is_null());
  EXPECT_LE(caption["x"].get<double>() + caption["width"].get<double>(),
            view["x"].get<double>() + view["width"].get<double>());
}

TEST_F(WorkbenchSkins, AStripOf64FillsItsPanelInRowsOfSquareCells) {
  std::ofstream csv(folder.file("strip.csv"));
  csv << "t";
  for (int channel = 0; channel < 64; ++channel) csv << ",ch" << channel;
  csv << "\n";
  for (int sample = 0; sample < 20; ++sample) {
    csv << sample / 10.0;
    for (int channel = 0; channel < 64; ++channel) csv << "," << (channel == sample ? 1 : 0);
    csv << "\n";
  }
  csv.close();
  const auto imported = test::run_program(
      "tactile",
      "import " + folder.file("strip.csv") + " --layout strip:64 --out " + folder.file("strip.h5"),
      folder);
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  snapshot(folder.file("strip.h5") + " --time 0.5", "strip");
  const nlohmann::json drawn = state("strip");
  EXPECT_GT(drawn["skin"]["columns"].get<int>(), 1);
  EXPECT_LT(drawn["skin"]["columns"].get<int>(), 64);
  const nlohmann::json& panel = drawn["views"]["skin"];
  double top = 1e9, bottom = -1e9;
  for (const auto& [id, box] : drawn["skin"]["taxels"].items()) {
    EXPECT_GE(box["width"].get<double>(), 30.0) << "ch" << id;
    EXPECT_NEAR(box["width"].get<double>(), box["height"].get<double>(), 1.0) << "ch" << id;
    top = std::min(top, box["y"].get<double>());
    bottom = std::max(bottom, box["y"].get<double>() + box["height"].get<double>());
  }
  // The rows fill more than half the panel's height (one row of 64 filled a 20th of it).
  EXPECT_GT(bottom - top, 0.5 * panel["height"].get<double>());
  // A cell names itself.
  EXPECT_EQ(times_named(drawn, "ch63"), 1) << drawn["skin"]["names"].dump();
}

TEST_F(WorkbenchSkins, RobovieNamesEveryBodyPartOnEachViewItIsSeenOnInItsOwnView) {
  snapshot(demo("robovie-s01-t01.h5") + " --time 12 --view skin", "robovie");
  const nlohmann::json drawn = state("robovie");
  const SkinLayout layout = load_layout("robovie");
  const Group& front = *layout.find_group("front");
  for (const Group& group : layout.groups) {
    if (group.kind != "body-part") continue;
    // Seen from the front, from behind, or both.
    const bool on_front = std::any_of(group.taxels.begin(), group.taxels.end(), [&](int64_t id) {
      return std::find(front.taxels.begin(), front.taxels.end(), id) != front.taxels.end();
    });
    const bool on_back = std::any_of(group.taxels.begin(), group.taxels.end(), [&](int64_t id) {
      return std::find(front.taxels.begin(), front.taxels.end(), id) == front.taxels.end();
    });
    EXPECT_EQ(times_named(drawn, group.id), int(on_front) + int(on_back))
        << group.id << " in " << drawn["skin"]["names"].dump();
  }
}

}  // namespace
}  // namespace tactile

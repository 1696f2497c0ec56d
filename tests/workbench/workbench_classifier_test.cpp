// Classifiers in the workbench, driven by scripts through ImGui's real input path: from a
// fresh demo workspace, train every preset, open the confusion matrix, click a wrong cell,
// land on its segment (the screenshot shows it); results opened from files; the SOM,
// scatter and somatosensory views as PNGs; the prediction lane corrected by keys.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "cli_test_support.h"
#include "demo_workspace.h"
#include "png_test_support.h"

namespace tactile {
namespace {

class WorkbenchClassifiers : public test::DemoWorkspace {
 protected:
  WorkbenchClassifiers() : DemoWorkspace("tactile-workbench-classifiers") {}
  test::CommandResult workbench(const std::string& arguments, const std::string& text = "") {
    return DemoWorkspace::workbench(arguments, text, "1400x800");
  }
  // SKIN simulated into folder/SKIN and described by its own pipeline: the table's path, or
  // "" (with the failure added) when a step failed.
  std::string simulated_table(const std::string& skin, int subjects, int repetitions) {
    const test::CommandResult simulated = test::run_program(
        "tactile",
        "simulate --skin " + skin + " --subjects " + std::to_string(subjects) + " --repetitions " +
            std::to_string(repetitions) + " --out " + folder.file(skin),
        folder);
    if (simulated.exit_code != 0) ADD_FAILURE() << simulated.err;
    const std::string table = folder.file(skin + "/features.csv");
    const test::CommandResult described =
        test::run_program("tactile",
                          "features --pipeline " + skin + " --labels " +
                              folder.file(skin + "/labels.db") + " --out " + table,
                          folder);
    if (described.exit_code != 0) ADD_FAILURE() << described.err;
    return simulated.exit_code == 0 && described.exit_code == 0 ? table : "";
  }
};

const char* kTrainAll =
    "wait 2\nclick item tab:model\nwait 2\nclick item button:Train all\nwait training\nwait 3\n";

// The RGB a view's legend shows for a class, read off its screenshot at the swatch's centre.
uint32_t legend_colour(const Png& png, const nlohmann::json& state, const std::string& view,
                       const std::string& name) {
  const nlohmann::json& swatch = state["legends"][view][name];
  if (swatch.is_null()) return 0;
  const unsigned char* p =
      png.at(static_cast<int>(swatch["x"].get<double>() + swatch["width"].get<double>() / 2),
             static_cast<int>(swatch["y"].get<double>() + swatch["height"].get<double>() / 2));
  return 0xFF000000u | p[0] << 16 | p[1] << 8 | p[2];
}

TEST_F(WorkbenchClassifiers, EachClassHasOneColourInTheLanesTheScatterTheSomAndTheConfusion) {
  const std::string table = simulated_table("fur", 2, 2);
  ASSERT_FALSE(table.empty());
  const auto run = workbench(
      folder.file("fur/fur-s01-t01.h5") + " --features " + table,
      std::string(kTrainAll) +
          "click item tab:confusion\nwait 2\nscreenshot @confusion.png\nstate @confusion.json\n"
          "click item tab:scatter\nwait jobs\nwait 1\nscreenshot @scatter.png\nstate "
          "@scatter.json\n"
          "click item tab:som\nwait jobs\nwait 1\nscreenshot @som.png\nstate @som.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::set<uint32_t> class_colours;
  for (const std::string name : {"slap", "pat", "fondle", "stroke", "tickle", "push"}) {
    const uint32_t lanes =
        legend_colour(read_png(folder.file("scatter.png")), state("scatter.json"), "lanes", name);
    ASSERT_NE(lanes, 0u) << name << ": no lanes legend " << state("scatter.json")["legends"];
    EXPECT_EQ(
        legend_colour(read_png(folder.file("scatter.png")), state("scatter.json"), "scatter", name),
        lanes)
        << name;
    EXPECT_EQ(legend_colour(read_png(folder.file("som.png")), state("som.json"), "som", name),
              lanes)
        << name;
    EXPECT_EQ(legend_colour(read_png(folder.file("confusion.png")), state("confusion.json"),
                            "confusion", name),
              lanes)
        << name;
    class_colours.insert(lanes);
  }
  EXPECT_EQ(class_colours.size(), 6u);             // no two classes share one
  EXPECT_FALSE(class_colours.count(0xFF969696u));  // nor the neutral grey of "unknown"
}

TEST_F(WorkbenchClassifiers, TrainAllThenAWrongCellLandsOnItsSegment) {
  // First run: which cells are wrong (training is seeded: the second run gets the same).
  const std::string recording = demo("fur-s01-t01.h5");
  auto trained = workbench(recording, std::string(kTrainAll) + "state @trained.json\n");
  ASSERT_EQ(trained.exit_code, 0) << trained.err;
  const nlohmann::json analysis = state("trained.json")["analysis"];
  ASSERT_GE(analysis["results"].size(), 15u);
  // The best row is current: the table's highest accuracy.
  double best = 0.0;
  for (const nlohmann::json& row : analysis["results"])
    if (row.contains("accuracy")) best = std::max(best, row["accuracy"].get<double>());
  std::string current_name = analysis["current"];
  for (const nlohmann::json& row : analysis["results"])
    if (row["classifier"] == current_name) {
      EXPECT_DOUBLE_EQ(row["accuracy"].get<double>(), best);
    }
  const auto classes = analysis["classes"].get<std::vector<std::string>>();
  const auto confusion = analysis["confusion"].get<std::vector<std::vector<int>>>();
  std::string truth, predicted;
  for (size_t row = 0; row < classes.size() && truth.empty(); ++row)
    for (size_t column = 0; column < classes.size(); ++column)
      if (row != column && confusion[row][column] > 0) {
        truth = classes[row], predicted = classes[column];
        break;
      }
  ASSERT_FALSE(truth.empty()) << "the best model made no mistake on the demo";

  auto landed =
      workbench(recording, std::string(kTrainAll) + "click cell " + truth + " " + predicted +
                               "\nwait 2\nstate @cell.json\nkey Enter\n"
                               "wait 12\nstate @landed.json\nscreenshot @landed.png\n"
                               "key N\nwait 3\nstate @next.json\n");
  ASSERT_EQ(landed.exit_code, 0) << landed.err;
  const nlohmann::json cell = state("cell.json")["analysis"]["cell"];
  EXPECT_EQ(cell["true"], truth);
  EXPECT_EQ(cell["predicted"], predicted);
  EXPECT_GE(cell["segments"].get<int>(), 1);
  // The list: the least sure first, each with its margin and probability.
  const nlohmann::json& list = cell["list"];
  ASSERT_EQ(list.size(), cell["segments"].get<size_t>());
  for (size_t k = 0; k < list.size(); ++k) {
    EXPECT_GE(list[k]["score"].get<double>(), 0.0);
    EXPECT_LE(list[k]["score"].get<double>(), 1.0);
    if (k > 0) {
      EXPECT_LE(list[k - 1]["margin"].get<double>(), list[k]["margin"].get<double>());
    }
  }
  const nlohmann::json at = state("landed.json");
  const nlohmann::json segment = at["analysis"]["landed"];
  ASSERT_FALSE(segment.is_null());
  EXPECT_EQ(segment["segment_id"], list[0]["segment_id"]);  // Enter: the first, least sure
  EXPECT_EQ(segment["true"], truth);
  EXPECT_EQ(segment["predicted"], predicted);
  // Its recording is open, the cursor inside the segment (replaying), the plot around it,
  // the label selected.
  EXPECT_EQ(at["recording"], segment["recording"]);
  EXPECT_GE(at["time"].get<double>(), segment["t0"].get<double>());
  EXPECT_LE(at["time"].get<double>(), segment["t1"].get<double>());
  EXPECT_LE(at["plot"]["t0"].get<double>(), segment["t0"].get<double>());
  EXPECT_GE(at["plot"]["t1"].get<double>(), segment["t1"].get<double>());
  EXPECT_EQ(at["selection"]["labels"], nlohmann::json::array({segment["segment_id"]}));
  EXPECT_EQ(at["error"], "");
  // The screenshot: the skin names both classes on a red banner (a wrong answer), the
  // touch lights the skin, the region is outlined in orange.
  const Png png = read_png(folder.file("landed.png"));
  ASSERT_TRUE(png.pixels);
  const nlohmann::json skin = at["views"]["skin"];
  const int x0 = skin["x"].get<int>(), y0 = skin["y"].get<int>();
  int banner = 0, outline = 0;
  for (int y = y0; y < y0 + skin["height"].get<int>(); ++y)
    for (int x = x0; x < x0 + skin["width"].get<int>(); ++x) {
      const unsigned char* p = png.at(x, y);
      banner += std::abs(p[0] - 120) < 6 && std::abs(p[1] - 30) < 6 && std::abs(p[2] - 25) < 6;
      outline += p[0] > 240 && std::abs(p[1] - 140) < 20 && p[2] < 70;
    }
  EXPECT_GT(banner, 500) << "no true/predicted banner over the skin";
  EXPECT_GT(outline, 100) << "the segment's region is not outlined";
  // N walks on to another mistake.
  const nlohmann::json next = state("next.json")["analysis"]["landed"];
  EXPECT_NE(next["true"], next["predicted"]);
}

// Train all shows each preset's result as it arrives (the quick ones first), says how far it
// is and how long is left, and Cancel keeps the results that finished.
TEST_F(WorkbenchClassifiers, TrainAllShowsEachResultAsItArrivesAndCancelKeepsThem) {
  auto run = workbench(demo("fur-s01-t01.h5"),
                       "wait 2\nclick item tab:model\nwait 2\nclick item button:Train all\n"
                       "wait results 3\nstate @partial.json\nclick item button:Cancel\n"
                       "wait jobs\nwait 2\nstate @cancelled.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The window's one list of jobs holds the run, which the model view shows.
  const nlohmann::json pending = state("partial.json")["pending_jobs"];
  ASSERT_EQ(pending.size(), 1u) << pending;
  EXPECT_EQ(pending[0]["kind"], "training");
  EXPECT_EQ(pending[0]["name"], "training");
  EXPECT_EQ(pending[0]["status"], "running");
  EXPECT_EQ(pending[0]["shown_in"], "model");
  const nlohmann::json partial = state("partial.json")["analysis"];
  EXPECT_EQ(partial["training"], "running");
  ASSERT_GE(partial["results"].size(), 3u);
  EXPECT_NE(partial["training_progress"].get<std::string>().find(" %"), std::string::npos);
  EXPECT_FALSE(partial["current"].is_null());  // the first to arrive is shown at once
  EXPECT_GT(partial["dataset_rows"].get<int>(), 0);
  // The quick ones first: Naive Bayes before boosting and the SOM.
  EXPECT_EQ(partial["results"][0]["classifier"], "gaussian-nb");

  const nlohmann::json cancelled = state("cancelled.json");
  EXPECT_TRUE(cancelled["pending_jobs"].empty()) << cancelled["pending_jobs"];
  const nlohmann::json analysis = cancelled["analysis"];
  EXPECT_EQ(analysis["training"], "idle");
  EXPECT_GE(analysis["results"].size(), partial["results"].size());
  EXPECT_LT(analysis["results"].size(), 24u) << "the run ended before Cancel";
  for (const nlohmann::json& row : analysis["results"])
    EXPECT_TRUE(row.contains("accuracy") || row.contains("skipped")) << row.dump();
  EXPECT_FALSE(analysis["current"].is_null());
  EXPECT_NE(cancelled["notice"].get<std::string>().find("kept the"), std::string::npos)
      << cancelled["notice"];
}

// The SOM map and the scatter's PCA run on a worker: the window goes on drawing frames, and
// each result is applied frames after its job started (it was fitted inside one frame,
// 18-20 s at 454 x 1692); a screenshot waits for the view's job.
TEST_F(WorkbenchClassifiers, TheSomMapAndTheScatterAreComputedWhileFramesGoOn) {
  const std::string table = simulated_table("flux", 2, 3);
  ASSERT_FALSE(table.empty());
  const auto run = workbench("--features " + table,
                             "wait 2\nclick item tab:som\nwait jobs\nwait 1\nstate @som.json\n"
                             "click item tab:scatter\nwait jobs\nwait 1\nstate @scatter.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto job = [](const nlohmann::json& state, const std::string& name) {
    for (const auto& entry : state["jobs"])
      if (entry["name"] == name) return entry;
    return nlohmann::json();
  };
  const nlohmann::json som_state = state("som.json");
  const nlohmann::json som = job(som_state, "SOM map");
  ASSERT_FALSE(som.is_null()) << som_state["jobs"];
  EXPECT_EQ(som["status"], "done");
  EXPECT_GT(som["finished_frame"].get<int>(), som["started_frame"].get<int>());
  EXPECT_FALSE(som_state["analysis"]["som"].is_null());
  EXPECT_EQ(som_state["error"], "");
  const nlohmann::json scatter = job(state("scatter.json"), "scatter");
  ASSERT_FALSE(scatter.is_null()) << state("scatter.json")["jobs"];
  EXPECT_EQ(scatter["status"], "done");
  EXPECT_GT(scatter["finished_frame"].get<int>(), scatter["started_frame"].get<int>());

  // Rendered to a PNG on its own, the view shows the map, not the progress of its job.
  const auto shot = workbench("--features " + table + " --view som --headless --screenshot " +
                              folder.file("som-alone.png"));
  ASSERT_EQ(shot.exit_code, 0) << shot.err;
  EXPECT_GT(colours_in(read_png(folder.file("som-alone.png"))), 30u);
}

TEST_F(WorkbenchClassifiers, ResultFilesOpenFromTheCommandLine) {
  // A table and a result of one skin, made with the command line.
  ASSERT_EQ(
      test::run_program(
          "tactile",
          "simulate --skin flux --subjects 2 --repetitions 3 --out " + folder.file("flux"), folder)
          .exit_code,
      0);
  const std::string table = folder.file("flux/features.csv");
  auto features = test::run_program(
      "tactile",
      "features --pipeline flux --labels " + folder.file("flux/labels.db") + " --out " + table,
      folder);
  ASSERT_EQ(features.exit_code, 0) << features.err;
  auto evaluated = test::run_program(
      "tactile",
      "evaluate --features " + table + " --classifier knn --protocol kfold:3 --out " +
          folder.file("flux/result.json") + " --save-model " + folder.file("flux/knn.json"),
      folder);
  ASSERT_EQ(evaluated.exit_code, 0) << evaluated.err;
  auto som = test::run_program("tactile",
                               "evaluate --features " + table +
                                   " --classifier som:epochs=50 --protocol kfold:3 --save-model " +
                                   folder.file("flux/som.json"),
                               folder);
  ASSERT_EQ(som.exit_code, 0) << som.err;

  // The confusion view of the result; the scatter of its rows (the table it names).
  for (const char* view : {"confusion", "scatter"}) {
    const std::string png_path = folder.file(std::string(view) + ".png");
    auto drawn = workbench("--evaluation " + folder.file("flux/result.json") + " --view " + view +
                           " --headless --screenshot " + png_path);
    ASSERT_EQ(drawn.exit_code, 0) << view << ": " << drawn.err;
    const Png png = read_png(png_path);
    ASSERT_TRUE(png.pixels);
    EXPECT_GT(colours_in(png), 12u) << view << " looks empty";
    if (std::string(view) == "confusion") {
      EXPECT_GT(count_viridis_top(png), 400) << "no full (100 %) cell drawn";
    }
  }
  // A SOM model's map, with the table's rows on it.
  auto map = workbench("--model " + folder.file("flux/som.json") + " --features " + table +
                       " --view som --headless --screenshot " + folder.file("som.png"));
  ASSERT_EQ(map.exit_code, 0) << map.err;
  EXPECT_GT(colours_in(read_png(folder.file("som.png"))), 30u);
  // A model of another kind has no map: said, not drawn as nothing.
  auto knn =
      workbench("--model " + folder.file("flux/knn.json"), "wait 2\nstate @knn-model.json\n");
  ASSERT_EQ(knn.exit_code, 0) << knn.err;
  EXPECT_NE(state("knn-model.json")["error"].get<std::string>().find("only a SOM has a map"),
            std::string::npos);
  // A damaged result is named, and the workbench still runs.
  std::ofstream(folder.file("broken.json")) << "{\"classifier\": \"knn\"}";
  auto broken =
      workbench("--evaluation " + folder.file("broken.json"), "wait 2\nstate @broken.json\n");
  ASSERT_EQ(broken.exit_code, 0) << broken.err;
  EXPECT_NE(state("broken.json")["error"].get<std::string>().find("missing field 'protocol'"),
            std::string::npos)
      << state("broken.json")["error"];

  // From an opened result, a click on a cell lands on a recording of the workspace.
  std::ifstream in(folder.file("flux/result.json"));
  const nlohmann::json result = nlohmann::json::parse(in);
  const std::string first = result["classes"][0];
  auto clicked = workbench(folder.file("flux") + " --evaluation " + folder.file("flux/result.json"),
                           "wait 2\nclick item tab:confusion\nwait 2\nclick cell " + first + " " +
                               first + "\nwait 2\nkey Enter\nwait 5\nstate @clicked.json\n");
  ASSERT_EQ(clicked.exit_code, 0) << clicked.err;
  const nlohmann::json landed = state("clicked.json");
  EXPECT_EQ(landed["analysis"]["landed"]["true"], first);
  EXPECT_EQ(landed["recording"], landed["analysis"]["landed"]["recording"]);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// A preset with a dash in its name, typed into the Model tab's box, trains and fills the
// results table (the box takes any name of the catalogue, the presets list shows them all).
TEST_F(WorkbenchClassifiers, ARandomForestTypedIntoTheModelTabTrains) {
  auto run = workbench(demo("fur-s01-t01.h5"),
                       "wait 2\nclick item tab:model\nwait 2\nclick item classifier\nwait 1\n"
                       "key Ctrl+A\ntype random-forest:trees=20\nkey Enter\nwait 2\n"
                       "click item button:Run\nwait training\nwait 2\nstate @forest.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json analysis = state("forest.json")["analysis"];
  ASSERT_EQ(analysis["results"].size(), 1u) << analysis.dump();
  EXPECT_EQ(analysis["results"][0]["classifier"], "random-forest:trees=20");
  EXPECT_GT(analysis["results"][0]["accuracy"].get<double>(), 0.5);
}

// The features' parameters typed beside their choice reach the table and the saved model (the
// route docs/FEATURES.md gives for a grid takes one); a key the pipeline does not read is
// refused, naming it, before anything runs.
TEST_F(WorkbenchClassifiers, PipelineParametersTypedInTheModelTabReachTheSavedModel) {
  auto run = workbench(demo("fur-s01-t01.h5"),
                       "wait 2\nclick item tab:model\nwait 2\nclick item input:pipeline-params\n"
                       "wait 1\ntype nonsense=1\nkey Enter\nwait 1\nclick item button:Run\nwait 2\n"
                       "state @refused.json\nclick item input:pipeline-params\nwait 1\nkey Ctrl+A\n"
                       "type cutoff_hz=5\nkey Enter\nwait 1\nclick item button:Run\n"
                       "wait training\nwait 2\nstate @trained.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json refused = state("refused.json");
  EXPECT_NE(refused["error"].get<std::string>().find("nonsense"), std::string::npos)
      << refused["error"];
  EXPECT_TRUE(refused["analysis"]["results"].empty());
  const nlohmann::json analysis = state("trained.json")["analysis"];
  EXPECT_EQ(analysis["pipeline"], "");  // the skin's own: fur
  EXPECT_EQ(analysis["pipeline_params"], "cutoff_hz=5");
  ASSERT_EQ(analysis["results"].size(), 1u) << analysis.dump();
  ASSERT_TRUE(analysis["model"].is_string());
  std::ifstream model_file(analysis["model"].get<std::string>());
  const nlohmann::json model = nlohmann::json::parse(model_file);
  EXPECT_EQ(model["pipeline"], "fur");
  EXPECT_NE(model["pipeline_params"].get<std::string>().find("cutoff_hz=5"), std::string::npos)
      << model["pipeline_params"];
}

// The loop of the prediction lane: Run one classifier (the linear SVM), Predict, U goes to
// the least sure prediction, Y confirms it, a digit corrects the next; both are manual labels
// at once. The SVM's scores are probabilities, so the margins differ and U has a smallest.
TEST_F(WorkbenchClassifiers, PredictionsRankByMarginAndAreConfirmedAndCorrectedByKeys) {
  auto run =
      workbench(demo("fur-s01-t01.h5"),
                "wait 2\nclick item tab:model\nwait 2\nclick item button:Run\nwait training\n"
                "wait 2\nclick item tab:model\nwait 2\nclick item button:Predict\nwait jobs\n"
                "state @predicted.json\nclick item header:margin\nwait 2\nstate @sorted.json\n"
                "key U\nwait 2\nstate @uncertain.json\nkey Y\nwait 2\n"
                "state @confirmed.json\nkey 1\nwait 2\nstate @corrected.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto lane = [](const nlohmann::json& at, const std::string& id) {
    for (const nlohmann::json& shown : at["lanes"])
      if (shown["id"] == id) return shown["labels"].get<int>();
    return 0;
  };
  EXPECT_EQ(lane(state("predicted.json"), "model:model"),
            lane(state("predicted.json"), "ground-truth"));
  EXPECT_EQ(state("uncertain.json")["selection"]["labels"].size(), 1u);
  {  // The margins of the model's labels (their notes: "margin=M model=SPEC"), U's the least.
    const auto predictions = test::run_program(
        "tactile", "labels list " + demo("labels.db") + " --source model --json", folder);
    ASSERT_EQ(predictions.exit_code, 0) << predictions.err;
    const nlohmann::json listed = nlohmann::json::parse(predictions.out);
    std::map<int64_t, double> margins;
    for (const nlohmann::json& label : listed["labels"])
      if (label["recording"] == "fur-s01-t01")
        margins[label["id"].get<int64_t>()] =
            std::stod(label["note"].get<std::string>().substr(std::string("margin=").size()));
    ASSERT_GE(margins.size(), 3u);
    std::set<double> distinct;
    double least = 2.0;
    for (const auto& [id, margin] : margins)
      distinct.insert(margin), least = std::min(least, margin);
    EXPECT_GT(distinct.size(), margins.size() / 2) << "margins tie: vote shares, not probabilities";
    const int64_t chosen = state("uncertain.json")["selection"]["labels"][0].get<int64_t>();
    ASSERT_TRUE(margins.count(chosen)) << chosen;
    EXPECT_EQ(margins[chosen], least);
    // The label table sorted by its margin header: the predictions least sure first, then
    // the labels that have no margin.
    const nlohmann::json table = state("sorted.json")["label_table"];
    EXPECT_EQ(table["sort"], "margin");
    EXPECT_EQ(table["ascending"], true);
    const auto ids = table["ids"].get<std::vector<int64_t>>();
    ASSERT_GT(ids.size(), margins.size());
    for (size_t k = 0; k < margins.size(); ++k) {
      ASSERT_TRUE(margins.count(ids[k])) << "a label without a margin before a prediction";
      if (k > 0) {
        EXPECT_LE(margins[ids[k - 1]], margins[ids[k]]);
      }
    }
    EXPECT_EQ(margins[ids[0]], least);
  }
  const nlohmann::json evaluation =
      nlohmann::json::parse(std::ifstream(demo("models/fur-linear-svm.evaluation.json")));
  std::set<double> row_margins;
  for (const nlohmann::json& row : evaluation["rows"])
    row_margins.insert(row["margin"].get<double>());
  EXPECT_GT(row_margins.size(), evaluation["rows"].size() / 2) << "the confusion list cannot rank";
  EXPECT_EQ(lane(state("confirmed.json"), "manual:ana"), 1);
  EXPECT_EQ(lane(state("corrected.json"), "manual:ana"), 2);
  EXPECT_TRUE(std::filesystem::exists(demo("models/fur-linear-svm.json")));
  EXPECT_TRUE(std::filesystem::exists(demo("models/fur-linear-svm.evaluation.json")));
  const auto listed = test::run_program(
      "tactile", "labels list " + demo("labels.db") + " --source manual --json", folder);
  const nlohmann::json labels = nlohmann::json::parse(listed.out)["labels"];
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_NE(labels[0]["note"].get<std::string>().find("confirmed model"), std::string::npos);
  EXPECT_NE(labels[1]["note"].get<std::string>().find("model"), std::string::npos);
}

// Predict, confirm and correct are commands: each undone exactly by Ctrl+Z (in a new process)
// and redone by Ctrl+Shift+Z, the whole label table compared.
TEST_F(WorkbenchClassifiers, PredictConfirmAndCorrectEachUndoAsOneCommand) {
  const auto all_labels = [&] {
    const auto listed =
        test::run_program("tactile", "labels list " + demo("labels.db") + " --json", folder);
    nlohmann::json labels = nlohmann::json::parse(listed.out)["labels"];
    for (nlohmann::json& label : labels)
      for (const char* field : {"id", "created", "modified"}) label.erase(field);
    return labels;
  };
  const std::string recording = demo("fur-s01-t01.h5");
  const auto expect_one_undo = [&](const std::string& command) {
    const nlohmann::json before = all_labels();
    const auto done = workbench(recording, command + "state @done.json\n");
    ASSERT_EQ(done.exit_code, 0) << done.err;
    ASSERT_EQ(state("done.json")["error"], "");
    const nlohmann::json after = all_labels();
    ASSERT_NE(after, before) << command;
    ASSERT_EQ(workbench(recording, "wait 2\nkey Ctrl+Z\nwait 1\nstate @undone.json\n").exit_code,
              0);
    EXPECT_TRUE(state("undone.json")["notice"].get<std::string>().starts_with("undone: "))
        << state("undone.json")["notice"];
    EXPECT_EQ(all_labels(), before) << command;
    ASSERT_EQ(workbench(recording, "wait 2\nkey Ctrl+Shift+Z\nwait 1\n").exit_code, 0);
    EXPECT_EQ(all_labels(), after) << command;
  };
  // The model is trained in the same process as Predict (the panel predicts with its last run).
  expect_one_undo(
      "wait 2\nclick item tab:model\nwait 2\nclick item button:Run\nwait training\nwait 2\n"
      "click item tab:model\nwait 2\nclick item button:Predict\nwait jobs\n");
  const nlohmann::json job = state("done.json")["jobs"].back();  // a job, applied frames later
  EXPECT_EQ(job["name"], "predict");
  EXPECT_EQ(job["status"], "done");
  EXPECT_GT(job["finished_frame"].get<int>(), job["started_frame"].get<int>());
  expect_one_undo("wait 2\nkey U\nwait 2\nkey Y\nwait 2\n");
  expect_one_undo("wait 2\nkey U\nwait 2\nkey 1\nwait 2\n");
}

// Cancel through the view's button ends the SOM's fit (15 s on a table of the size),
// leaves no map, and Compute starts it again.
TEST_F(WorkbenchClassifiers, CancellingTheSomMapsJobLeavesNoMapAndComputeStartsItAgain) {
  const std::string table = folder.file("table.csv");
  {
    std::ofstream out(table);
    for (int c = 0; c < 1692; ++c) out << "f" << c << ",";
    out << "class,subject,recording,segment_id\n";
    std::srand(3);
    for (int row = 0; row < 454; ++row) {
      for (int c = 0; c < 1692; ++c) out << 0.3 * (row % 6) + std::rand() / double(RAND_MAX) << ",";
      out << "class" << row % 6 + 1 << ",s" << row % 10 + 1 << ",r" << row / 20 << "," << row + 1
          << "\n";
    }
  }
  const auto run =
      workbench("--features " + table,
                "wait 2\nclick item tab:som\nwait 3\nclick item button:Cancel\nwait jobs\n"
                "wait 1\nstate @cancelled.json\nclick item button:Compute\nwait 3\n"
                "state @again.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json cancelled = state("cancelled.json");
  ASSERT_FALSE(cancelled["jobs"].empty()) << cancelled.dump(1);
  const nlohmann::json job = cancelled["jobs"].back();
  EXPECT_EQ(job["name"], "SOM map");
  EXPECT_EQ(job["status"], "cancelled");
  // Ended as cancelled, not done: it stopped between epochs (how soon is the benchmark's: a
  // frame count here would measure the build, 5 frames in Release, 100 under ASan).
  EXPECT_TRUE(cancelled["analysis"]["som"].is_null());
  const nlohmann::json again = state("again.json");
  EXPECT_EQ(again["jobs"].back()["status"], "running");
}

// The somatosensory map is a job: chosen in the skin view's menu, computed while frames go on.
TEST_F(WorkbenchClassifiers, TheSomatosensoryMapIsComputedWhileFramesGoOn) {
  const auto run = workbench(demo("robovie-s01-t01.h5"),
                             "wait 2\nclick item map\nwait 1\nclick item map:somatosensory\n"
                             "wait jobs\nwait 1\nstate @map.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json map = state("map.json");
  ASSERT_FALSE(map["jobs"].empty()) << map.dump(1);
  const nlohmann::json job = map["jobs"].back();
  EXPECT_EQ(job["name"], "somatosensory map");
  EXPECT_EQ(job["status"], "done");
  EXPECT_GT(job["finished_frame"].get<int>(), job["started_frame"].get<int>());
  EXPECT_EQ(map["error"], "");
}

// Each classifier view exports headless, and the somatosensory map of Robovie's films.
TEST_F(WorkbenchClassifiers, SomatosensoryMapRendersAndIsCachedBesideTheRecording) {
  const std::string png = folder.file("somatosensory.png");
  auto drawn = workbench(demo("robovie-s01-t01.h5") +
                         " --time 12 --view somatosensory --headless --screenshot " + png);
  ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
  const Png image = read_png(png);
  ASSERT_TRUE(image.pixels);
  EXPECT_GT(colours_in(image), 30u);
  bool cached = false;
  for (const auto& entry : std::filesystem::directory_iterator(folder.file("demo")))
    cached |= entry.path().filename().string().starts_with("robovie-s01-t01.somatosensory-");
  EXPECT_TRUE(cached);
}

}  // namespace
}  // namespace tactile

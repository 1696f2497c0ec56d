// `tactile evaluate` end to end on small feature CSVs written by the tests.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_test_support.h"

namespace tactile::test {
namespace {

// Two well separated classes, 4 subjects, segment ids 500 + row, the layout
// `tactile features` writes: features, then class, subject, recording, segment_id, side.
void write_features(const std::string& path, double separation) {
  std::mt19937_64 random(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::ofstream out(path);
  out << "energy,peak,class,subject,recording,segment_id,side\n";
  for (int row = 0; row < 40; ++row) {
    const bool stroke = row % 2 == 1;
    const double offset = stroke ? separation : 0.0;
    out << normal(random) + offset << "," << normal(random) + offset << ","
        << (stroke ? "stroke" : "tap") << ",s" << row % 4 << ",rec" << row % 4 << ".h5,"
        << 500 + row << "," << (row < 20 ? "front" : "back") << "\n";
  }
}

TEST(EvaluateCli, SeparableFeaturesGiveAccuracyOneInJson) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 20.0);
  const CommandResult result =
      run_program("tactile",
                  "evaluate --features '" + folder.file("features.csv") +
                      "' --classifier knn:k=3 --protocol kfold:5x2 --seed 4 --json",
                  folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  EXPECT_DOUBLE_EQ(json["accuracy"].get<double>(), 1.0);
  EXPECT_EQ(json["classes"], nlohmann::json({"tap", "stroke"}));
  EXPECT_EQ(json["confusion"], nlohmann::json({{40, 0}, {0, 40}}));
  EXPECT_TRUE(json["misclassified"].empty());
  EXPECT_EQ(json["per_class"].size(), 2u);
  EXPECT_GE(json["seconds"].get<double>(), 0.0);
}

TEST(EvaluateCli, TextReportShowsConfusionAndMisclassifiedSegments) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 2.5);  // overlapping: some errors
  const CommandResult text = run_program(
      "tactile",
      "evaluate --features '" + folder.file("features.csv") + "' --classifier knn --protocol loso",
      folder);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("accuracy"), std::string::npos);
  EXPECT_NE(text.out.find("confusion (rows true, columns predicted)"), std::string::npos);
  EXPECT_NE(text.out.find("stroke"), std::string::npos);
  const CommandResult json = run_program("tactile",
                                         "evaluate --features '" + folder.file("features.csv") +
                                             "' --classifier knn --protocol loso --json",
                                         folder);
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  ASSERT_FALSE(parsed["misclassified"].empty());
  const int64_t first = parsed["misclassified"][0].get<int64_t>();
  EXPECT_GE(first, 500);
  EXPECT_NE(text.out.find("segments: " + std::to_string(first)), std::string::npos) << text.out;
  const double accuracy = parsed["accuracy"].get<double>();
  EXPECT_GT(accuracy, 0.5);
  EXPECT_LT(accuracy, 1.0);
}

TEST(EvaluateCli, SplitBySideTrainsOnFrontAndTestsOnBack) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 20.0);
  const CommandResult result =
      run_program("tactile",
                  "evaluate --features '" + folder.file("features.csv") +
                      "' --classifier weighted-knn --protocol 'split:side=front/side=back' --json",
                  folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(nlohmann::json::parse(result.out)["predictions"].get<int>(), 20);
}

TEST(EvaluateCli, SavedModelLoadsBack) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 20.0);
  const CommandResult result =
      run_program("tactile",
                  "evaluate --features '" + folder.file("features.csv") +
                      "' --classifier cosine-knn --protocol kfold:4 --save-model '" +
                      folder.file("m.json") + "'",
                  folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json model = nlohmann::json::parse(read_text(folder.path() / "m.json"));
  EXPECT_EQ(model["name"], "cosine-knn");
  EXPECT_EQ(model["classes"], nlohmann::json({"tap", "stroke"}));
  EXPECT_EQ(model["features"], nlohmann::json({"energy", "peak"}));
  EXPECT_FALSE(std::filesystem::exists(folder.file("m.json.tmp")));
}

TEST(EvaluateCli, ListNamesEveryClassifier) {
  TempFolder folder;
  const CommandResult result = run_program("tactile", "evaluate --list", folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* name : {"knn ", "cosine-knn", "weighted-knn", "subspace-knn", "grid-search"})
    EXPECT_NE(result.out.find(name), std::string::npos) << name;
}

TEST(EvaluateCli, BadInputExitsOneWithTheReason) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 20.0);
  const std::string features = "--features '" + folder.file("features.csv") + "' ";
  const struct {
    std::string arguments;
    std::string reason;
  } cases[] = {
      {features + "--classifier svm-of-dreams", "unknown classifier 'svm-of-dreams'"},
      {features + "--classifier knn:k=3,colour=blue", "unknown parameter 'colour'"},
      {features + "--classifier knn --protocol kfold:1", "--protocol"},
      {features + "--classifier knn --protocol split:side=top/side=back", "side=top"},
      {"--features '" + folder.file("missing.csv") + "' --classifier knn", "missing.csv"},
      {features, "--classifier"},
  };
  for (const auto& bad : cases) {
    const CommandResult result = run_program("tactile", "evaluate " + bad.arguments, folder);
    EXPECT_EQ(result.exit_code, 1) << bad.arguments;
    EXPECT_NE(result.err.find(bad.reason), std::string::npos) << bad.arguments << "\n"
                                                              << result.err;
  }
}

TEST(EvaluateCli, NaNInTheFeaturesIsAnErrorNotAResult) {
  TempFolder folder;
  std::ofstream(folder.file("nan.csv")) << "a,class\n1,x\nnan,y\n2,x\n3,y\n";
  const CommandResult result = run_program(
      "tactile",
      "evaluate --features '" + folder.file("nan.csv") + "' --classifier knn --protocol loo",
      folder);
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_FALSE(result.err.empty());
  EXPECT_EQ(result.out.find("accuracy"), std::string::npos);
}

// --out: the evaluation as a file, with one row per test prediction (where its
// segment is, what was true, what was answered, how sure), readable by the workbench.
TEST(EvaluateCli, OutWritesEveryTestRowWithItsSegmentAndScore) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 2.5);
  const CommandResult result = run_program("tactile",
                                           "evaluate --features '" + folder.file("features.csv") +
                                               "' --classifier knn:k=3 --protocol kfold:4 --out '" +
                                               folder.file("result.json") + "'",
                                           folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(read_text(folder.file("result.json")));
  ASSERT_EQ(json["rows"].size(), 40u);
  int wrong = 0;
  for (const nlohmann::json& row : json["rows"]) {
    for (const char* key : {"recording", "t0", "t1", "region", "true", "predicted", "score"})
      EXPECT_TRUE(row.contains(key)) << key;
    EXPECT_GE(row["score"].get<double>(), 1.0 / 3.0 - 1e-12);  // a 3-NN vote's winner
    EXPECT_LE(row["score"].get<double>(), 1.0);
    wrong += row["true"] != row["predicted"];
  }
  EXPECT_EQ(wrong, static_cast<int>(json["misclassified_predictions"].size()));
  EXPECT_GT(wrong, 0);
  EXPECT_NEAR(json["accuracy"].get<double>(), (40 - wrong) / 40.0, 1e-12);
  // A name that is not .json is refused before any work.
  const CommandResult bad =
      run_program("tactile",
                  "evaluate --features '" + folder.file("features.csv") +
                      "' --classifier knn --out '" + folder.file("r.txt") + "'",
                  folder);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--out"), std::string::npos) << bad.err;
}

// --classifier all: every preset on the same folds, a table sorted by accuracy; a preset
// that cannot learn from the data is listed as skipped, not fatal.
TEST(EvaluateCli, AllRunsEveryPresetIntoOneSortedTable) {
  TempFolder folder;
  write_features(folder.file("features.csv"), 3.0);
  const CommandResult result = run_program("tactile",
                                           "evaluate --features '" + folder.file("features.csv") +
                                               "' --classifier all --protocol kfold:4 --out '" +
                                               folder.file("all.json") + "'",
                                           folder);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("mean recall"), std::string::npos) << result.out;
  const nlohmann::json json = nlohmann::json::parse(read_text(folder.file("all.json")));
  ASSERT_GE(json["presets"].size(), 15u);
  double previous = 2.0;
  for (const nlohmann::json& preset : json["presets"]) {
    if (!preset.contains("accuracy")) continue;
    EXPECT_LE(preset["accuracy"].get<double>(), previous + 1e-12);
    previous = preset["accuracy"].get<double>();
  }
  EXPECT_FALSE(json["evaluations"].empty());
  EXPECT_EQ(json["evaluations"][0]["rows"].size(), 40u);
  for (const nlohmann::json& preset : json["presets"])
    EXPECT_NE(preset["classifier"], "grid-search");  // a search, not a preset
  const CommandResult model = run_program("tactile",
                                          "evaluate --features '" + folder.file("features.csv") +
                                              "' --classifier all --save-model m.json",
                                          folder);
  EXPECT_NE(model.exit_code, 0);
}

TEST(EvaluateCli, RandomForestPrintsItsFeatureImportances) {
  // `contact` tells the classes apart, `drift` is noise: the forest splits on contact most.
  TempFolder folder;
  {
    std::mt19937_64 random(8);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::ofstream out(folder.file("features.csv"));
    out << "drift,contact,class,subject,recording,segment_id\n";
    for (int row = 0; row < 40; ++row) {
      const bool stroke = row % 2 == 1;
      out << normal(random) << "," << normal(random) + (stroke ? 4.0 : 0.0) << ","
          << (stroke ? "stroke" : "tap") << ",s" << row % 4 << ",rec" << row % 4 << ".h5,"
          << 500 + row << "\n";
    }
  }
  const std::string command = "evaluate --features '" + folder.file("features.csv") +
                              "' --classifier random-forest:trees=20 --protocol kfold:4";
  const CommandResult text = run_program("tactile", command, folder);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const size_t heading = text.out.find("importance  top 2 of 2 features");
  ASSERT_NE(heading, std::string::npos) << text.out;
  EXPECT_LT(text.out.find("contact", heading), text.out.find("drift", heading)) << text.out;
  const CommandResult json = run_program("tactile", command + " --json", folder);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json document = nlohmann::json::parse(json.out);
  ASSERT_EQ(document["importances"].size(), 2u);
  EXPECT_EQ(document["importances"][0]["feature"], "contact");
  EXPECT_GT(document["importances"][0]["importance"].get<double>(),
            document["importances"][1]["importance"].get<double>());
}

}  // namespace
}  // namespace tactile::test

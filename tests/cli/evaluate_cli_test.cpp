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

}  // namespace
}  // namespace tactile::test

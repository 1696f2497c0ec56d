// auto's search (issue 26): column selection inside the training fold, successive halving,
// blocks of a stacked table (one pipeline each), and the stack of pipelines itself.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "ml_test_data.h"
#include "tactile/error.h"
#include "tactile/features/stack.h"
#include "tactile/ml/column_selection.h"
#include "tactile/ml/grid_search.h"

namespace tactile::ml {
namespace {

// Two classes told apart by column `informative` only; every other column is noise.
Dataset one_informative_column(int rows, int columns, int informative, uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Dataset dataset;
  dataset.features.resize(rows, columns);
  for (int r = 0; r < rows; ++r) {
    const int label = r % 2;
    for (int c = 0; c < columns; ++c) dataset.features(r, c) = normal(engine);
    dataset.features(r, informative) += 6.0 * label;
    dataset.classes.push_back(label == 0 ? "a" : "b");
    dataset.subjects.push_back("s");
    dataset.recordings.push_back("r");
    dataset.segment_ids.push_back(r + 1);
    dataset.metadata.emplace_back();
  }
  for (int c = 0; c < columns; ++c) dataset.columns.push_back({numbered("f", c), ""});
  return dataset;
}

std::vector<int> labels_of(const Dataset& dataset) {
  std::vector<int> labels;
  for (const std::string& name : dataset.classes) labels.push_back(name == "b" ? 1 : 0);
  return labels;
}

TEST(AnovaF, IsTheBetweenOverTheWithinMeanSquare) {
  Matrix x(6, 3);
  // Column 0: groups {1,2,3} and {4,5,6}; column 1 constant; column 2 separates perfectly.
  x << 1, 7, 0, 2, 7, 0, 3, 7, 0, 4, 7, 1, 5, 7, 1, 6, 7, 1;
  const Vector f = anova_f(x, {0, 0, 0, 1, 1, 1}, 2);
  // Between: 3 (2-3.5)^2 + 3 (5-3.5)^2 = 13.5 on 1 df; within: 2 + 2 = 4 on 4 df.
  EXPECT_DOUBLE_EQ(f(0), 13.5);
  EXPECT_EQ(f(1), 0.0);
  EXPECT_TRUE(std::isinf(f(2)));
  EXPECT_EQ(top_columns(f, 2), (std::vector<int>{0, 2}));
  EXPECT_EQ(top_columns(f, 1), (std::vector<int>{2}));
}

TEST(SelectClassifier, KeepsTheColumnsThatSeparateTheTrainingRows) {
  const Dataset dataset = one_informative_column(40, 30, 17, 3);
  auto select = make_classifier("select:k=3,base=knn:k=1;standardize=true");
  select->fit(dataset.features, labels_of(dataset), 2, 1);
  const auto& chosen = dynamic_cast<const SelectedColumnsClassifier&>(*select).chosen_columns();
  ASSERT_EQ(chosen.size(), 3u);
  EXPECT_NE(std::find(chosen.begin(), chosen.end(), 17), chosen.end());
  // A block restricts the columns before k is applied: the informative one is outside it.
  auto blocked = make_classifier("select:columns=0-9,k=3,base=knn");
  blocked->fit(dataset.features, labels_of(dataset), 2, 1);
  for (int column : dynamic_cast<const SelectedColumnsClassifier&>(*blocked).chosen_columns())
    EXPECT_LE(column, 9);
  const auto restored = load_classifier(nlohmann::json::parse(save_classifier(*select).dump()));
  EXPECT_EQ(restored->scores(dataset.features), select->scores(dataset.features));
  EXPECT_EQ(specification_of(*restored), specification_of(*select));
}

TEST(SelectClassifier, RefusesBadParametersByName) {
  EXPECT_THROW(make_classifier("select:k=3"), Error);                   // no base
  EXPECT_THROW(make_classifier("select:k=-1,base=knn"), Error);         // negative k
  EXPECT_THROW(make_classifier("select:columns=5-2,base=knn"), Error);  // A > B
  EXPECT_THROW(make_classifier("select:columns=x,base=knn"), Error);    // not A-B
  EXPECT_THROW(make_classifier("select:k=2,base=no-such-classifier"), Error);
  const Dataset dataset = one_informative_column(20, 4, 1, 1);
  auto outside = make_classifier("select:columns=2-9,base=knn");
  EXPECT_THROW(outside->fit(dataset.features, labels_of(dataset), 2, 1), Error);
}

TEST(SuccessiveHalving, RungsGrowByThreeUpToEveryRow) {
  // 25 candidates on 935 rows of 11 classes: a ninth, a third, all; 25 -> 9 -> 3 compared on all.
  EXPECT_EQ(rung_sizes(935, 11, 25), (std::vector<int64_t>{103, 311, 935}));
  // Few rows: no rung below 5 a class or 30 rows, so the size repeats.
  EXPECT_EQ(rung_sizes(60, 2, 25), (std::vector<int64_t>{30, 30, 60}));
  EXPECT_EQ(rung_sizes(40, 9, 25), (std::vector<int64_t>{40, 40, 40}));
  // Few candidates: one halving leaves at most three.
  EXPECT_EQ(rung_sizes(900, 2, 3), (std::vector<int64_t>{900}));
  EXPECT_EQ(rung_sizes(900, 2, 4), (std::vector<int64_t>{300, 900}));
}

TEST(SuccessiveHalving, AutoRecordsHowFarEachCandidateCameAndPicksAGoodOne) {
  const Dataset dataset = blob_dataset({60, 60, 60}, 4, 9, 2.0);
  std::vector<int> labels;
  for (const std::string& name : dataset.classes) labels.push_back(name[1] - '0');
  auto picker = make_classifier("auto:inner=kfold:3");
  picker->fit(dataset.features, labels, 3, 4);
  const auto& search = dynamic_cast<const GridSearchClassifier&>(*picker);
  int on_every_row = 0, on_fewer = 0;
  for (const GridCandidate& candidate : search.candidates()) {
    EXPECT_GT(candidate.rows, 0) << candidate.specification;
    (candidate.rows == 180 ? on_every_row : on_fewer) += 1;
  }
  // A third go on at each rung; at most three reach every row.
  const std::vector<int64_t> sizes = rung_sizes(180, 3, search.candidates().size());
  ASSERT_GE(sizes.size(), 2u);
  size_t left = search.candidates().size();
  for (size_t rung = 0; rung + 1 < sizes.size(); ++rung) left = (left + 2) / 3;
  EXPECT_LE(left, 3u);
  EXPECT_GE(on_every_row, static_cast<int>(left));  // those, and any earlier rungs' on 180 rows
  EXPECT_GT(on_fewer, 0);
  EXPECT_EQ(picker->scores(dataset.features).cols(), 3);
  // Deterministic by seed.
  auto again = make_classifier("auto:inner=kfold:3");
  again->fit(dataset.features, labels, 3, 4);
  EXPECT_EQ(dynamic_cast<const GridSearchClassifier&>(*again).chosen_specification(),
            search.chosen_specification());
}

TEST(SuccessiveHalving, WideTablesAlsoTryTheSelectedColumns) {
  const Dataset dataset = one_informative_column(60, 200, 123, 5);
  auto picker = make_classifier("auto:candidates=knn|linear-svm,inner=kfold:3");
  picker->fit(dataset.features, labels_of(dataset), 2, 1);
  const auto& candidates = dynamic_cast<const GridSearchClassifier&>(*picker).candidates();
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_EQ(candidates[2].specification, "select:k=15,base=knn");
  EXPECT_EQ(candidates[3].specification, "select:k=15,base=linear-svm");
  // A saved and loaded search keeps its added candidates and its choice.
  const auto restored = load_classifier(nlohmann::json::parse(save_classifier(*picker).dump()));
  EXPECT_EQ(restored->scores(dataset.features), picker->scores(dataset.features));
}

// Full-covariance models are tried whole only up to their catalog widest; a wider table gives
// them its selected columns alone (a 600 x 600 covariance is no candidate worth its time).
TEST(SuccessiveHalving, ACandidateWiderThanItsWidestRunsOnlyOnSelectedColumns) {
  EXPECT_EQ(widest_columns("qda:ridge=1"), 500);
  EXPECT_EQ(widest_columns("knn"), 0);
  const Dataset dataset = one_informative_column(60, 600, 7, 5);
  auto picker = make_classifier("auto:candidates=qda|knn,inner=kfold:3");
  picker->fit(dataset.features, labels_of(dataset), 2, 1);
  const auto& candidates = dynamic_cast<const GridSearchClassifier&>(*picker).candidates();
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_EQ(candidates[0].specification, "qda");
  EXPECT_EQ(candidates[0].rows, 0) << "qda ran on all 600 columns";
  EXPECT_LT(candidates[0].inner_accuracy, 0.0);
  EXPECT_EQ(candidates[2].specification, "select:k=15,base=qda");
  EXPECT_GT(candidates[2].rows, 0);
  EXPECT_GT(candidates[1].rows, 0);  // knn has no widest: it ran whole
}

TEST(AutoBlocks, SearchesTheBlocksOfAStackedTableAndNamesTheChosenPipeline) {
  // Columns 0-9 are noise ("noise/"), 10-19 hold the class ("useful/").
  Dataset dataset = one_informative_column(60, 20, 14, 8);
  for (int c = 0; c < 20; ++c)
    dataset.columns[static_cast<size_t>(c)].name =
        (c < 10 ? "noise/f" : "useful/f") + std::to_string(c);
  EXPECT_EQ(stack_blocks(dataset.columns), "noise:0-9|useful:10-19");
  EXPECT_EQ(searched_specification("auto", dataset.columns), "auto:blocks=noise:0-9|useful:10-19");
  EXPECT_EQ(searched_specification("auto:inner=kfold:3", dataset.columns),
            "auto:inner=kfold:3,blocks=noise:0-9|useful:10-19");
  EXPECT_EQ(searched_specification("knn", dataset.columns), "knn");
  const EvaluationResult result =
      evaluate(dataset, "auto:candidates=knn:k=3,inner=kfold:3", Protocol::parse("kfold:3"), 2);
  EXPECT_EQ(result.classifier, "auto:candidates=knn:k=3,inner=kfold:3");
  EXPECT_GT(result.accuracy, 0.9);
  for (const std::string& model : result.fold_models)
    EXPECT_EQ(model.rfind("useful/select:", 0), 0u) << model;
  EXPECT_THROW(make_classifier("auto:blocks=generic:3"), Error);
  EXPECT_THROW(make_classifier("auto:blocks=generic:3-1"), Error);
}

// Column 0 tells the classes apart the same way for everyone, but blurred; column 1 tells
// them apart perfectly within each subject, and for no one else. Inner folds that mix a
// subject's rows favour column 1; when the outer evaluation leaves subjects out, so do auto's
// inner folds, and it picks column 0, which holds for a subject it has not seen. With six
// subjects the last rung leaves one of the five others out at a time; with twelve it deals
// the eleven into five folds of whole subjects (not eleven folds), and still picks column 0.
Dataset general_and_personal(int subjects, int per_subject) {
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  Dataset dataset;
  dataset.features.resize(subjects * per_subject, 2);
  for (int subject = 0; subject < subjects; ++subject) {
    // Each subject's own pair of levels, far from the others': a neighbour from another
    // subject says nothing of the class.
    const double a = 100.0 * subject, b = 100.0 * subject + 50.0;
    for (int k = 0; k < per_subject; ++k) {
      const int row = subject * per_subject + k, label = k % 2;
      dataset.features(row, 0) = 1.5 * label + normal(engine);
      dataset.features(row, 1) = (label == 1 ? a : b) + 0.01 * normal(engine);
      dataset.classes.push_back(label == 0 ? "a" : "b");
      dataset.subjects.push_back("s" + std::to_string(subject));
      dataset.recordings.push_back("r" + std::to_string(subject));
      dataset.segment_ids.push_back(row + 1);
      dataset.metadata.emplace_back();
    }
  }
  dataset.columns = {{"general/f0", ""}, {"personal/f1", ""}};
  return dataset;
}

TEST(AutoBlocks, InnerFoldsKeepTheOuterGroupsWhole) {
  const std::string specification = "auto:candidates=knn:k=3,blocks=general:0-0|personal:1-1";
  for (const int subjects : {6, 12}) {
    const Dataset dataset = general_and_personal(subjects, 24);
    EXPECT_EQ(protocol_groups(dataset, Protocol::parse("loso")), dataset.subjects);
    EXPECT_TRUE(protocol_groups(dataset, Protocol::parse("kfold:3")).empty());
    const EvaluationResult by_subject =
        evaluate(dataset, specification, Protocol::parse("loso"), 3);
    for (const std::string& model : by_subject.fold_models)
      EXPECT_EQ(model.rfind("general/", 0), 0u) << subjects << " subjects: " << model;
    // Without groups held out, the personal column wins the inner folds.
    const EvaluationResult mixed = evaluate(dataset, specification, Protocol::parse("kfold:3"), 3);
    for (const std::string& model : mixed.fold_models)
      EXPECT_EQ(model.rfind("personal/", 0), 0u) << subjects << " subjects: " << model;
  }
}

TEST(StackBlocks, NeedTwoPipelinesEachSideBySide) {
  const auto columns = [](std::vector<std::string> names) {
    std::vector<FeatureColumn> result;
    for (std::string& name : names) result.push_back({std::move(name), ""});
    return result;
  };
  EXPECT_EQ(stack_blocks(columns({"a/x", "a/y", "b/x"})), "a:0-1|b:2-2");
  EXPECT_EQ(stack_blocks(columns({"a/x", "a/y"})), "");         // one pipeline
  EXPECT_EQ(stack_blocks(columns({"a/x", "b/x", "a/y"})), "");  // a apart
  EXPECT_EQ(stack_blocks(columns({"a/x", "plain"})), "");       // not every column stacked
}

TEST(StackExtractor, RefusesARepeatedOrUnknownPipelineAndParameters) {
  EXPECT_THROW(make_feature_extractor("generic+generic"), Error);
  EXPECT_THROW(make_feature_extractor("generic+no-such"), Error);
  EXPECT_THROW(make_feature_extractor("generic+"), Error);
  EXPECT_THROW(make_feature_extractor("generic+kaboli", Parameters::parse("threshold=0.1", "test")),
               Error);
  EXPECT_EQ(make_feature_extractor("generic+kaboli")->name(), "generic+kaboli");
}

}  // namespace
}  // namespace tactile::ml

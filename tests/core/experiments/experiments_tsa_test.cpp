// `tsa-classifiers` on a quick simulated corpus: Table 4's shape and figures.
#include <gtest/gtest.h>

#include "experiment_test_support.h"

namespace tactile::test {
namespace {

TEST(TsaClassifiersExperiment, QuickRunGivesTable4ForTenPresetsAboveChance) {
  int progress_calls = 0;
  const experiments::ExperimentReport report = run_quick("tsa-classifiers", &progress_calls);
  EXPECT_EQ(report.name, "tsa-classifiers");
  EXPECT_GT(progress_calls, 0);
  const experiments::ReportTable* table = find_table(report, "Table 4");
  ASSERT_NE(table, nullptr);
  ASSERT_EQ(table->rows.size(), 10u);
  EXPECT_EQ(table->rows[0][0], "Medium Tree");
  EXPECT_EQ(table->rows[9][0], "Subspace KNN");
  // classifier, T1..T6, mean ours, mean paper, accuracy
  EXPECT_EQ(table->columns.size(), 10u);
  EXPECT_EQ(table->rows[7][1].substr(table->rows[7][1].find('/')), "/ 100");  // Cosine KNN T1
  EXPECT_EQ(table->rows[4][8], "68.33");                                      // Quadratic SVM
  const auto& classifiers = report.json["tables"][0]["classifiers"];
  ASSERT_EQ(classifiers.size(), 10u);
  const double chance = 1.0 / 6.0;
  for (const auto& row : classifiers) {
    const double accuracy = row["accuracy"].get<double>();
    EXPECT_GE(accuracy, 0.0);
    EXPECT_LE(accuracy, 1.0);
    EXPECT_GT(row["paper_accuracy"].get<double>(), 0.6);
    EXPECT_EQ(row["confusion"].size(), 6u);
  }
  // The best preset is well above chance on six balanced classes.
  EXPECT_GT(report.json["accuracy"].get<double>(), 2.0 * chance);
  EXPECT_DOUBLE_EQ(report.json["paper_accuracy"].get<double>(), 0.6867);
}

}  // namespace
}  // namespace tactile::test

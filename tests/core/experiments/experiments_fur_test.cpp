// `fur-ml` on a quick simulated corpus: Table 1, SBS order, per-user and grouped rates.
#include <gtest/gtest.h>

#include <set>

#include "experiment_test_support.h"

namespace tactile::test {
namespace {

TEST(FurMlExperiment, QuickRunGivesTable1SbsOrderAndGroupedRates) {
  const experiments::ExperimentReport report = run_quick("fur-ml", nullptr);
  const experiments::ReportTable* matrix = find_table(report, "Table 1 (left)");
  ASSERT_NE(matrix, nullptr);
  ASSERT_EQ(matrix->rows.size(), 7u);  // six gestures and the accuracy row
  EXPECT_EQ(matrix->rows[0][0], "slap");
  EXPECT_EQ(matrix->rows[5][0], "push");
  EXPECT_EQ(matrix->rows[0].back(), "93.2");  // paper: 55 of 59 slaps
  EXPECT_EQ(matrix->rows[6].back(), "81.5");  // paper: 325 / 399

  // SBS order: every feature once.
  const auto& order = report.json["sbs_order"];
  ASSERT_EQ(order.size(), 15u);
  std::set<std::string> distinct;
  for (const auto& name : order) distinct.insert(name.get<std::string>());
  EXPECT_EQ(distinct.size(), 15u);

  const auto& tables = report.json["tables"];
  ASSERT_EQ(tables.size(), 4u);
  for (const auto& table : tables) {
    EXPECT_GE(table["accuracy"].get<double>(), 0.0);
    EXPECT_LE(table["accuracy"].get<double>(), 1.0);
    EXPECT_GT(table["paper_accuracy"].get<double>(), 0.8);
  }
  // Six classes, chance 1/6; four groups, chance at most the largest group (1/3).
  EXPECT_GT(report.json["accuracy"].get<double>(), 0.5);
  EXPECT_GT(tables[2]["accuracy"].get<double>(), 0.5);
  EXPECT_NEAR(report.json["paper_accuracy"].get<double>(), 0.8145, 1e-4);
}

}  // namespace
}  // namespace tactile::test

// `flux-som` on a quick simulated corpus: PCA components, the 7 x 7 region map, confusion.
#include <gtest/gtest.h>

#include "experiment_test_support.h"

namespace tactile::test {
namespace {

TEST(FluxSomExperiment, QuickRunGivesComponentsRegionMapAndConfusion) {
  const experiments::ExperimentReport report = run_quick("flux-som", nullptr);
  ASSERT_EQ(report.tables.size(), 3u);
  const experiments::ReportTable* regions = find_table(report, "Fig 8B");
  ASSERT_NE(regions, nullptr);
  EXPECT_EQ(regions->rows.size(), 7u);
  EXPECT_EQ(regions->columns.size(), 8u);
  const auto& tables = report.json["tables"];
  EXPECT_EQ(tables[0]["paper_components"].get<int>(), 8);
  const int components = tables[0]["components"].get<int>();
  const auto& cumulative = tables[0]["cumulative_ratio"];
  ASSERT_GE(cumulative.size(), static_cast<size_t>(components));
  // The smallest k reaching 90 %.
  EXPECT_GE(cumulative[components - 1].get<double>(), 0.9 - 1e-12);
  if (components > 1) {
    EXPECT_LT(cumulative[components - 2].get<double>(), 0.9);
  }
  EXPECT_EQ(tables[1]["neuron_class"].size(), 49u);
  const auto& confusion = tables[2]["confusion"];
  ASSERT_EQ(confusion.size(), 6u);
  int total = 0;
  for (const auto& row : confusion)
    for (const auto& cell : row) total += cell.get<int>();
  EXPECT_EQ(total, report.json["segments"].get<int>());  // one 5-fold pass in quick mode
  const double accuracy = report.json["accuracy"].get<double>();
  EXPECT_LE(accuracy, 1.0);
  EXPECT_GT(accuracy, 2.0 / 6.0);                        // six classes: twice chance
  EXPECT_TRUE(report.json["paper_accuracy"].is_null());  // the paper reports none
}

}  // namespace
}  // namespace tactile::test

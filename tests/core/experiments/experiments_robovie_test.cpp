// `robovie-clafic` on a quick simulated corpus: KNN and the six CLAFIC conditions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "experiment_test_support.h"

namespace tactile::test {
namespace {

TEST(RobovieClaficExperiment, QuickRunGivesSevenConditionsWithShrinkingSensorBanks) {
  const experiments::ExperimentReport report = run_quick("robovie-clafic", nullptr);
  const experiments::ReportTable* per_class = find_table(report, "per class");
  ASSERT_NE(per_class, nullptr);
  EXPECT_EQ(per_class->rows.size(), 15u);
  EXPECT_EQ(per_class->columns.size(), 8u);  // class, KNN, six CLAFIC conditions
  const auto& conditions = report.json["conditions"];
  ASSERT_EQ(conditions.size(), 7u);
  EXPECT_EQ(conditions[0]["title"], "KNN k=3");
  for (const auto& condition : conditions) {
    EXPECT_GE(condition["accuracy"].get<double>(), 0.0);
    EXPECT_LE(condition["accuracy"].get<double>(), 1.0);
    EXPECT_EQ(condition["recognition"].size(), 15u);
    EXPECT_FALSE(condition["paper"].get<std::string>().empty());
  }
  // The figure held against the paper's reading: recognition over the classes it names.
  EXPECT_EQ(conditions[0]["paper_classes"], nlohmann::json({2, 6, 7, 8, 11, 15}));
  double named = 0.0;
  for (const int k : {2, 6, 7, 8, 11, 15})
    named += conditions[0]["recognition"][static_cast<size_t>(k - 1)].get<double>() / 6.0;
  EXPECT_NEAR(conditions[0]["paper_classes_recognition"].get<double>(), named, 1e-12);
  EXPECT_TRUE(conditions[1]["paper_classes_recognition"].is_null());
  // C2 thresholds shrink the banks: (0.15, 2) uses less of the feature space than (0.15, 0).
  EXPECT_DOUBLE_EQ(conditions[4]["feature_fraction"].get<double>(), 1.0);
  EXPECT_LT(conditions[6]["feature_fraction"].get<double>(),
            conditions[5]["feature_fraction"].get<double>());
  EXPECT_LT(conditions[5]["feature_fraction"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(conditions[6]["paper_feature_fraction"].get<double>(), 0.05);
  // 15 classes: chance is 1/15; the best condition beats it clearly.
  EXPECT_GT(report.json["accuracy"].get<double>(), 2.0 / 15.0);
}

}  // namespace
}  // namespace tactile::test

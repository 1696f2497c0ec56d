// Each Kaboli experiment end to end on a quick simulated corpus: tables shaped like the paper's,
// accuracies that are fractions and clearly above the 1-in-9 chance of guessing, and the paper's
// figures beside ours.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io_test_files.h"
#include "tactile/experiments/kaboli.h"

namespace tactile::experiments {
namespace {

constexpr double kChance = 1.0 / 9.0;

class KaboliExperiments : public ::testing::Test {
 protected:
  // A folder of this process's own: another test run on the machine may run the same test.
  void SetUp() override { folder_ = directory_.path(); }
  ExperimentOptions options() const {
    ExperimentOptions options;
    options.work_dir = folder_.string();
    options.seed = 7;
    options.quick = true;
    return options;
  }
  tactile::testing::TemporaryDirectory directory_;
  std::filesystem::path folder_;
};

// A confusion table: nine class rows and an accuracy row whose last two cells are ours and the
// paper's.
void expect_confusion_table(const ReportTable& table, const std::string& paper_accuracy) {
  ASSERT_EQ(table.rows.size(), 10u) << table.title;
  EXPECT_EQ(table.rows.front().front(), "pat");
  EXPECT_EQ(table.rows[8].front(), "tickle");
  EXPECT_EQ(table.columns.back(), "paper %");
  EXPECT_EQ(table.rows.back().back(), paper_accuracy);
}

void expect_accuracy(const nlohmann::json& entry, double margin) {
  const double accuracy = entry.at("accuracy").get<double>();
  EXPECT_GE(accuracy, 0.0);
  EXPECT_LE(accuracy, 1.0);
  EXPECT_GT(accuracy, kChance + margin) << entry.dump();
  EXPECT_TRUE(entry.at("paper_accuracy").is_number()) << entry.dump();
}

TEST_F(KaboliExperiments, LocationTrainsOnTheBackAndRecognisesTouchesOnTheFront) {
  std::string stages;
  ExperimentOptions settings = options();
  settings.progress = [&](const std::string& stage, int, int) { stages += stage + ";"; };
  const ExperimentReport report = run_kaboli_location(settings);
  EXPECT_EQ(report.name, "kaboli-location");
  ASSERT_EQ(report.tables.size(), 1u);
  expect_confusion_table(report.tables[0], "96.79");
  EXPECT_DOUBLE_EQ(report.json.at("paper_accuracy").get<double>(), 0.9679);
  expect_accuracy(report.json, 0.25);
  // Every front touch is counted once: nine classes x 2 repetitions x 2 subjects, minus misses.
  int counted = 0;
  for (const auto& row : report.json.at("tables")[0].at("confusion"))
    for (const auto& cell : row) counted += cell.get<int>();
  EXPECT_GT(counted, 27);
  EXPECT_LE(counted, 36);
  EXPECT_NE(stages.find("simulate back-stationary"), std::string::npos);
  EXPECT_NE(stages.find("svm"), std::string::npos);
}

TEST_F(KaboliExperiments, MotionReportsTablesSixAndSeven) {
  const ExperimentReport report = run_kaboli_motion(options());
  ASSERT_EQ(report.tables.size(), 2u);
  expect_confusion_table(report.tables[0], "94.40");
  expect_confusion_table(report.tables[1], "92.52");
  // The simulated moving NAO shakes every accelerometer, so these are the hardest sets.
  for (const auto& entry : report.json.at("tables")) expect_accuracy(entry, 0.1);
}

TEST_F(KaboliExperiments, MultiTouchScoresEachBodyPartOnItsOwn) {
  const ExperimentReport report = run_kaboli_multitouch(options());
  ASSERT_EQ(report.tables.size(), 1u);
  expect_confusion_table(report.tables[0], "93.03");
  expect_accuracy(report.json, 0.15);
  // Both body parts of a trial are scored: more descriptors than multi-touch trials (9 pairs x
  // 2 repetitions x 2 subjects = 36).
  int counted = 0;
  for (const auto& row : report.json.at("tables")[0].at("confusion"))
    for (const auto& cell : row) counted += cell.get<int>();
  EXPECT_GT(counted, 36);
}

TEST_F(KaboliExperiments, EmMapsClustersToClassesInFourScenarios) {
  const ExperimentReport report = run_kaboli_em(options());
  ASSERT_EQ(report.tables.size(), 1u);
  const ReportTable& table = report.tables[0];
  ASSERT_EQ(table.rows.size(), 4u);
  EXPECT_EQ(table.rows[0][4], "81.83");
  EXPECT_EQ(table.rows[3][4], "80.10");
  // Unsupervised clusters on 4 touches per class: each scenario is a fraction, and over all
  // test segments the mapped clusters beat guessing.
  for (const auto& entry : report.json.at("tables")) {
    const double accuracy = entry.at("accuracy").get<double>();
    EXPECT_GE(accuracy, 0.0);
    EXPECT_LE(accuracy, 1.0);
    EXPECT_TRUE(entry.at("paper_accuracy").is_number());
    // The diagnostic beside it: EM started from the training classes, a real fit whose
    // likelihood is a finite (log-density, may be positive or negative) number per sample.
    const double from_classes = entry.at("from_classes_accuracy").get<double>();
    EXPECT_GE(from_classes, 0.0);
    EXPECT_LE(from_classes, 1.0);
    EXPECT_TRUE(std::isfinite(entry.at("log_likelihood_per_sample").get<double>()));
    EXPECT_TRUE(std::isfinite(entry.at("from_classes_log_likelihood_per_sample").get<double>()));
  }
  // The three scenarios trained on back-stationary share one fit per start.
  const auto& tables = report.json.at("tables");
  EXPECT_EQ(tables[0].at("from_classes_log_likelihood_per_sample"),
            tables[2].at("from_classes_log_likelihood_per_sample"));
  EXPECT_EQ(table.columns.size(), 8u);
  expect_accuracy(report.json, 0.05);
}

TEST_F(KaboliExperiments, CompareRunsFourFeatureSetsWithFourClassifiers) {
  const ExperimentReport report = run_kaboli_compare(options());
  ASSERT_EQ(report.tables.size(), 1u);
  const ReportTable& table = report.tables[0];
  ASSERT_EQ(table.rows.size(), 4u);
  ASSERT_EQ(table.columns.size(), 9u);
  EXPECT_EQ(table.rows[0][2], "60.40");  // Naya with K-NN in the paper
  EXPECT_EQ(table.rows[0][4], "-");      // not run in the paper
  EXPECT_EQ(table.rows[3][8], "96.75");
  ASSERT_EQ(report.json.at("tables").size(), 16u);
  for (const auto& entry : report.json.at("tables")) {
    const double accuracy = entry.at("accuracy").get<double>();
    EXPECT_GE(accuracy, 0.0);
    EXPECT_LE(accuracy, 1.0);
  }
  // The proposed descriptor with the SVM is the paper's headline; it must beat chance clearly.
  expect_accuracy(report.json, 0.25);
}

}  // namespace
}  // namespace tactile::experiments

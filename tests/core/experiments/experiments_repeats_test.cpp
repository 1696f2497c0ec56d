// Repeats of an experiment over consecutive seeds: the summary's figures against the runs'
// own, a report kept as JSON formatting as the report does, and the runs of a shard.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "experiment_test_support.h"
#include "tactile/error.h"
#include "tactile/experiments/repeats.h"

namespace tactile::test {
namespace {

using experiments::RepeatFigure;
using experiments::RepeatRun;

// A report as an experiment gives it: a headline and tables, one with rows of its own.
RepeatRun repeat_with(uint64_t seed, double headline, double first_table, double row) {
  RepeatRun run;
  run.seed = seed;
  run.report.name = "made-up";
  run.report.paper = "Someone et al., Table 1";
  run.report.tables.push_back({"Table 1: made up", {"class", "ours %"}, {{"a", "50.0"}}, "note"});
  run.report.json["accuracy"] = headline;
  run.report.json["paper_accuracy"] = 0.9;
  run.report.json["tables"] = nlohmann::json::array(
      {{{"title", "Table 1: made up"},
        {"accuracy", first_table},
        {"paper_accuracy", 0.8},
        {"classifiers", nlohmann::json::array({{{"classifier", "KNN"}, {"accuracy", row}}})}},
       {{"title", "not a figure"}, {"accuracy", nullptr}, {"paper_accuracy", nullptr}}});
  return run;
}

const RepeatFigure& figure_named(const std::vector<RepeatFigure>& figures, const std::string& table,
                                 const std::string& title) {
  for (const RepeatFigure& figure : figures)
    if (figure.table == table && figure.title == title) return figure;
  throw std::runtime_error("no figure " + table + " / " + title);
}

TEST(ExperimentRepeats, SummaryIsMeanSampleDeviationAndRangeOfTheRunsFigures) {
  const std::vector<RepeatRun> runs = {
      repeat_with(4, 0.5, 0.6, 0.25), repeat_with(5, 0.7, 0.6, 0.5), repeat_with(6, 0.9, 0.6, 1.0)};
  const std::vector<RepeatFigure> figures = experiments::summarise_repeats(runs);
  ASSERT_EQ(figures.size(), 3u);  // the null accuracy is no figure
  const RepeatFigure& headline = figure_named(figures, "headline", "accuracy");
  EXPECT_EQ(&headline, &figures.front());
  EXPECT_DOUBLE_EQ(headline.mean, 0.7);
  EXPECT_DOUBLE_EQ(headline.sd, 0.2);  // sqrt((0.04 + 0 + 0.04) / 2)
  EXPECT_DOUBLE_EQ(headline.min, 0.5);
  EXPECT_DOUBLE_EQ(headline.max, 0.9);
  EXPECT_EQ(headline.paper, 0.9);
  EXPECT_EQ(headline.values, (std::vector<double>{0.5, 0.7, 0.9}));
  const RepeatFigure& table = figure_named(figures, "Table 1: made up", "accuracy");
  EXPECT_DOUBLE_EQ(table.mean, 0.6);
  EXPECT_DOUBLE_EQ(table.sd, 0.0);
  EXPECT_EQ(table.paper, 0.8);
  const RepeatFigure& row = figure_named(figures, "Table 1: made up", "KNN");
  EXPECT_NEAR(row.mean, 1.75 / 3.0, 1e-15);
  EXPECT_NEAR(
      row.sd,
      std::sqrt(((0.25 - 1.75 / 3) * (0.25 - 1.75 / 3) + (0.5 - 1.75 / 3) * (0.5 - 1.75 / 3) +
                 (1.0 - 1.75 / 3) * (1.0 - 1.75 / 3)) /
                2.0),
      1e-15);
  EXPECT_FALSE(row.paper.has_value());
}

TEST(ExperimentRepeats, AllExperimentsTableListsTheFiguresThePaperGivesInPercent) {
  const std::vector<RepeatRun> runs = {
      repeat_with(4, 0.5, 0.6, 0.25), repeat_with(5, 0.7, 0.6, 0.5), repeat_with(6, 0.9, 0.6, 1.0)};
  // The row of classifier KNN has no paper figure: left out.
  const std::vector<experiments::PaperRow> rows = experiments::paper_rows("made-up", runs);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].experiment, "made-up");
  const std::string table = experiments::format_paper_rows(rows, 3);
  // Headline 70 % (sd 20) against 90 %: 20 points off, marked; the table's 60 % against 80 %.
  EXPECT_NE(table.find("| made-up | accuracy | 70.0 (20.0) | 90.0 | -20.0 ** |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| made-up | Table 1: made up: accuracy | 60.0 (0.0) | 80.0 | -20.0 ** |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("2 figures; 2 more than 5 points from the paper"), std::string::npos);
  // Within five points: not marked.
  const std::string close = experiments::format_paper_rows(
      experiments::paper_rows("close", {repeat_with(1, 0.88, 0.79, 0)}), 1);
  EXPECT_NE(close.find("| close | accuracy | 88.0 (0.0) | 90.0 | -2.0 |"), std::string::npos)
      << close;
  const nlohmann::json document = experiments::paper_rows_json(rows, 3);
  EXPECT_EQ(document["repeats"], 3);
  EXPECT_DOUBLE_EQ(document["figures"][0]["difference"].get<double>(), 0.7 - 0.9);
}

TEST(ExperimentRepeats, FigureMissingFromARunIsSummarisedOverTheRunsThatGiveIt) {
  std::vector<RepeatRun> runs = {repeat_with(1, 0.5, 0.6, 0.2), repeat_with(2, 0.7, 0.6, 0.4)};
  runs[1].report.json["accuracy"] = std::nan("");  // written as null: no figure
  const std::vector<RepeatFigure> figures = experiments::summarise_repeats(runs);
  const RepeatFigure& headline = figure_named(figures, "headline", "accuracy");
  EXPECT_EQ(headline.values, (std::vector<double>{0.5}));
  EXPECT_DOUBLE_EQ(headline.sd, 0.0);
  EXPECT_EQ(figure_named(figures, "Table 1: made up", "KNN").values.size(), 2u);
}

TEST(ExperimentRepeats, ReportKeptAsJsonFormatsAsTheReport) {
  const RepeatRun run = repeat_with(3, 0.5, 0.6, 0.2);
  const experiments::ExperimentReport back = experiments::report_from_json(
      nlohmann::json::parse(experiments::report_to_json(run.report).dump()));
  EXPECT_EQ(experiments::format_report(back), experiments::format_report(run.report));
  EXPECT_EQ(back.json, run.report.json);
  EXPECT_THROW(experiments::report_from_json({{"name", "x"}}), Error);
  const RepeatRun item = experiments::repeat_from_item(experiments::repeat_item(7, run));
  EXPECT_EQ(item.seed, 3u);
  EXPECT_EQ(experiments::format_report(item.report), experiments::format_report(run.report));
}

TEST(ExperimentRepeats, SeedsFollowTheFirstAndRepeatsBelowOneAreRefused) {
  experiments::RepeatsJob job{"tsa-classifiers", 9, 3, true};
  EXPECT_EQ(experiments::repeat_seeds(job), (std::vector<uint64_t>{9, 10, 11}));
  EXPECT_EQ(experiments::repeats_plan(job).back(), "tsa-classifiers#seed-11");
  EXPECT_EQ(experiments::repeat_work_dir("/w", 10),
            (std::filesystem::path("/w") / "seed-10").string());
  job.repeats = 0;
  EXPECT_THROW(experiments::repeat_seeds(job), Error);
}

// Each run is the experiment run alone with its seed, in its own folder, removed after it
// when asked; a shard runs only its seeds.
TEST(ExperimentRepeats, RunsAreTheExperimentWithEachSeedInItsOwnFolder) {
  ExperimentFolder folder;
  experiments::ExperimentOptions options;
  options.work_dir = folder.work_dir();
  const experiments::RepeatsJob job{"tsa-classifiers", 3, 2, true};
  const std::vector<RepeatRun> runs = experiments::run_repeats(job, options, {}, false);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].seed, 3u);
  EXPECT_EQ(runs[1].seed, 4u);
  EXPECT_TRUE(std::filesystem::exists(folder.work_dir() + "/seed-3/tsa/labels.db"));
  EXPECT_TRUE(std::filesystem::exists(folder.work_dir() + "/seed-4/tsa/labels.db"));
  EXPECT_NE(runs[0].report.json, runs[1].report.json);  // the seeds simulate different skins

  ExperimentFolder alone_folder;
  experiments::ExperimentOptions alone = options;
  alone.work_dir = alone_folder.work_dir();
  alone.seed = 4;
  alone.quick = true;
  EXPECT_EQ(experiments::run_experiment("tsa-classifiers", alone).json, runs[1].report.json);

  ExperimentFolder shard_folder;
  options.work_dir = shard_folder.work_dir();
  const std::vector<RepeatRun> second =
      experiments::run_repeats(job, options, Shard::parse("2/2"), true);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].seed, 4u);
  EXPECT_EQ(second[0].report.json, runs[1].report.json);
  EXPECT_FALSE(std::filesystem::exists(shard_folder.work_dir() + "/seed-4"));
}

}  // namespace
}  // namespace tactile::test

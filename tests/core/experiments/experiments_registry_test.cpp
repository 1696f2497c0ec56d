// The experiment registry and the text rendering of reports.
#include <gtest/gtest.h>

#include <algorithm>

#include "tactile/error.h"
#include "tactile/experiments/experiment.h"

namespace tactile::test {
namespace {

TEST(ExperimentRegistry, ListsEveryPapersExperiment) {
  const std::vector<std::string> names = experiments::experiment_names();
  EXPECT_EQ(names.size(), 9u);
  for (const char* name :
       {"kaboli-location", "kaboli-motion", "kaboli-multitouch", "kaboli-em", "kaboli-compare",
        "tsa-classifiers", "fur-ml", "robovie-clafic", "flux-som"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(ExperimentRegistry, UnknownNameErrorListsKnownOnes) {
  try {
    experiments::run_experiment("no-such-experiment", {});
    FAIL() << "no error";
  } catch (const Error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("no-such-experiment"), std::string::npos) << text;
    EXPECT_NE(text.find("fur-ml"), std::string::npos) << text;
    EXPECT_NE(text.find("flux-som"), std::string::npos) << text;
  }
}

TEST(ExperimentRegistry, FormatReportAlignsColumnsAndKeepsNotes) {
  experiments::ExperimentReport report;
  report.name = "demo";
  report.paper = "Paper, Table 9";
  experiments::ReportTable table;
  table.title = "Table 9: demo";
  table.columns = {"class", "ours %"};
  table.rows = {{"tap", "81.5"}, {"stroke-long", "7.0"}};
  table.note = "a note";
  report.tables.push_back(table);
  const std::string text = experiments::format_report(report);
  EXPECT_EQ(text,
            "demo (Paper, Table 9)\n"
            "\n"
            "Table 9: demo\n"
            "class       | ours %\n"
            "------------+-------\n"
            "tap         | 81.5\n"
            "stroke-long | 7.0\n"
            "a note\n");
}

}  // namespace
}  // namespace tactile::test

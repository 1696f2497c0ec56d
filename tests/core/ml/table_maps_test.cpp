// The table drawn as maps: its rows on two principal components, a SOM with each row's winner.
#include "tactile/ml/table_maps.h"

#include <gtest/gtest.h>

#include "tactile/jobs/job.h"

namespace tactile::ml {
namespace {

// Two classes apart on the first half of the features, noise elsewhere.
Dataset two_classes(int rows, int columns) {
  Dataset table;
  table.features = Matrix::Random(rows, columns) * 0.1;
  for (int row = 0; row < rows; ++row) {
    const bool second = row % 2 == 1;
    table.features.row(row).head(columns / 2).array() += second ? 3.0 : 0.0;
    table.classes.push_back(second ? "slap" : "pat");
  }
  return table;
}

TEST(TableMaps, TheScatterSeparatesWhatTheFirstComponentSeparates) {
  const Dataset table = two_classes(20, 40);  // fewer rows than columns, as the workbench meets
  double last = -1.0;
  const TableScatter scatter =
      scatter_of(table.features, [&](double fraction) { last = fraction; });
  ASSERT_EQ(scatter.points.rows(), 20);
  ASSERT_EQ(scatter.points.cols(), 2);
  EXPECT_GT(scatter.explained, 0.0);
  EXPECT_LE(scatter.explained, 1.0 + 1e-12);
  EXPECT_GT(last, 0.0);
  for (int row = 2; row < 20; ++row)  // the classes on either side of zero on the first axis
    EXPECT_EQ(scatter.points(row, 0) > 0, scatter.points(row % 2, 0) > 0) << row;
  EXPECT_EQ(scatter_of(table.features.leftCols(1)).points.col(1).norm(), 0.0);
}

TEST(TableMaps, TheSomGivesEveryRowAWinnerAndStopsWhenCancelled) {
  const Dataset table = two_classes(30, 5);
  const TableSom fit = som_of(table);
  ASSERT_TRUE(fit.som);
  EXPECT_EQ(fit.classes, (std::vector<std::string>{"pat", "slap"}));
  ASSERT_EQ(fit.winners.size(), 30u);
  EXPECT_EQ(som_winners(*fit.som, table.features), fit.winners);
  EXPECT_TRUE(som_winners(*fit.som, table.features.leftCols(4)).empty());  // another table
  JobProgress progress;
  progress.cancel();
  EXPECT_THROW(som_of(table, [&](double) { progress.check(); }), JobCancelled);
}

}  // namespace
}  // namespace tactile::ml

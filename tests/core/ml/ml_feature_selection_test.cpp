#include <gtest/gtest.h>

#include <random>

#include "ml_prob_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/feature_selection.h"
#include "tactile/ml/gaussian.h"

namespace tactile::ml {
namespace {

SubsetCriterion weighted_sum(std::vector<double> weights) {
  return [weights](const std::vector<int>& features) {
    double sum = 0.0;
    for (int feature : features) sum += weights[static_cast<size_t>(feature)];
    return sum;
  };
}

TEST(SequentialBackwardSelection, RemovesTheLeastUsefulFeatureEachRound) {
  const BackwardSelection selection =
      sequential_backward_selection(4, weighted_sum({0.5, 0.1, 0.3, 0.2}));
  EXPECT_EQ(selection.removed, (std::vector<int>{1, 3, 2}));
  EXPECT_EQ(selection.order, (std::vector<int>{0, 2, 3, 1}));
  ASSERT_EQ(selection.rate.size(), 4u);
  EXPECT_NEAR(selection.rate[0], 0.5, 1e-12);  // feature 0 alone
  EXPECT_NEAR(selection.rate[1], 0.8, 1e-12);  // {0, 2}
  EXPECT_NEAR(selection.rate[2], 1.0, 1e-12);  // {0, 2, 3}
  EXPECT_NEAR(selection.rate[3], 1.1, 1e-12);  // all
}

TEST(SequentialBackwardSelection, TiesRemoveTheHighestIndex) {
  const BackwardSelection selection =
      sequential_backward_selection(4, [](const std::vector<int>&) { return 0.7; });
  EXPECT_EQ(selection.removed, (std::vector<int>{3, 2, 1}));
  EXPECT_EQ(selection.order, (std::vector<int>{0, 1, 2, 3}));
}

TEST(SequentialBackwardSelection, KeepsAPairThatIsOnlyUsefulTogether) {
  // Features 1 and 2 are worthless alone and decisive together; feature 0 is mildly useful.
  const SubsetCriterion criterion = [](const std::vector<int>& features) {
    const auto has = [&](int f) {
      return std::find(features.begin(), features.end(), f) != features.end();
    };
    return (has(1) && has(2) ? 0.9 : 0.0) + (has(0) ? 0.05 : 0.0);
  };
  const BackwardSelection selection = sequential_backward_selection(3, criterion);
  EXPECT_EQ(selection.removed.front(), 0);
  const std::vector<FeatureRank> ranking = individual_ranking(3, criterion);
  EXPECT_EQ(ranking[0].feature, 0);
  EXPECT_EQ(ranking[1].feature, 1);  // tie with feature 2: lower index first
  EXPECT_EQ(ranking[2].feature, 2);
  EXPECT_THROW(sequential_backward_selection(0, criterion), Error);
}

TEST(LeaveOneOut, CountsEachHeldOutSampleOnce) {
  // The sample 0.15 labelled 1 sits inside class 0: held out it is misclassified; every
  // other sample is right.
  Matrix x(8, 1);
  x << 0, 0.1, 0.2, 0.3, 5, 5.1, 5.2, 0.15;
  const std::vector<int> y = {0, 0, 0, 0, 1, 1, 1, 1};
  const double accuracy = leave_one_out_accuracy(
      x, y, 2, {0}, [] { return std::make_unique<GaussianMaximumLikelihood>(); });
  EXPECT_DOUBLE_EQ(accuracy, 7.0 / 8.0);
  EXPECT_THROW(leave_one_out_accuracy(x, y, 2, {1},
                                      [] { return std::make_unique<GaussianMaximumLikelihood>(); }),
               Error);
}

TEST(SequentialBackwardSelection, GaussianLeaveOneOutPutsTheInformativeFeatureFirst) {
  std::mt19937_64 random(12);
  const int per_class = 15;
  Matrix x(3 * per_class, 4);
  std::vector<int> y;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < per_class; ++i) {
      const Eigen::Index row = k * per_class + i;
      x(row, 0) = test_data::standard_normal(random);                  // noise
      x(row, 1) = 4.0 * k + 0.5 * test_data::standard_normal(random);  // separates the classes
      x(row, 2) = test_data::standard_normal(random);                  // noise
      x(row, 3) = test_data::standard_normal(random);                  // noise
      y.push_back(k);
    }
  const SubsetCriterion criterion = gaussian_ml_leave_one_out(x, y, 3);
  const BackwardSelection selection = sequential_backward_selection(4, criterion);
  EXPECT_EQ(selection.order.front(), 1);
  EXPECT_GE(selection.rate[0], 0.95);
  const std::vector<FeatureRank> ranking = individual_ranking(4, criterion);
  EXPECT_EQ(ranking.front().feature, 1);
  EXPECT_LT(ranking.back().rate, 0.7);
}

}  // namespace
}  // namespace tactile::ml

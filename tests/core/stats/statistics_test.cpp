// Spec test vectors K1-K3 (TEST_VECTORS.md) and the §0 conventions.
#include "tactile/stats/statistics.h"

#include <gtest/gtest.h>

namespace tactile::stats {
namespace {

using Vector = std::vector<double>;

TEST(Hjorth, MatchesVectorK1) {
  const Vector x = {1, 3, 2, 5, 4, 6, 3, 2};
  EXPECT_EQ(diff(x), (Vector{2, -1, 3, -1, 2, -3, -1}));
  const Hjorth h = hjorth(x);
  EXPECT_NEAR(h.activity, 2.4375, 1e-12);
  EXPECT_NEAR(variance(diff(x)), 4.12245, 1e-5);
  EXPECT_NEAR(variance(diff(diff(x))), 12.9167, 1e-4);
  EXPECT_NEAR(h.mobility, 1.30048, 1e-5);
  EXPECT_NEAR(h.complexity, 1.36111, 1e-5);
  EXPECT_NEAR(h.mobility * 250.0, 325.121, 1e-3);
}

TEST(Hjorth, DegenerateSignalsGiveZerosNotNaN) {
  const Hjorth constant = hjorth(Vector{4, 4, 4, 4});
  EXPECT_EQ(constant.activity, 0.0);
  EXPECT_EQ(constant.mobility, 0.0);
  EXPECT_EQ(constant.complexity, 0.0);
  const Hjorth single = hjorth(Vector{7});
  EXPECT_EQ(single.activity, 0.0);
  EXPECT_EQ(single.mobility, 0.0);
  const Hjorth ramp = hjorth(Vector{1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(ramp.activity, 1.25);
  // dx is constant: Act(dx) = 0, so Mob = 0 and Comp = 0.
  EXPECT_EQ(ramp.mobility, 0.0);
  EXPECT_EQ(ramp.complexity, 0.0);
}

TEST(Pearson, MatchesVectorK2AndZeroVarianceIsZero) {
  EXPECT_NEAR(pearson(Vector{1, 2, 3, 4, 5}, Vector{2, 1, 4, 3, 5}), 0.8, 1e-12);
  EXPECT_EQ(pearson(Vector{1, 2, 3, 4, 5}, Vector{3, 3, 3, 3, 3}), 0.0);
  EXPECT_EQ(pearson(Vector{1}, Vector{2}), 0.0);
}

TEST(Spearman, TiesGetAverageRanksAsInVectorK3) {
  const Vector x = {1, 2, 2, 3, 5, 5, 5, 8};
  const Vector y = {2, 1, 3, 3, 4, 6, 5, 7};
  EXPECT_EQ(rank(x), (Vector{1, 2.5, 2.5, 4, 6, 6, 6, 8}));
  EXPECT_EQ(rank(y), (Vector{2, 1, 3.5, 3.5, 5, 7, 6, 8}));
  EXPECT_NEAR(spearman(x, y), 0.920034, 1e-6);
  EXPECT_NEAR(spearman_eq6(x, y), 0.922619, 1e-6);
  EXPECT_NEAR(spearman(Vector{10, 20, 30, 40, 50}, Vector{1, 3, 2, 5, 4}), 0.8, 1e-12);
  EXPECT_NEAR(spearman_eq6(Vector{10, 20, 30, 40, 50}, Vector{1, 3, 2, 5, 4}), 0.8, 1e-12);
}

TEST(DescriptiveStatistics, FollowSpecConventions) {
  EXPECT_EQ(mean(Vector{}), 0.0);
  EXPECT_EQ(variance(Vector{}), 0.0);
  EXPECT_EQ(sample_std(Vector{3}), 0.0);
  EXPECT_NEAR(sample_std(Vector{1, 2, 3, 4}), std::sqrt(1.25 * 4 / 3), 1e-12);
  EXPECT_EQ(argmax(Vector{1, 5, 5, 2}), 1);
  EXPECT_EQ(argmin(Vector{3, 1, 1}), 1);
  EXPECT_TRUE(is_zero_variance(0.0, Vector{2, 2}));
  EXPECT_FALSE(is_zero_variance(0.25, Vector{1, 2}));
}

TEST(Median, IsTheMiddleValueOrTheMeanOfTheTwoMiddleValues) {
  EXPECT_EQ(median(Vector{}), 0.0);
  EXPECT_EQ(median(Vector{7, 1, 4}), 4.0);
  EXPECT_EQ(median(Vector{8, 1, 2, 4}), 3.0);
  EXPECT_EQ(median(std::vector<float>{0.5f, -1.0f, 3.0f, 2.0f}), 1.25f);
  EXPECT_EQ(median(std::vector<float>{}), 0.0f);
}

TEST(NthSmallest, GivesTheValueSortingPutsAtTheIndex) {
  Vector values{5, 3, 9, 1, 7};
  EXPECT_EQ(nth_smallest(values, 0), 1.0);
  EXPECT_EQ(nth_smallest(values, 4), 9.0);
  EXPECT_EQ(nth_smallest(values, 1), 3.0);
  std::vector<float> floats{2.5f, -1.0f, 0.0f};
  EXPECT_EQ(nth_smallest(floats, 2), 2.5f);
}

}  // namespace
}  // namespace tactile::stats

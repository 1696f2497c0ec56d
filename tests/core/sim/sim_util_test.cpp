#include "tactile/sim/sim_util.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tactile/sim/simulator.h"

namespace tactile::sim {
namespace {

TEST(SimRandom, SameSeedAndPurposeGiveTheSameDraws) {
  Random a(derive_engine(7, "nao", 1, 2));
  Random b(derive_engine(7, "nao", 1, 2));
  Random c(derive_engine(7, "nao", 1, 3));
  bool differs = false;
  for (int k = 0; k < 100; ++k) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    differs |= x != c.normal();
  }
  EXPECT_TRUE(differs);
}

TEST(SimRandom, NormalDrawsHaveTheAskedMeanAndSpread) {
  Random random(derive_engine(1, "moments"));
  double sum = 0.0, squares = 0.0;
  const int count = 200000;
  for (int k = 0; k < count; ++k) {
    const double x = random.normal(3.0, 2.0);
    sum += x;
    squares += x * x;
  }
  const double mean = sum / count;
  EXPECT_NEAR(mean, 3.0, 0.02);
  EXPECT_NEAR(std::sqrt(squares / count - mean * mean), 2.0, 0.02);
}

TEST(SimRandom, IntegersCoverTheirInclusiveRange) {
  Random random(derive_engine(1, "integers"));
  int seen[4] = {};
  for (int k = 0; k < 4000; ++k) {
    const int64_t value = random.integer(2, 5);
    ASSERT_GE(value, 2);
    ASSERT_LE(value, 5);
    ++seen[value - 2];
  }
  for (int count : seen) EXPECT_GT(count, 800);
}

TEST(SimRandom, WeightedDrawsFollowTheWeightsAndNeverPickAZeroWeight) {
  Random random(derive_engine(1, "weighted"));
  const std::vector<double> weights = {3.0, 0.0, 1.0};
  int seen[3] = {};
  for (int k = 0; k < 8000; ++k) ++seen[random.weighted(weights)];
  EXPECT_EQ(seen[1], 0);
  EXPECT_NEAR(seen[0] / 8000.0, 0.75, 0.03);
  EXPECT_NEAR(seen[2] / 8000.0, 0.25, 0.03);
  EXPECT_EQ(random.weighted({0.0, 0.0, 2.0}), 2);
}

TEST(SimQuantize, SaturatesAndRoundsToAdcLevels) {
  EXPECT_FLOAT_EQ(quantize(5.0, 0.0, 3.0, 12), 3.0f);
  EXPECT_FLOAT_EQ(quantize(-1.0, 0.0, 3.0, 12), 0.0f);
  // 2 bits over [0, 3]: levels 0, 1, 2, 3.
  EXPECT_FLOAT_EQ(quantize(1.4, 0.0, 3.0, 2), 1.0f);
  EXPECT_FLOAT_EQ(quantize(1.6, 0.0, 3.0, 2), 2.0f);
}

TEST(SimEnvelope, RisesHoldsAndFalls) {
  EXPECT_DOUBLE_EQ(contact_envelope(0.9, 1.0, 2.0, 0.2, 0.4), 0.0);
  EXPECT_NEAR(contact_envelope(1.1, 1.0, 2.0, 0.2, 0.4), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(contact_envelope(2.0, 1.0, 2.0, 0.2, 0.4), 1.0);
  EXPECT_NEAR(contact_envelope(2.8, 1.0, 2.0, 0.2, 0.4), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(contact_envelope(3.0, 1.0, 2.0, 0.2, 0.4), 0.0);
}

TEST(SimClasses, EveryClassAppearsItsRepetitionsAndNeverTwiceInARow) {
  Random random(derive_engine(3, "order"));
  const std::vector<int> order = shuffled_classes(6, 5, random);
  ASSERT_EQ(order.size(), 30u);
  int counts[6] = {};
  for (size_t k = 0; k < order.size(); ++k) {
    ++counts[order[k]];
    if (k > 0) {
      EXPECT_NE(order[k], order[k - 1]);
    }
  }
  for (int count : counts) EXPECT_EQ(count, 5);
}

}  // namespace
}  // namespace tactile::sim

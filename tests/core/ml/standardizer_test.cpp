#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tactile/ml/classifier.h"

namespace tactile::ml {
namespace {

TEST(Standardizer, UsesSampleStdOfTheTrainingDataOnly) {
  Matrix train(4, 2);
  train << 1, 5, 2, 5, 3, 5, 4, 5;
  Standardizer standardizer;
  standardizer.fit(train);
  EXPECT_DOUBLE_EQ(standardizer.mean(0), 2.5);
  EXPECT_NEAR(standardizer.scale(0), std::sqrt(5.0 / 3.0), 1e-12);
  // A constant training column is only centred (spec §6.4: s = 0 -> z = x - mean).
  EXPECT_DOUBLE_EQ(standardizer.scale(1), 1.0);
  Matrix test(1, 2);
  test << 2.5, 7;
  const Matrix z = standardizer.transform(test);
  EXPECT_DOUBLE_EQ(z(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(z(0, 1), 2.0);
  Standardizer restored;
  restored.load(standardizer.save());
  EXPECT_EQ(restored.transform(test), z);
}

}  // namespace
}  // namespace tactile::ml

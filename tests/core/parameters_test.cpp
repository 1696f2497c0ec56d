#include <gtest/gtest.h>

#include "tactile/error.h"
#include "tactile/parameters.h"

namespace tactile {
namespace {

TEST(Parameters, ParsesTypedValuesAndFallsBackWhenAbsent) {
  const Parameters parameters = Parameters::parse("k=3, metric=cosine,c=0.5,standardize=false", "--classifier");
  EXPECT_EQ(parameters.integer("k", 1), 3);
  EXPECT_EQ(parameters.text("metric", "euclidean"), "cosine");
  EXPECT_DOUBLE_EQ(parameters.number("c", 1.0), 0.5);
  EXPECT_FALSE(parameters.flag("standardize", true));
  EXPECT_DOUBLE_EQ(parameters.number("gamma", 2.0), 2.0);
  EXPECT_TRUE(Parameters::parse("", "x").values().empty());
}

TEST(Parameters, BadValuesNameTheKeyAndTheSource) {
  const Parameters parameters = Parameters::parse("k=three,c=nan", "--classifier knn");
  try {
    parameters.integer("k", 1);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "--classifier knn");
    EXPECT_NE(error.message().find("k=three"), std::string::npos);
  }
  EXPECT_THROW(parameters.number("c", 1.0), Error);
  EXPECT_THROW(Parameters::parse("k", "x"), Error);
  EXPECT_THROW(Parameters::parse("k=1,k=2", "x"), Error);
}

TEST(Parameters, UnknownKeysAreRefusedWithTheKnownOnesListed) {
  const Parameters parameters = Parameters::parse("kk=3", "--classifier knn");
  try {
    parameters.expect_only({"k", "metric"});
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("'kk'"), std::string::npos);
    EXPECT_NE(error.message().find("k, metric"), std::string::npos);
  }
}

}  // namespace
}  // namespace tactile

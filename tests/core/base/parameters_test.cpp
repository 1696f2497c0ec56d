#include "tactile/parameters.h"

#include <gtest/gtest.h>

#include <map>

#include "tactile/error.h"

namespace tactile {
namespace {

TEST(Parameters, ParsesTypedValuesAndFallsBackWhenAbsent) {
  const Parameters parameters =
      Parameters::parse("k=3, metric=cosine,c=0.5,standardize=false", "--classifier");
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

TEST(Parameters, EveryGetterLeavesTheValueItAnswered) {
  const Parameters parameters = Parameters::parse("k=3,metric=cosine,flag=yes", "x");
  EXPECT_EQ(parameters.integer("k", 1), 3);
  EXPECT_EQ(parameters.text("metric", "euclidean"), "cosine");
  EXPECT_TRUE(parameters.flag("flag", false));
  EXPECT_EQ(parameters.number("c", 0.1), 0.1);  // defaulted
  EXPECT_EQ(parameters.integer("n", -7), -7);
  EXPECT_FALSE(parameters.flag("off", false));
  EXPECT_EQ(parameters.text("name", ""), "");
  const std::map<std::string, std::string> expected = {
      {"k", "3"},  {"metric", "cosine"}, {"flag", "true"}, {"c", "0.1"},
      {"n", "-7"}, {"off", "false"},     {"name", ""}};
  EXPECT_EQ(parameters.answered(), expected);
  EXPECT_EQ(parameters.answered_text(), "c=0.1,flag=true,k=3,metric=cosine,n=-7,name=,off=false");
  // Read back, the text gives the same answers, numbers to the last bit.
  const Parameters again = Parameters::parse(parameters.answered_text(), "y");
  EXPECT_EQ(again.number("c", 5.0), 0.1);
  EXPECT_EQ(again.text("name", "other"), "");
  const Parameters third = Parameters::parse("", "z");
  EXPECT_EQ(third.number("x", 1.0 / 3.0), 1.0 / 3.0);
  EXPECT_EQ(Parameters::parse(third.answered_text(), "z").number("x", 0.0), 1.0 / 3.0);
}

}  // namespace
}  // namespace tactile

#include "tactile/text.h"

#include <gtest/gtest.h>

#include <limits>

namespace tactile {
namespace {

TEST(SecondsText, PrintsATimeToTheMicrosecondInItsShortestForm) {
  EXPECT_EQ(seconds_text(4.4639999999999995), "4.464");
  EXPECT_EQ(seconds_text(1.5), "1.5");
  EXPECT_EQ(seconds_text(0.1 + 0.2), "0.3");
  EXPECT_EQ(seconds_text(12.0000004), "12");
  EXPECT_EQ(seconds_text(0.000001), "1e-06");
  EXPECT_EQ(seconds_text(-0.0000004), "0");
  EXPECT_EQ(seconds_text(3600.25), "3600.25");
}

TEST(Joined, PutsTheSeparatorBetweenItemsOnly) {
  EXPECT_EQ(joined({}), "");
  EXPECT_EQ(joined({"nao"}), "nao");
  EXPECT_EQ(joined({"a", "b", "c"}), "a, b, c");
  EXPECT_EQ(joined({"a", "b"}, " | "), "a | b");
}

}  // namespace
}  // namespace tactile

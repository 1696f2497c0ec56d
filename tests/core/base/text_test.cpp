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

TEST(PrintableText, EscapesControlBytesAndBrokenUtf8AndKeepsTheRest) {
  // The damaged signal count of an EDF header (issue 44): a NUL in the middle must not cut it.
  EXPECT_EQ(printable_text(std::string("\xfe\xff\x00\x18", 4)), "\\xFE\\xFF\\x00\\x18");
  EXPECT_EQ(printable_text("Fz 12"), "Fz 12");
  EXPECT_EQ(printable_text("tab\there\x7f"), "tab\\x09here\\x7F");
  EXPECT_EQ(printable_text("M\xc3\xbcller"), "M\xc3\xbcller") << "whole UTF-8 stays";
  EXPECT_EQ(printable_text("\xc3"), "\\xC3") << "a lead byte without its follower";
  EXPECT_EQ(printable_text("\xc0\xaf"), "\\xC0\\xAF") << "an overlong form";
  EXPECT_EQ(printable_text("\xed\xa0\x80"), "\\xED\\xA0\\x80") << "a surrogate";
}

TEST(Joined, PutsTheSeparatorBetweenItemsOnly) {
  EXPECT_EQ(joined({}), "");
  EXPECT_EQ(joined({"nao"}), "nao");
  EXPECT_EQ(joined({"a", "b", "c"}), "a, b, c");
  EXPECT_EQ(joined({"a", "b"}, " | "), "a | b");
}

}  // namespace
}  // namespace tactile

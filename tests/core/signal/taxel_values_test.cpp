#include "tactile/signal/taxel_values.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tactile {
namespace {

SkinLayout two_taxels_two_modalities() {
  SkinLayout layout;
  layout.id = "test";
  layout.modalities = {"force", "proximity"};
  layout.channels = {
      {"a.force", "N", "force"}, {"a.prox", "mm", "proximity"}, {"b.force", "N", "force"}};
  Taxel a;
  a.id = 1;
  a.channels = {0, 1};
  Taxel b;
  b.id = 2;
  b.channels = {2, -1};
  layout.taxels = {a, b};
  return layout;
}

TEST(TaxelValues, ColumnsAreMatchedByChannelNameNotPosition) {
  const SkinLayout layout = two_taxels_two_modalities();
  // The stream carries the channels in another order than the layout.
  const std::vector<std::string> stream_channels = {"b.force", "a.prox", "a.force"};
  EXPECT_EQ(taxel_columns(layout, stream_channels, 0), (std::vector<int>{2, 0}));
  EXPECT_EQ(taxel_columns(layout, stream_channels, 1), (std::vector<int>{1, -1}));
}

TEST(TaxelValues, TaxelWithoutTheModalityIsNaN) {
  const SkinLayout layout = two_taxels_two_modalities();
  Stream stream;
  stream.channels = {"a.force", "a.prox", "b.force"};
  stream.samples.resize(2, 3);
  stream.samples << 1, 2, 3, 4, 5, 6;
  const std::vector<float> values =
      taxel_values(stream, taxel_columns(layout, stream.channels, 1), 1);
  EXPECT_FLOAT_EQ(values[0], 5.0f);
  EXPECT_TRUE(std::isnan(values[1]));
  const std::vector<float> forces =
      taxel_values(stream, taxel_columns(layout, stream.channels, 0), 0);
  EXPECT_FLOAT_EQ(forces[0], 1.0f);
  EXPECT_FLOAT_EQ(forces[1], 3.0f);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

TEST(TaxelValuesOfAnInstant, PickEachTaxelsChannelAndNaNWhereThereIsNone) {
  const std::vector<float> channels = {10.0f, 11.0f, 12.0f};
  const std::vector<float> values = taxel_values(channels, {2, -1, 0, 7});
  EXPECT_EQ(values[0], 12.0f);
  EXPECT_TRUE(std::isnan(values[1]));
  EXPECT_EQ(values[2], 10.0f);
  EXPECT_TRUE(std::isnan(values[3]));  // a column beyond the channels given
}

}  // namespace
}  // namespace tactile

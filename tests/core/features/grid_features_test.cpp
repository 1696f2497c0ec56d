// The whole-grid descriptor set: the same row wherever a touch lands, orientation the only
// column a rotation moves, the same columns for every grid size; generic's choice of block.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tactile/error.h"
#include "tactile/features/generic.h"
#include "tactile/features/grid.h"

namespace tactile {
namespace {

constexpr double kRate = 25.0;
constexpr int64_t kFrames = 60;

// Uncalibrated rest levels, different per taxel.
Recording resting_grid(const SkinLayout& layout) {
  Recording recording;
  recording.id = "hand-built";
  recording.layout_id = layout.id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = kRate;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples.resize(kFrames, static_cast<int64_t>(layout.channels.size()));
  for (int64_t taxel = 0; taxel < stream.samples.cols(); ++taxel)
    stream.samples.col(taxel).setConstant(static_cast<float>(100 + (taxel * 37) % 61));
  recording.streams.push_back(std::move(stream));
  return recording;
}

// An elliptic patch (semi-axes 2.5 and 1.2 taxels, long axis at `angle`) pressing from frame
// 10 to 30, moving 4 taxels along its long axis, starting at (row, column); compact, so a
// shifted touch inside the grid is the same touch. With `transpose`, rows and columns swap.
void stroke(Recording& recording, int64_t columns, double row, double column, double angle,
            bool transpose = false) {
  SampleMatrix& samples = recording.streams[0].samples;
  const int64_t rows = samples.cols() / columns;
  for (int64_t frame = 10; frame < 30; ++frame) {
    const double progress = static_cast<double>(frame - 10) / 19.0;
    const double force = 200.0 * std::sin(std::numbers::pi * (frame - 9) / 21.0);
    const double centre_row = row + 4.0 * progress * std::sin(angle);
    const double centre_column = column + 4.0 * progress * std::cos(angle);
    for (int64_t r = 0; r < rows; ++r)
      for (int64_t c = 0; c < columns; ++c) {
        const double dr = static_cast<double>(r) - centre_row,
                     dc = static_cast<double>(c) - centre_column;
        const double along = dc * std::cos(angle) + dr * std::sin(angle);
        const double across = -dc * std::sin(angle) + dr * std::cos(angle);
        const double q = along * along / 6.25 + across * across / 1.44;
        if (q >= 1.0) continue;
        const int64_t taxel = transpose ? c * columns + r : r * columns + c;
        samples(frame, taxel) += static_cast<float>(std::round(force * (1.0 - q)));
      }
  }
}

std::vector<double> grid_row_of(const FeatureExtractor& extractor, const Recording& recording,
                                const SkinLayout& layout) {
  Label label;
  label.recording = recording.id;
  label.t0 = 8.0 / kRate;
  label.t1 = 32.0 / kRate;
  const Recording prepared = extractor.preprocess(recording, layout);
  const FeatureResult result = extractor.extract(SegmentInput{prepared, layout, label});
  EXPECT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  return result.values;
}

TEST(GridFeatures, TheSameTouchShiftedOnTheGridGivesTheSameRow) {
  const SkinLayout layout = make_grid_layout(16, 16);
  const auto extractor = make_grid_extractor({});
  Recording here = resting_grid(layout), there = resting_grid(layout);
  stroke(here, 16, 3.0, 2.0, 0.5);
  stroke(there, 16, 9.0, 7.0, 0.5);
  const std::vector<double> a = grid_row_of(*extractor, here, layout),
                            b = grid_row_of(*extractor, there, layout);
  const std::vector<FeatureColumn> columns = extractor->columns(layout);
  ASSERT_EQ(a.size(), columns.size());
  ASSERT_EQ(b.size(), columns.size());
  for (size_t k = 0; k < a.size(); ++k)
    EXPECT_NEAR(a[k], b[k], 1e-9 * std::max(1.0, std::abs(a[k]))) << columns[k].name;
  // A touch, not nothing: it moved, lengthwise, over a region longer than wide.
  auto value = [&](const std::string& name) {
    for (size_t k = 0; k < columns.size(); ++k)
      if (columns[k].name == name) return a[k];
    ADD_FAILURE() << name;
    return 0.0;
  };
  EXPECT_NEAR(value("grid.displacement"), 40.0, 8.0);  // 4 taxels at 10 mm
  EXPECT_GT(value("grid.alignment"), 0.9);
  EXPECT_GT(value("grid.eccentricity_mean"), 0.7);
  EXPECT_NEAR(value("grid.orientation_mean"), 0.5, 0.1);
  EXPECT_EQ(value("grid.blobs_max"), 1.0);
}

TEST(GridFeatures, ARotatedStrokeChangesItsOrientationOnly) {
  const SkinLayout layout = make_grid_layout(16, 16);
  const auto extractor = make_grid_extractor({});
  Recording straight = resting_grid(layout), turned = resting_grid(layout);
  stroke(straight, 16, 4.0, 3.0, 0.4);
  stroke(turned, 16, 4.0, 3.0, 0.4,
         true);  // mirrored about the diagonal: a quarter turn of the axis
  const std::vector<double> a = grid_row_of(*extractor, straight, layout),
                            b = grid_row_of(*extractor, turned, layout);
  const std::vector<FeatureColumn> columns = extractor->columns(layout);
  for (size_t k = 0; k < a.size(); ++k) {
    if (columns[k].name == "grid.orientation_mean") {
      EXPECT_NEAR(a[k], 0.4, 0.1);
      EXPECT_NEAR(b[k], std::numbers::pi / 2 - a[k], 1e-9);
    } else {
      EXPECT_NEAR(a[k], b[k], 1e-9 * std::max(1.0, std::abs(a[k]))) << columns[k].name;
    }
  }
}

TEST(GridFeatures, EveryGridSizeGivesTheSameColumns) {
  const auto extractor = make_grid_extractor({});
  const std::vector<FeatureColumn> small = extractor->columns(make_grid_layout(4, 5));
  EXPECT_EQ(small.size(), kGridColumnCount);
  for (const SkinLayout& layout :
       {make_grid_layout(16, 16), make_grid_layout(19, 27), make_grid_layout(64, 64)}) {
    const std::vector<FeatureColumn> columns = extractor->columns(layout);
    ASSERT_EQ(columns.size(), small.size()) << layout.id;
    for (size_t k = 0; k < columns.size(); ++k) EXPECT_EQ(columns[k].name, small[k].name);
  }
  EXPECT_THROW(extractor->columns(make_strip_layout(8)), Error);  // no 2-D map
  EXPECT_THROW(make_grid_extractor(Parameters::parse("threshold=0", "--params")), Error);
}

// With share=0.5 the pressed region is where the touch presses at least half as hard as its
// hardest point in the segment: a weak skirt around a firm press is not its area. By default
// (share=0) every taxel past the noise is.
TEST(GridFeatures, TheContactRegionIsWhereTheTouchPressesAtLeastHalfItsPeak) {
  const SkinLayout layout = make_grid_layout(8, 8);
  Recording recording = resting_grid(layout);
  SampleMatrix& samples = recording.streams[0].samples;
  for (int64_t frame = 10; frame < 30; ++frame)
    for (int64_t r = 1; r <= 5; ++r)
      for (int64_t c = 1; c <= 5; ++c) {
        const bool core = std::abs(r - 3) + std::abs(c - 3) <= 1;  // 5 taxels
        samples(frame, r * 8 + c) += core ? 200.0f : 40.0f;        // 20 more in the skirt
      }
  const auto area = [&](const std::string& parameters) {
    const auto extractor = make_grid_extractor(Parameters::parse(parameters, "--params"));
    const std::vector<FeatureColumn> columns = extractor->columns(layout);
    const std::vector<double> row = grid_row_of(*extractor, recording, layout);
    for (size_t k = 0; k < columns.size(); ++k)
      if (columns[k].name == "grid.area_max") return row[k];
    ADD_FAILURE() << "no grid.area_max";
    return 0.0;
  };
  const double taxel_area = area("share=0.99");  // the five core taxels
  EXPECT_DOUBLE_EQ(area("share=0.5"), taxel_area);
  EXPECT_DOUBLE_EQ(area("share=0"), taxel_area * 25.0 / 5.0);
  EXPECT_DOUBLE_EQ(area(""), taxel_area * 25.0 / 5.0);
  EXPECT_DOUBLE_EQ(area("share=0.15"), taxel_area * 25.0 / 5.0);  // 40 is past 0.15 x 200
  EXPECT_THROW(make_grid_extractor(Parameters::parse("share=1", "--params")), Error);
  EXPECT_THROW(make_grid_extractor(Parameters::parse("share=-0.1", "--params")), Error);
}

TEST(GridFeatures, AStuckTaxelAndQuietNoiseAreNoContact) {
  const SkinLayout layout = make_grid_layout(8, 8);
  Recording recording = resting_grid(layout);
  SampleMatrix& samples = recording.streams[0].samples;
  for (int64_t frame = 0; frame < kFrames; ++frame)
    for (int64_t taxel = 0; taxel < samples.cols(); ++taxel)
      samples(frame, taxel) += static_cast<float>((frame * 7 + taxel * 3) % 3 - 1);  // +-1 count
  samples.col(5).setConstant(1000.0f);                                               // stuck
  const auto extractor = make_grid_extractor({});
  const std::vector<double> row = grid_row_of(*extractor, recording, layout);
  EXPECT_EQ(row.at(1), 0.0);  // contact_share
}

TEST(GridFeatures, GenericKeepsItsPerChannelBlockUpToSixtyFourChannels) {
  const auto generic = make_generic_extractor({});
  const std::vector<FeatureColumn> small = generic->columns(make_grid_layout(8, 8));
  const std::vector<FeatureColumn> large = generic->columns(make_grid_layout(9, 9));
  EXPECT_EQ(small.front().name, "ch0.hjorth_activity");
  EXPECT_EQ(small.back().name, "contact.spread");
  EXPECT_EQ(large.front().name, "busiest.hjorth_activity");
  EXPECT_EQ(large.back().name, "grid.orientation_spread");
  EXPECT_LT(large.size(), 100u);
  EXPECT_NE(generic->layout_note(make_grid_layout(9, 9)).find("whole-grid"), std::string::npos);
  EXPECT_NE(generic->layout_note(make_grid_layout(8, 8)).find("per-channel"), std::string::npos);
  // Forced either way.
  const auto per_channel = make_generic_extractor(Parameters::parse("per_channel=yes", "--params"));
  EXPECT_EQ(per_channel->columns(make_grid_layout(9, 9)).size(), 81u * 26u + 26u + 1u + 1u + 5u);
  const auto whole = make_generic_extractor(Parameters::parse("per_channel=no", "--params"));
  EXPECT_EQ(whole->columns(make_grid_layout(8, 8)).back().name, "grid.orientation_spread");
  EXPECT_THROW(whole->columns(make_strip_layout(8)), Error);
  EXPECT_THROW(make_generic_extractor(Parameters::parse("per_channel=maybe", "--params")), Error);
  // The small skins of the papers keep their tables.
  for (const std::string skin : {"nao", "flux"})
    EXPECT_EQ(generic->columns(load_layout(skin)).size(),
              per_channel->columns(load_layout(skin)).size())
        << skin;
}

TEST(GridFeatures, GenericOnALargeGridWritesTheGridPipelinesFigures) {
  const SkinLayout layout = make_grid_layout(10, 10);
  Recording recording = resting_grid(layout);
  stroke(recording, 10, 2.0, 2.0, 0.3);
  const auto generic = make_generic_extractor({});
  const auto grid = make_grid_extractor({});
  const std::vector<double> generic_row = grid_row_of(*generic, recording, layout);
  const std::vector<double> grid_row = grid_row_of(*grid, recording, layout);
  ASSERT_GE(generic_row.size(), grid_row.size());
  const size_t offset = generic_row.size() - grid_row.size();
  for (size_t k = 0; k < grid_row.size(); ++k)
    EXPECT_DOUBLE_EQ(generic_row[offset + k], grid_row[k]) << k;
}

}  // namespace
}  // namespace tactile

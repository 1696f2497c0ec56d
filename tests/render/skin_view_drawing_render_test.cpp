// What makes a crowded skin legible: taxels grown towards their neighbours, touched taxels
// drawn on top at a readable size, the body outline under the taxels, region colours with
// their legend, and the colour scale along the bottom of a wide map.

#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <vector>

#include "osmesa_renderer.h"
#include "render_test_support.h"
#include "tactile/widgets/colormap.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {
namespace {

using testing::begin_canvas;
using testing::close_to;
using testing::close_to_packed;
using testing::end_canvas;

// rows x columns round pads of 5 mm at a 7 mm pitch (a TSA sheet's geometry).
SkinLayout pad_sheet(int rows, int columns) {
  SkinLayout layout = make_grid_layout(rows, columns, "pads");
  for (Taxel& taxel : layout.taxels) {
    taxel.position = {taxel.position.x * 0.7, taxel.position.y * 0.7};
    taxel.size = {5.0, 5.0};
    taxel.shape = TaxelShape::kCircle;
  }
  return layout;
}

struct DrawnSkin {
  SkinViewResult result;
  Image image;
};

DrawnSkin draw_once(OffscreenRenderer& renderer, const SkinLayout& layout,
                    const std::vector<float>& values, const SkinViewStyle& style) {
  renderer.new_frame();
  begin_canvas(renderer);
  SkinViewResult result = draw_skin_view(
      "skin", layout, values, 0.0, 1.0,
      ImVec2(static_cast<float>(renderer.width()), static_cast<float>(renderer.height())), style);
  end_canvas();
  return {std::move(result), renderer.render()};
}

float box_width(const SkinViewBox& box) { return box.max.x - box.min.x; }

TEST(SkinViewDrawing, SmallTaxelsGrowTowardsTheirNeighboursWithoutTouchingThem) {
  OffscreenRenderer renderer(300, 300);
  const SkinLayout layout = pad_sheet(4, 4);
  const std::vector<float> values(16, 0.0f);
  const std::vector<double> spacing = nearest_taxel_distances(layout);
  const DrawnSkin own = draw_once(renderer, layout, values, {.show_group_names = false});
  const DrawnSkin grown = draw_once(renderer, layout, values,
                                    {.show_group_names = false, .neighbour_distances = spacing});
  const double scale = own.result.transform.scale;
  EXPECT_NEAR(box_width(own.result.taxels[5]), 5.0 * scale, 1.0);
  // Grown to a pixel (or a twentieth of the pitch) short of the 7 mm pitch.
  EXPECT_GT(box_width(grown.result.taxels[5]), 6.4 * scale);
  EXPECT_LT(box_width(grown.result.taxels[5]), 7.0 * scale - 0.9);
  EXPECT_LT(grown.result.taxels[4].max.x, grown.result.taxels[5].min.x);
}

TEST(SkinViewDrawing, ATouchedTinyTaxelIsDrawnOnTopEighteenPixelsAcross) {
  // 30 x 40 pads in 240 x 220 pixels: about 4 pixels a pad (TSA's in the default window, whose
  // touches drawn 10 pixels across read as dots; issue 41).
  OffscreenRenderer renderer(240, 220);
  const SkinLayout layout = pad_sheet(30, 40);
  std::vector<float> values(layout.taxels.size(), 0.0f);
  const size_t touched = 15 * 40 + 20;
  values[touched] = 1.0f;
  values[touched + 1] = 0.3f;  // under half the scale: lit, not drawn as touched
  const DrawnSkin drawn = draw_once(renderer, layout, values, {.show_group_names = false});
  write_png(testing::png_path("skin_touched_pad"), drawn.image);
  ASSERT_EQ(drawn.result.touched_taxels, std::vector<int64_t>{layout.taxels[touched].id});
  EXPECT_LT(5.0 * drawn.result.transform.scale, 6.0);
  const SkinViewBox& box = drawn.result.taxels[touched];
  EXPECT_GE(box_width(box), 17.5f);
  EXPECT_LE(box_width(box), 19.0f);
  int lit = 0;
  const Colour top = viridis(1.0f);
  for (int y = static_cast<int>(box.min.y); y <= static_cast<int>(box.max.y); ++y)
    for (int x = static_cast<int>(box.min.x); x <= static_cast<int>(box.max.x); ++x)
      lit += close_to(drawn.image.at(x, y), top, 12);
  EXPECT_GE(lit, 150);
}

TEST(SkinViewDrawing, TheBodyOutlineIsDrawnUnderTheTaxels) {
  OffscreenRenderer renderer(300, 300);
  SkinLayout layout = pad_sheet(2, 2);
  // A body well around the pads, and a pad's colour still at its centre.
  layout.body_outline = {{{-20.0, -20.0}, {34.0, -20.0}, {34.0, 34.0}, {-20.0, 34.0}}};
  const std::vector<float> values = {0.0f, 1.0f, 0.5f, 0.25f};
  const DrawnSkin with_body = draw_once(renderer, layout, values, {.show_group_names = false});
  write_png(testing::png_path("skin_body_outline"), with_body.image);
  const MapTransform& transform = with_body.result.transform;
  // Fitted around the outline (54 mm across), not the pads alone.
  const SkinViewGeometry geometry = skin_view_geometry(layout, ImVec2(0, 0), ImVec2(300, 300));
  EXPECT_NEAR(54.0 * transform.scale, std::min(geometry.map_size.x, geometry.map_size.y) - 16.0,
              0.5);
  // Inside the body, away from the pads: the faint fill over the background.
  const ImVec2 inside = transform.apply({-10.0, 25.0});
  const Image::Rgba filled =
      with_body.image.at(static_cast<int>(inside.x), static_cast<int>(inside.y));
  const Image::Rgba background = with_body.image.at(2, 2);  // the margin, outside the body
  EXPECT_GT(filled.r + filled.g + filled.b, background.r + background.g + background.b + 15);
  // The outline itself: a light line on the body's left edge.
  const ImVec2 edge = transform.apply({-20.0, 7.0});
  int brightest = 0;
  for (int dx = -1; dx <= 1; ++dx) {
    const Image::Rgba line =
        with_body.image.at(static_cast<int>(edge.x) + dx, static_cast<int>(edge.y));
    brightest = std::max(brightest, line.r + line.g + line.b);
  }
  EXPECT_GT(brightest, 300);
  for (size_t pad = 0; pad < 4; ++pad) {
    const ImVec2 centre = transform.apply(layout.taxels[pad].position);
    EXPECT_TRUE(close_to(with_body.image.at(static_cast<int>(centre.x), static_cast<int>(centre.y)),
                         viridis(values[pad]), 3))
        << "pad " << pad;
  }
}

TEST(SkinViewDrawing, CategoriesColourTheTaxelsAndTheLegendNamesThem) {
  OffscreenRenderer renderer(400, 300);
  const SkinLayout layout = make_grid_layout(2, 2);
  SkinViewCategories regions;
  regions.of_taxel = {0, 0, 1, -1};
  regions.names = {"upper row", "lower left"};
  regions.colours = {IM_COL32(31, 119, 180, 255), IM_COL32(255, 127, 14, 255)};
  const std::vector<float> values = {0.0f, 0.0f, 0.0f, 0.0f};
  const DrawnSkin drawn =
      draw_once(renderer, layout, values, {.show_group_names = false, .categories = &regions});
  write_png(testing::png_path("skin_categories"), drawn.image);
  const auto centre_of = [&](size_t taxel) {
    const ImVec2 centre = drawn.result.transform.apply(layout.taxels[taxel].position);
    return drawn.image.at(static_cast<int>(centre.x), static_cast<int>(centre.y));
  };
  EXPECT_TRUE(close_to_packed(centre_of(0), regions.colours[0], 3));
  EXPECT_TRUE(close_to_packed(centre_of(2), regions.colours[1], 3));
  EXPECT_FALSE(close_to_packed(centre_of(3), regions.colours[0], 40));  // no region: grey
  ASSERT_EQ(drawn.result.legend.size(), 2u);
  EXPECT_EQ(drawn.result.legend[1].id, "lower left");
  const SkinViewBox& swatch = drawn.result.legend[1].box;
  EXPECT_GT(swatch.min.x, drawn.result.taxels[1].max.x);  // beside the map
  EXPECT_TRUE(close_to_packed(
      drawn.image.at(static_cast<int>(swatch.min.x + 5), static_cast<int>(swatch.min.y + 5)),
      regions.colours[1], 3));
}

TEST(SkinViewDrawing, AWideMapTakesTheColourScaleAlongTheBottom) {
  OffscreenRenderer renderer(400, 300);
  const SkinLayout strip = make_strip_layout(16);
  const std::vector<float> values(16, 0.0f);
  const DrawnSkin drawn = draw_once(renderer, strip, values, {.show_group_names = false});
  // (After a frame: the legend's height follows the font.)
  const SkinViewGeometry geometry = skin_view_geometry(strip, ImVec2(0, 0), ImVec2(400, 300));
  EXPECT_TRUE(geometry.legend_along_bottom);
  EXPECT_NEAR(geometry.transform.scale, (400.0 - 16.0) / 160.0, 1e-9);  // the whole width
  write_png(testing::png_path("skin_bottom_legend"), drawn.image);
  // The bar: value_min (dark) on the left, value_max (yellow) on the right.
  const int bar_y = static_cast<int>(geometry.legend_min.y) + 10;
  const Image::Rgba right = drawn.image.at(388, bar_y);
  EXPECT_TRUE(right.r > 180 && right.g > 180 && right.b < 100)
      << int(right.r) << "," << int(right.g) << "," << int(right.b) << " at y " << bar_y;
  const SkinViewGeometry square =
      skin_view_geometry(make_grid_layout(4, 4), ImVec2(0, 0), ImVec2(400, 300));
  EXPECT_FALSE(square.legend_along_bottom);  // a square map in a wide view keeps it on the right
}

}  // namespace
}  // namespace tactile

#include <gtest/gtest.h>
#include <imgui.h>

#include <limits>
#include <vector>

#include "osmesa_renderer.h"
#include "render_test_support.h"
#include "tactile/widgets/colormap.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {
namespace {

using testing::begin_canvas;
using testing::close_to;
using testing::end_canvas;

// A 3 x 3 grid of 9 mm squares at a 10 mm pitch, ids r-major, with one body part
// per row so group names have something to show.
SkinLayout grid_layout() {
  SkinLayout layout;
  layout.id = "grid:3x3";
  layout.display_modality = "value";
  for (int row = 0; row < 3; ++row) {
    Group group{"row-" + std::to_string(row), "body-part", "row " + std::to_string(row), {}};
    for (int column = 0; column < 3; ++column) {
      Taxel taxel;
      taxel.id = row * 3 + column;
      taxel.name = "ch" + std::to_string(taxel.id);
      taxel.body_part = group.id;
      taxel.position = {5.0 + 10.0 * column, 5.0 + 10.0 * row};
      taxel.size = {9.0, 9.0};
      taxel.area = 81.0;
      taxel.shape = TaxelShape::kRectangle;
      layout.taxels.push_back(taxel);
      group.taxels.push_back(taxel.id);
    }
    layout.groups.push_back(group);
  }
  return layout;
}

struct GridFixture : ::testing::Test {
  OffscreenRenderer renderer{400, 300};
  SkinLayout layout = grid_layout();
  std::vector<float> values = {0.0f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f, 1.0f};

  SkinViewResult frame(double value_min, double value_max, const SkinViewStyle& style) {
    renderer.new_frame();
    begin_canvas(renderer);
    const SkinViewResult result =
        draw_skin_view("skin", layout, values, value_min, value_max, ImVec2(400, 300), style);
    end_canvas();
    return result;
  }
  Image::Rgba centre_pixel(const Image& image, const SkinViewResult& result, int taxel) const {
    const ImVec2 centre = result.transform.apply(layout.taxels[taxel].position);
    return image.at(static_cast<int>(centre.x), static_cast<int>(centre.y));
  }
};

TEST_F(GridFixture, EachTaxelCentreHasTheViridisColourOfItsValue) {
  const SkinViewResult result = frame(0.0, 1.0, {.show_group_names = false});
  const Image image = renderer.render();
  write_png(testing::png_path("skin_grid"), image);
  for (int taxel = 0; taxel < 9; ++taxel) {
    const Colour expected = viridis(values[taxel]);
    const Image::Rgba pixel = centre_pixel(image, result, taxel);
    EXPECT_TRUE(close_to(pixel, expected, 3))
        << "taxel " << taxel << ": got " << int(pixel.r) << "," << int(pixel.g) << ","
        << int(pixel.b) << " expected " << int(expected.r) << "," << int(expected.g) << ","
        << int(expected.b);
  }
  // Between taxels (the 1 mm gap) the background shows, not a taxel colour.
  const ImVec2 gap = result.transform.apply({10.0, 5.0});
  EXPECT_FALSE(
      close_to(image.at(static_cast<int>(gap.x), static_cast<int>(gap.y)), viridis(0.0f), 20));
}

// Orange pixels (the selection outline) on the vertical line through a taxel's centre,
// between the centres of the taxels above and below it.
int selection_pixels_across(const Image& image, const SkinViewResult& result,
                            const SkinLayout& layout, int taxel) {
  const Point2 centre = layout.taxels[taxel].position;
  const ImVec2 top = result.transform.apply({centre.x, centre.y - 9.0});
  const ImVec2 bottom = result.transform.apply({centre.x, centre.y + 9.0});
  int count = 0;
  // A taxel on the map's edge has no neighbour there: stay inside the image.
  const int first = std::max(0, static_cast<int>(top.y));
  const int last = std::min(image.height - 1, static_cast<int>(bottom.y));
  for (int y = first; y <= last; ++y)
    count += testing::close_to_packed(image.at(static_cast<int>(top.x), y),
                                      IM_COL32(255, 140, 40, 255), 30);
  return count;
}

TEST_F(GridFixture, SelectedTaxelsAreOutlined) {
  const std::vector<int64_t> selected = {layout.taxels[4].id};
  const SkinViewResult result =
      frame(0.0, 1.0, {.show_group_names = false, .selected_taxels = selected});
  const Image image = renderer.render();
  write_png(testing::png_path("skin_grid_selected"), image);
  EXPECT_GE(selection_pixels_across(image, result, layout, 4), 4);  // top and bottom edges
  EXPECT_EQ(selection_pixels_across(image, result, layout, 0), 0);  // not selected
}

TEST_F(GridFixture, ABodyPartNameWithNoRoomBesideItIsLeftOut) {
  // The rows touch and the map fills the view: no room beside row 1 for a long name, and it
  // is never written over the taxels instead.
  layout.groups[1].name = "a much longer name than one taxel";
  const SkinViewResult result = frame(0.0, 1.0, {});
  const Image with_names = renderer.render();
  frame(0.0, 1.0, {.show_group_names = false});
  const Image plain = renderer.render();
  for (const SkinViewLabel& name : result.names) EXPECT_NE(name.id, "row-1");
  const ImVec2 centre = result.transform.apply({15.0, 15.0});
  int changed = 0;
  for (int dy = -6; dy <= 6; ++dy)
    for (int dx = -20; dx <= 20; ++dx) {
      const int x = static_cast<int>(centre.x) + dx, y = static_cast<int>(centre.y) + dy;
      changed += with_names.at(x, y).r != plain.at(x, y).r;
    }
  EXPECT_EQ(changed, 0);
}

TEST_F(GridFixture, ReversedRangeReversesTheColours) {
  const SkinViewResult result = frame(1.0, 0.0, {.show_group_names = false});
  const Image image = renderer.render();
  for (int taxel = 0; taxel < 9; ++taxel) {
    EXPECT_TRUE(close_to(centre_pixel(image, result, taxel), viridis(1.0f - values[taxel]), 3))
        << "taxel " << taxel;
  }
}

TEST_F(GridFixture, CallerRangeMapsAndClamps) {
  // [0.5, 0.75]: values below are the darkest colour, above the brightest.
  const SkinViewResult result = frame(0.5, 0.75, {.show_group_names = false});
  const Image image = renderer.render();
  EXPECT_TRUE(close_to(centre_pixel(image, result, 2), viridis(0.0f), 3));
  EXPECT_TRUE(close_to(centre_pixel(image, result, 5), viridis(0.5f), 3));
  EXPECT_TRUE(close_to(centre_pixel(image, result, 8), viridis(1.0f), 3));
}

TEST_F(GridFixture, MapIsCentredWithItsAspectRatioKept) {
  const SkinViewResult result = frame(0.0, 1.0, {});
  renderer.render();
  // The legend takes the right strip; the map is square, so its height decides.
  const SkinViewGeometry geometry = skin_view_geometry(layout, ImVec2(0, 0), ImVec2(400, 300));
  EXPECT_DOUBLE_EQ(result.transform.scale, geometry.transform.scale);
  const auto [low, high] = layout.bounds();
  EXPECT_NEAR(result.transform.scale, (300.0 - 16.0) / (high.y - low.y), 1e-9);
  const ImVec2 centre = result.transform.apply({0.5 * (low.x + high.x), 0.5 * (low.y + high.y)});
  EXPECT_NEAR(centre.x, 0.5f * geometry.map_size.x, 1e-3f);
  EXPECT_NEAR(centre.y, 150.0f, 1e-3f);
}

TEST_F(GridFixture, LegendRunsFromMaxDownToMinAndNamesLeaveTaxelsClear) {
  const SkinViewResult result = frame(0.0, 1.0, {.modality_label = "force (N)"});
  const Image image = renderer.render();
  write_png(testing::png_path("skin_grid_names"), image);
  // The legend bar runs from bright yellow (value_max) at the top to dark purple
  // (value_min) at the bottom.
  const SkinViewGeometry geometry = skin_view_geometry(layout, ImVec2(0, 0), ImVec2(400, 300));
  const int bar_x = static_cast<int>(geometry.map_size.x) + 15;
  const Image::Rgba top = image.at(bar_x, 30);
  const Image::Rgba bottom = image.at(bar_x, 282);
  EXPECT_TRUE(top.r > 180 && top.g > 180 && top.b < 100);
  EXPECT_TRUE(bottom.r < 100 && bottom.g < 40 && bottom.b > 60);
  // Names go beside the taxels, never over them: every taxel's centre keeps its colour.
  for (int taxel = 0; taxel < 9; ++taxel)
    EXPECT_TRUE(close_to(centre_pixel(image, result, taxel), viridis(values[taxel]), 3))
        << "taxel " << taxel;
}

TEST_F(GridFixture, HoverAndClickNameTheTaxelUnderTheMouse) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(1, 1);
  SkinViewResult result = frame(0.0, 1.0, {});
  renderer.render();
  io.MousePos = result.transform.apply(layout.taxels[5].position);
  result = frame(0.0, 1.0, {});
  renderer.render();
  EXPECT_EQ(result.hovered_taxel, 5);
  EXPECT_EQ(result.clicked_taxel, -1);
  io.MouseDown[0] = true;
  result = frame(0.0, 1.0, {});
  const Image image = renderer.render();
  write_png(testing::png_path("skin_grid_hover"), image);
  EXPECT_EQ(result.clicked_taxel, 5);
  io.MouseDown[0] = false;
  io.MousePos = result.transform.apply({10.0, 10.0});  // the gap between four taxels
  frame(0.0, 1.0, {});
  renderer.render();
  result = frame(0.0, 1.0, {});
  renderer.render();
  EXPECT_EQ(result.hovered_taxel, -1);
}

TEST_F(GridFixture, ShortValueArrayDrawsMissingTaxelsGrey) {
  values.resize(4);
  const SkinViewResult result = frame(0.0, 1.0, {.show_group_names = false});
  const Image image = renderer.render();
  EXPECT_TRUE(close_to(centre_pixel(image, result, 3), viridis(0.375f), 3));
  EXPECT_TRUE(close_to(centre_pixel(image, result, 8),
                       viridis(std::numeric_limits<float>::quiet_NaN()), 3));
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

TEST_F(GridFixture, WheelZoomKeepsTheTaxelUnderThePointerAndDoubleClickResets) {
  SkinViewZoom zoom;
  SkinViewStyle style;
  style.zoom = &zoom;
  ImGuiIO& io = ImGui::GetIO();
  const SkinViewResult fitted = frame(0.0, 1.0, style);
  renderer.render();
  const ImVec2 pointer = fitted.transform.apply(layout.taxels[2].position);
  io.MousePos = pointer;
  io.MouseWheel = 2.0f;
  const SkinViewResult zoomed = frame(0.0, 1.0, style);
  io.MouseWheel = 0.0f;
  const Image image = renderer.render();
  EXPECT_NEAR(zoom.zoom, 1.44, 1e-9);
  EXPECT_NEAR(zoomed.transform.scale, fitted.transform.scale * 1.44, 1e-6);
  const ImVec2 still = zoomed.transform.apply(layout.taxels[2].position);
  EXPECT_NEAR(still.x, pointer.x, 0.5);
  EXPECT_NEAR(still.y, pointer.y, 0.5);
  EXPECT_TRUE(close_to(centre_pixel(image, zoomed, 2), viridis(values[2]), 3));

  io.MouseDown[0] = true;
  frame(0.0, 1.0, style);
  renderer.render();
  io.MouseDown[0] = false;
  frame(0.0, 1.0, style);
  renderer.render();
  io.MouseDown[0] = true;
  frame(0.0, 1.0, style);  // second press: a double-click
  renderer.render();
  io.MouseDown[0] = false;
  EXPECT_DOUBLE_EQ(zoom.zoom, 1.0);
  EXPECT_DOUBLE_EQ(zoom.pan_x, 0.0);
}

}  // namespace
}  // namespace tactile

// The five research skins drawn by SkinView: known values, colours checked at
// taxel centres through the view's own map transform.

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "osmesa_renderer.h"
#include "render_test_support.h"
#include "tactile/widgets/colormap.h"
#include "tactile/widgets/polygon.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {
namespace {

using testing::begin_canvas;
using testing::close_to;
using testing::end_canvas;

double distance_to_segment(Point2 point, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double length = dx * dx + dy * dy;
  const double t =
      length > 0 ? std::clamp(((point.x - a.x) * dx + (point.y - a.y) * dy) / length, 0.0, 1.0)
                 : 0.0;
  return std::hypot(point.x - (a.x + t * dx), point.y - (a.y + t * dy));
}

class SkinLayoutRender : public ::testing::TestWithParam<std::string> {};

TEST_P(SkinLayoutRender, TaxelCentresShowTheirValueColour) {
  const SkinLayout layout = load_layout(GetParam());
  ASSERT_FALSE(layout.taxels.empty());
  std::vector<float> values(layout.taxels.size());
  // Values over the lower half of the scale, and every tenth taxel touched (at the top): a
  // touched tiny taxel is drawn 18 pixels across over its neighbours (TSA here), so touches
  // are kept apart enough to leave centres to check.
  for (size_t index = 0; index < values.size(); ++index)
    values[index] = index % 10 == 9 ? 1.0f : static_cast<float>(index % 5) / 10.0f;

  OffscreenRenderer renderer(1000, 700);
  for (bool names : {true, false}) {
    renderer.new_frame();
    begin_canvas(renderer);
    const SkinViewResult result = draw_skin_view("skin", layout, values, 0.0, 1.0,
                                                 ImVec2(1000, 700), {.show_group_names = names});
    end_canvas();
    const Image image = renderer.render();
    if (names) {
      write_png(testing::png_path("skin_" + GetParam()), image);
      continue;
    }
    // Screen outlines, in drawing order, to find the topmost taxel at a point and
    // keep clear of edges (outlines and anti-aliased fringes). Touched taxels are drawn again
    // last (weakest first), enlarged about their centres to their drawn boxes.
    std::vector<std::vector<Point2>> outlines;
    std::vector<size_t> order;
    for (size_t index = 0; index < layout.taxels.size(); ++index) {
      std::vector<Point2> screen;
      for (const Point2& point : taxel_outline(layout.taxels[index])) {
        const ImVec2 pixel = result.transform.apply(point);
        screen.push_back({pixel.x, pixel.y});
      }
      outlines.push_back(screen);
      order.push_back(index);
    }
    for (const int64_t id : result.touched_taxels) {
      const auto found = std::find_if(layout.taxels.begin(), layout.taxels.end(),
                                      [id](const Taxel& taxel) { return taxel.id == id; });
      const auto index = static_cast<size_t>(found - layout.taxels.begin());
      const ImVec2 centre = result.transform.apply(layout.taxels[index].position);
      double low = 1e9, high = -1e9;
      for (const Point2& point : outlines[index])
        low = std::min(low, point.x), high = std::max(high, point.x);
      const double factor =
          high > low ? (result.taxels[index].max.x - result.taxels[index].min.x) / (high - low)
                     : 1.0;
      std::vector<Point2> enlarged;
      for (const Point2& point : outlines[index])
        enlarged.push_back(
            {centre.x + factor * (point.x - centre.x), centre.y + factor * (point.y - centre.y)});
      outlines.push_back(enlarged);
      order.push_back(index);
    }
    int checked = 0;
    const size_t step = std::max<size_t>(1, layout.taxels.size() / 40);
    for (size_t index = 0; index < layout.taxels.size(); index += step) {
      const ImVec2 centre = result.transform.apply(layout.taxels[index].position);
      const Point2 pixel_centre{std::floor(centre.x) + 0.5, std::floor(centre.y) + 0.5};
      int topmost = -1;
      double clearance = 1e9;
      for (size_t drawn = 0; drawn < outlines.size(); ++drawn) {
        const std::vector<Point2>& outline = outlines[drawn];
        for (size_t corner = 0; corner < outline.size(); ++corner) {
          clearance =
              std::min(clearance, distance_to_segment(pixel_centre, outline[corner],
                                                      outline[(corner + 1) % outline.size()]));
        }
        if (point_in_polygon(outline, pixel_centre)) topmost = static_cast<int>(order[drawn]);
      }
      if (topmost < 0 || clearance < 2.5) continue;
      const Image::Rgba pixel = image.at(static_cast<int>(centre.x), static_cast<int>(centre.y));
      const Colour expected = viridis(values[topmost]);
      EXPECT_TRUE(close_to(pixel, expected, 3))
          << GetParam() << " taxel " << layout.taxels[index].id << " (topmost "
          << layout.taxels[topmost].id << "): got " << int(pixel.r) << "," << int(pixel.g) << ","
          << int(pixel.b) << " expected " << int(expected.r) << "," << int(expected.g) << ","
          << int(expected.b);
      ++checked;
    }
    // Enough taxels were large enough to check, so the test cannot pass empty.
    EXPECT_GE(checked, std::min<int>(5, static_cast<int>(layout.taxels.size()))) << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(FiveSkins, SkinLayoutRender,
                         ::testing::Values("nao", "tsa", "fur", "robovie", "flux"));

}  // namespace
}  // namespace tactile

#include <gtest/gtest.h>
#include <imgui.h>

#include "osmesa_renderer.h"

namespace tactile {
namespace {

TEST(OffscreenRenderer, FilledRectangleLandsOnItsPixels) {
  OffscreenRenderer renderer(200, 100);
  renderer.new_frame();
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->AddRectFilled(ImVec2(20, 10), ImVec2(60, 40), IM_COL32(255, 0, 0, 255));
  const Image image = renderer.render(0.0f, 0.0f, 0.0f);
  ASSERT_EQ(image.width, 200);
  ASSERT_EQ(image.height, 100);
  const Image::Rgba inside = image.at(40, 25);
  EXPECT_EQ(inside.r, 255);
  EXPECT_EQ(inside.g, 0);
  const Image::Rgba outside = image.at(100, 80);
  EXPECT_EQ(outside.r, 0);
  // The top-left corner of the rectangle is near the top of the image, not flipped.
  EXPECT_EQ(image.at(21, 11).r, 255);
  EXPECT_EQ(image.at(21, 88).r, 0);
}

}  // namespace
}  // namespace tactile

#include "tactile/widgets/polygon.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tactile {
namespace {

// An L: the unit square [0, 2]^2 less its top-right quarter, clockwise on a y-down screen.
const std::vector<Point2> kEll = {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}, {0, 2}};

double triangle_area(const std::vector<Point2>& polygon, const std::array<int, 3>& triangle) {
  return std::abs(signed_area({polygon[triangle[0]], polygon[triangle[1]], polygon[triangle[2]]}));
}

TEST(Polygon, ClockwiseOnScreenHasPositiveArea) {
  EXPECT_DOUBLE_EQ(signed_area({{0, 0}, {2, 0}, {2, 3}, {0, 3}}), 6.0);
  EXPECT_DOUBLE_EQ(signed_area({{0, 0}, {0, 3}, {2, 3}, {2, 0}}), -6.0);
  EXPECT_DOUBLE_EQ(signed_area(kEll), 3.0);
}

TEST(Polygon, LShapeIsConcaveAndHexagonIsConvex) {
  EXPECT_FALSE(is_convex(kEll));
  std::vector<Point2> hexagon;
  for (int corner = 0; corner < 6; ++corner) {
    hexagon.push_back({std::cos(corner * M_PI / 3), std::sin(corner * M_PI / 3)});
  }
  EXPECT_TRUE(is_convex(hexagon));
}

TEST(Polygon, PointInLShapeFollowsItsNotch) {
  EXPECT_TRUE(point_in_polygon(kEll, {0.5, 0.5}));
  EXPECT_TRUE(point_in_polygon(kEll, {1.5, 1.5}));
  EXPECT_FALSE(point_in_polygon(kEll, {1.5, 0.5}));  // the missing quarter
  EXPECT_FALSE(point_in_polygon(kEll, {3.0, 1.5}));
}

TEST(Polygon, TriangulationOfLShapeCoversItsAreaOnly) {
  for (bool reversed : {false, true}) {
    std::vector<Point2> polygon = kEll;
    if (reversed) std::reverse(polygon.begin(), polygon.end());
    const auto triangles = triangulate(polygon);
    ASSERT_EQ(triangles.size(), 4u);  // n - 2
    double area = 0.0;
    for (const auto& triangle : triangles) area += triangle_area(polygon, triangle);
    EXPECT_NEAR(area, 3.0, 1e-12);
    // No triangle covers the notch.
    for (const auto& triangle : triangles) {
      EXPECT_FALSE(point_in_polygon(
          {polygon[triangle[0]], polygon[triangle[1]], polygon[triangle[2]]}, {1.5, 0.5}));
    }
  }
}

}  // namespace
}  // namespace tactile

#pragma once
// Plane polygon helpers for drawing and picking taxel outlines. Pure geometry: no
// ImGui, so the tests check them directly.

#include <array>
#include <vector>

#include "tactile/layout/skin_layout.h"

namespace tactile {

// Shoelace sum: positive when the vertices run clockwise on a y-down screen.
double signed_area(const std::vector<Point2>& polygon);
// True when every turn goes the same way (collinear vertices allowed).
bool is_convex(const std::vector<Point2>& polygon);
// Even-odd rule; points on an edge may go either way.
bool point_in_polygon(const std::vector<Point2>& polygon, Point2 point);
// Ear-clipping triangulation of a simple polygon (either winding): vertex index
// triples. A degenerate polygon that leaves no ear is closed with a fan.
std::vector<std::array<int, 3>> triangulate(const std::vector<Point2>& polygon);

}  // namespace tactile

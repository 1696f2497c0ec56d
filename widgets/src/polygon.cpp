#include "tactile/widgets/polygon.h"

#include <cmath>
#include <numeric>

namespace tactile {

namespace {

double cross(Point2 origin, Point2 a, Point2 b) {
  return (a.x - origin.x) * (b.y - origin.y) - (a.y - origin.y) * (b.x - origin.x);
}

bool inside_triangle(Point2 point, Point2 a, Point2 b, Point2 c) {
  const double ab = cross(a, b, point);
  const double bc = cross(b, c, point);
  const double ca = cross(c, a, point);
  return (ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0);
}

}  // namespace

double signed_area(const std::vector<Point2>& polygon) {
  double sum = 0.0;
  for (size_t index = 0; index < polygon.size(); ++index) {
    const Point2& a = polygon[index];
    const Point2& b = polygon[(index + 1) % polygon.size()];
    sum += a.x * b.y - b.x * a.y;
  }
  return 0.5 * sum;
}

bool is_convex(const std::vector<Point2>& polygon) {
  const size_t count = polygon.size();
  if (count < 4) return true;
  int sign = 0;
  for (size_t index = 0; index < count; ++index) {
    const double turn =
        cross(polygon[index], polygon[(index + 1) % count], polygon[(index + 2) % count]);
    if (turn == 0.0) continue;
    const int turn_sign = turn > 0 ? 1 : -1;
    if (sign != 0 && turn_sign != sign) return false;
    sign = turn_sign;
  }
  return true;
}

bool point_in_polygon(const std::vector<Point2>& polygon, Point2 point) {
  bool inside = false;
  for (size_t index = 0, previous = polygon.size() - 1; index < polygon.size();
       previous = index++) {
    const Point2& a = polygon[index];
    const Point2& b = polygon[previous];
    if ((a.y > point.y) != (b.y > point.y) &&
        point.x < (b.x - a.x) * (point.y - a.y) / (b.y - a.y) + a.x) {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<std::array<int, 3>> triangulate(const std::vector<Point2>& polygon) {
  std::vector<std::array<int, 3>> triangles;
  const int count = static_cast<int>(polygon.size());
  if (count < 3) return triangles;
  std::vector<int> remaining(count);
  std::iota(remaining.begin(), remaining.end(), 0);
  // An ear is a convex corner (turning like the whole polygon) whose triangle
  // holds no other remaining vertex.
  const double orientation = signed_area(polygon) >= 0 ? 1.0 : -1.0;
  while (remaining.size() > 3) {
    const int size = static_cast<int>(remaining.size());
    bool clipped = false;
    for (int corner = 0; corner < size && !clipped; ++corner) {
      const int before = remaining[(corner + size - 1) % size];
      const int at = remaining[corner];
      const int after = remaining[(corner + 1) % size];
      if (cross(polygon[before], polygon[at], polygon[after]) * orientation <= 0) continue;
      bool holds_other = false;
      for (int other : remaining) {
        if (other == before || other == at || other == after) continue;
        if (inside_triangle(polygon[other], polygon[before], polygon[at], polygon[after])) {
          holds_other = true;
          break;
        }
      }
      if (holds_other) continue;
      triangles.push_back({before, at, after});
      remaining.erase(remaining.begin() + corner);
      clipped = true;
    }
    if (!clipped) {
      // Self-touching or degenerate input: finish with a fan rather than loop.
      for (int index = 1; index + 1 < static_cast<int>(remaining.size()); ++index) {
        triangles.push_back({remaining[0], remaining[index], remaining[index + 1]});
      }
      return triangles;
    }
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

}  // namespace tactile

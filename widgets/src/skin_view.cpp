#include "tactile/widgets/skin_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "skin_view_parts.h"
#include "tactile/widgets/colormap.h"
#include "tactile/widgets/polygon.h"

namespace tactile {

namespace {

using skin_parts::kOutline;

constexpr float kMapMargin = 8.0f;
constexpr float kOutlineMinPixels = 6.0f;  // smaller taxels: outlines would hide the fill
// A taxel grows towards its neighbours at most this much, and stops this many pixels (or a
// twentieth of the spacing) short of touching them.
constexpr double kMaxGrowth = 1.6;
constexpr double kGapPixels = 1.0;
// A taxel at least half-way up the colour scale reads as touched: drawn on top of its
// neighbours and at least this large (at most three times its size), so that a touch on the
// small pads of a crowded map still shows.
constexpr float kTouchedPosition = 0.5f;
constexpr float kTouchedMinPixels = 10.0f;
// A touched taxel of fewer pixels than this (TSA's 4-pixel pads in the default window, whose
// touches read as two or three dots of 5 pixels) is drawn kTinyTouchedPixels across.
constexpr float kTinyTaxelPixels = 8.0f;
constexpr float kTinyTouchedPixels = 18.0f;

// Selected taxels: the colour of the time cursor, so "what is selected" reads as one thing.
const ImU32 kSelection = IM_COL32(255, 140, 40, 255);
const ImU32 kHighlight = IM_COL32(255, 255, 255, 255);
const ImU32 kBodyFill = IM_COL32(120, 130, 150, 26);
const ImU32 kBodyLine = IM_COL32(125, 135, 155, 190);
const ImU32 kNoCategory = IM_COL32(90, 90, 95, 255);

// A taxel's outline on screen, clockwise on the y-down screen as ImGui's anti-aliased fill
// wants; grown towards its neighbours when the style gives their distances.
struct ScreenTaxel {
  std::vector<ImVec2> points;
  std::vector<Point2> map_points;  // the drawn outline on the map, for picking
  ImVec2 centre;
  bool convex = true;
  float extent = 0.0f;  // smaller side of its screen bounding box
  SkinViewBox box;
};

ScreenTaxel screen_taxel(const Taxel& taxel, const MapTransform& transform, double spacing,
                         float min_pixels) {
  ScreenTaxel screen;
  screen.map_points = taxel_outline(taxel);
  if (signed_area(screen.map_points) < 0) {
    std::reverse(screen.map_points.begin(), screen.map_points.end());
  }
  screen.convex = is_convex(screen.map_points);
  if (std::isfinite(spacing) && spacing > 0.0 && !screen.map_points.empty()) {
    Point2 low = screen.map_points.front(), high = low;
    for (const Point2& point : screen.map_points) {
      low = {std::min(low.x, point.x), std::min(low.y, point.y)};
      high = {std::max(high.x, point.x), std::max(high.y, point.y)};
    }
    const double own = std::max(high.x - low.x, high.y - low.y);
    const double gap = std::max(0.05 * spacing, kGapPixels / transform.scale);
    const double factor = own > 0.0 ? std::clamp((spacing - gap) / own, 1.0, kMaxGrowth) : 1.0;
    if (factor > 1.0) {
      const Point2 centre = taxel.position;
      for (Point2& point : screen.map_points)
        point = {centre.x + factor * (point.x - centre.x),
                 centre.y + factor * (point.y - centre.y)};
    }
  }
  if (min_pixels > 0.0f && !screen.map_points.empty()) {
    double extent = std::numeric_limits<double>::max();
    Point2 low = screen.map_points.front(), high = low;
    for (const Point2& point : screen.map_points) {
      low = {std::min(low.x, point.x), std::min(low.y, point.y)};
      high = {std::max(high.x, point.x), std::max(high.y, point.y)};
    }
    extent = std::min(high.x - low.x, high.y - low.y) * transform.scale;
    if (extent > 0.0 && extent < min_pixels) {
      const double factor = min_pixels / extent;
      const Point2 centre = taxel.position;
      for (Point2& point : screen.map_points)
        point = {centre.x + factor * (point.x - centre.x),
                 centre.y + factor * (point.y - centre.y)};
    }
  }
  ImVec2 low(std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
  ImVec2 high(-low.x, -low.y);
  for (const Point2& point : screen.map_points) {
    const ImVec2 pixel = transform.apply(point);
    screen.points.push_back(pixel);
    low = ImVec2(std::min(low.x, pixel.x), std::min(low.y, pixel.y));
    high = ImVec2(std::max(high.x, pixel.x), std::max(high.y, pixel.y));
  }
  screen.centre = transform.apply(taxel.position);
  screen.extent = screen.points.empty() ? 0.0f : std::min(high.x - low.x, high.y - low.y);
  screen.box =
      screen.points.empty() ? SkinViewBox{screen.centre, screen.centre} : SkinViewBox{low, high};
  return screen;
}

void fill_taxel(ImDrawList& draw, const ScreenTaxel& taxel, ImU32 colour) {
  const int count = static_cast<int>(taxel.points.size());
  if (count < 3) return;
  if (taxel.convex) {
    draw.AddConvexPolyFilled(taxel.points.data(), count, colour);
    return;
  }
  for (const std::array<int, 3>& triangle : triangulate(taxel.map_points)) {
    draw.AddTriangleFilled(taxel.points[triangle[0]], taxel.points[triangle[1]],
                           taxel.points[triangle[2]], colour);
  }
}

// A touched taxel again, on top, enlarged about its centre to kTouchedMinPixels when smaller
// (kTinyTouchedPixels when tiny),
// with a dark rim that parts it from its lit neighbours (and a white ring when its fill is a
// region's colour, not its value's). Returns its drawn box.
SkinViewBox draw_touched(ImDrawList& draw, const ScreenTaxel& taxel, ImU32 fill, bool ring) {
  const float least = taxel.extent < kTinyTaxelPixels ? kTinyTouchedPixels : kTouchedMinPixels;
  const float factor =
      taxel.extent > 0.0f && taxel.extent < least
          ? std::min(least / taxel.extent, taxel.extent < kTinyTaxelPixels ? 5.0f : 3.0f)
          : 1.0f;
  ScreenTaxel enlarged = taxel;
  SkinViewBox box{taxel.centre, taxel.centre};
  for (ImVec2& point : enlarged.points) {
    point = ImVec2(taxel.centre.x + factor * (point.x - taxel.centre.x),
                   taxel.centre.y + factor * (point.y - taxel.centre.y));
    box.min = ImVec2(std::min(box.min.x, point.x), std::min(box.min.y, point.y));
    box.max = ImVec2(std::max(box.max.x, point.x), std::max(box.max.y, point.y));
  }
  const int count = static_cast<int>(enlarged.points.size());
  if (count < 3) return box;
  fill_taxel(draw, enlarged, fill);
  draw.AddPolyline(enlarged.points.data(), count, ring ? kHighlight : kOutline, ImDrawFlags_Closed,
                   ring ? 2.0f : 1.0f);
  return box;
}

// The body's silhouette under the taxels: a faint fill and a line. Concave polygons are
// filled by triangles without anti-aliasing, whose fringes would show as seams.
void draw_body_outline(ImDrawList& draw, const SkinLayout& layout, const MapTransform& transform) {
  for (std::vector<Point2> polygon : layout.body_outline) {
    if (polygon.size() < 3) continue;
    if (signed_area(polygon) < 0) std::reverse(polygon.begin(), polygon.end());
    std::vector<ImVec2> points;
    points.reserve(polygon.size());
    for (const Point2& point : polygon) points.push_back(transform.apply(point));
    const int count = static_cast<int>(points.size());
    if (is_convex(polygon)) {
      draw.AddConvexPolyFilled(points.data(), count, kBodyFill);
    } else {
      const ImDrawListFlags flags = draw.Flags;
      draw.Flags &= ~ImDrawListFlags_AntiAliasedFill;
      for (const std::array<int, 3>& triangle : triangulate(polygon))
        draw.AddTriangleFilled(points[triangle[0]], points[triangle[1]], points[triangle[2]],
                               kBodyFill);
      draw.Flags = flags;
    }
    draw.AddPolyline(points.data(), count, kBodyLine, ImDrawFlags_Closed, 1.5f);
  }
}

void taxel_tooltip(const SkinLayout& layout, const Taxel& taxel, float value, bool has_value) {
  ImGui::BeginTooltip();
  ImGui::Text("Taxel %lld  %s", static_cast<long long>(taxel.id), taxel.name.c_str());
  // A taxel of one channel named otherwise (a grid's r3c14 records ch94): the recorded name.
  const auto channel = std::find_if(taxel.channels.begin(), taxel.channels.end(),
                                    [](int index) { return index >= 0; });
  if (std::count_if(taxel.channels.begin(), taxel.channels.end(),
                    [](int index) { return index >= 0; }) == 1 &&
      static_cast<size_t>(*channel) < layout.channels.size() &&
      layout.channels[static_cast<size_t>(*channel)].name != taxel.name)
    ImGui::Text("Channel: %s", layout.channels[static_cast<size_t>(*channel)].name.c_str());
  if (!taxel.body_part.empty()) ImGui::Text("Body part: %s", taxel.body_part.c_str());
  std::string groups;
  for (const Group* group : layout.groups_of(taxel.id)) {
    if (!groups.empty()) groups += ", ";
    groups += group->name.empty() ? group->id : group->name;
  }
  if (!groups.empty()) ImGui::Text("Groups: %s", groups.c_str());
  if (!has_value) {
    ImGui::TextUnformatted("Value: none");
  } else if (std::isnan(value)) {
    ImGui::TextUnformatted("Value: missing (NaN)");
  } else {
    ImGui::Text("Value: %.6g", value);
  }
  ImGui::EndTooltip();
}

// Updates the caller's zoom from the mouse, then applies it to the fitted transform:
// screen = centre + zoom * (fitted - centre) + pan.
void apply_zoom(SkinViewZoom& zoom, SkinViewGeometry& geometry, bool hovered, ImVec2 mouse) {
  const ImGuiIO& io = ImGui::GetIO();
  const double centre_x = geometry.map_min.x + 0.5 * geometry.map_size.x;
  const double centre_y = geometry.map_min.y + 0.5 * geometry.map_size.y;
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) zoom = SkinViewZoom{};
  if (hovered && io.MouseWheel != 0.0f) {
    // Keep the map point under the pointer where it is.
    const double factor = std::pow(1.2, static_cast<double>(io.MouseWheel));
    const double next = std::clamp(zoom.zoom * factor, 1.0, 40.0);
    const double applied = next / zoom.zoom;
    zoom.pan_x = (mouse.x - centre_x) - applied * (mouse.x - centre_x - zoom.pan_x);
    zoom.pan_y = (mouse.y - centre_y) - applied * (mouse.y - centre_y - zoom.pan_y);
    zoom.zoom = next;
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
    zoom.pan_x += io.MouseDelta.x;
    zoom.pan_y += io.MouseDelta.y;
  }
  if (zoom.zoom <= 1.0) zoom.pan_x = zoom.pan_y = 0.0;
  MapTransform& transform = geometry.transform;
  transform.offset_x = centre_x + zoom.zoom * (transform.offset_x - centre_x) + zoom.pan_x;
  transform.offset_y = centre_y + zoom.zoom * (transform.offset_y - centre_y) + zoom.pan_y;
  transform.scale *= zoom.zoom;
}

bool has_side_groups(const SkinLayout& layout) {
  return std::any_of(layout.groups.begin(), layout.groups.end(),
                     [](const Group& group) { return group.kind == "side"; });
}

}  // namespace

//---- Public

MapTransform fit_map(const SkinLayout& layout, ImVec2 top_left, ImVec2 size, float margin) {
  MapTransform transform;
  const float usable_x = std::max(size.x - 2.0f * margin, 1.0f);
  const float usable_y = std::max(size.y - 2.0f * margin, 1.0f);
  if (layout.taxels.empty()) {
    transform.offset_x = top_left.x + 0.5 * size.x;
    transform.offset_y = top_left.y + 0.5 * size.y;
    return transform;
  }
  auto [low, high] = layout.bounds();
  for (const std::vector<Point2>& polygon : layout.body_outline)
    for (const Point2& point : polygon) {
      low = {std::min(low.x, point.x), std::min(low.y, point.y)};
      high = {std::max(high.x, point.x), std::max(high.y, point.y)};
    }
  const double width = high.x - low.x;
  const double height = high.y - low.y;
  // A map of zero width or height (one stripe, one row of points) still fits the other way.
  const double scale_x = width > 0 ? usable_x / width : std::numeric_limits<double>::infinity();
  const double scale_y = height > 0 ? usable_y / height : std::numeric_limits<double>::infinity();
  transform.scale = std::min(scale_x, scale_y);
  if (!std::isfinite(transform.scale)) transform.scale = 1.0;
  transform.offset_x =
      top_left.x + margin + 0.5 * (usable_x - width * transform.scale) - low.x * transform.scale;
  transform.offset_y =
      top_left.y + margin + 0.5 * (usable_y - height * transform.scale) - low.y * transform.scale;
  return transform;
}

SkinViewGeometry skin_view_geometry(const SkinLayout& layout, ImVec2 top_left, ImVec2 size,
                                    const SkinViewStyle& style) {
  // Side names go above their taxels: keep a line free for them.
  const float label_line =
      style.show_group_names && has_side_groups(layout) ? ImGui::GetFontSize() : 0.0f;
  const ImVec2 below_names(size.x, std::max(size.y - label_line, 1.0f));
  const auto fitted = [&](ImVec2 map_size) {
    SkinViewGeometry geometry;
    geometry.map_min = ImVec2(top_left.x, top_left.y + label_line);
    geometry.map_size = ImVec2(std::max(map_size.x, 1.0f), std::max(map_size.y, 1.0f));
    geometry.transform = fit_map(layout, geometry.map_min, geometry.map_size, kMapMargin);
    return geometry;
  };
  if (!style.show_legend) return fitted(below_names);
  const float right_width =
      style.categories
          ? std::min(skin_parts::category_legend_width(*style.categories, size.y), 0.45f * size.x)
          : skin_parts::kLegendWidth;
  SkinViewGeometry right = fitted(ImVec2(below_names.x - right_width, below_names.y));
  right.legend_min = ImVec2(top_left.x + right.map_size.x, top_left.y);
  right.legend_size = ImVec2(size.x - right.map_size.x, size.y);
  if (style.categories) {
    // A legend of many regions beside a narrow panel left the map its left 60 %: then it goes
    // under the map, in as many columns as the width holds.
    if (right_width <= 0.3f * size.x) return right;
    const float strip = skin_parts::category_legend_height(*style.categories, size.x);
    if (strip > 0.4f * size.y) return right;
    SkinViewGeometry bottom = fitted(ImVec2(below_names.x, below_names.y - strip));
    bottom.legend_along_bottom = true;
    bottom.legend_min = ImVec2(top_left.x, top_left.y + size.y - strip);
    bottom.legend_size = ImVec2(size.x, strip);
    return bottom;
  }
  // The colour scale along the bottom instead when the map is wider than the panel's shape
  // and so grows by it.
  const float strip = skin_parts::bottom_legend_height();
  SkinViewGeometry bottom = fitted(ImVec2(below_names.x, below_names.y - strip));
  if (bottom.transform.scale <= 1.02 * right.transform.scale) return right;
  bottom.legend_along_bottom = true;
  bottom.legend_min = ImVec2(top_left.x, top_left.y + size.y - strip);
  bottom.legend_size = ImVec2(size.x, strip);
  return bottom;
}

float scale_position(float value, double value_min, double value_max) {
  if (value_max == value_min) return std::isnan(value) ? value : 0.5f;
  return static_cast<float>((value - value_min) / (value_max - value_min));
}

SkinViewResult draw_skin_view(const char* id, const SkinLayout& layout,
                              std::span<const float> taxel_values, double value_min,
                              double value_max, ImVec2 size, const SkinViewStyle& style) {
  SkinViewResult result;
  ImGui::PushID(id);
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  SkinViewGeometry geometry = skin_view_geometry(layout, origin, size, style);

  ImGui::SetCursorScreenPos(geometry.map_min);
  ImGui::InvisibleButton("map", geometry.map_size,
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hovered = ImGui::IsItemHovered();
  const bool clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  if (style.zoom) apply_zoom(*style.zoom, geometry, hovered, mouse);
  result.transform = geometry.transform;

  // From the top of the view: side names sit in the line above the map.
  const ImVec2 map_max(geometry.map_min.x + geometry.map_size.x,
                       geometry.map_min.y + geometry.map_size.y);
  draw.PushClipRect(origin, map_max, true);
  draw_body_outline(draw, layout, geometry.transform);
  const SkinViewCategories* categories = style.categories;
  const auto fill_of = [&](size_t index, float position) -> ImU32 {
    if (!categories) return pack_abgr(viridis(position));
    const int category = index < categories->of_taxel.size() ? categories->of_taxel[index] : -1;
    return category >= 0 && category < static_cast<int>(categories->colours.size())
               ? categories->colours[static_cast<size_t>(category)]
               : kNoCategory;
  };
  const ScreenTaxel* hovered_outline = nullptr;
  std::vector<ScreenTaxel> screens;
  screens.reserve(layout.taxels.size());
  std::vector<float> positions(layout.taxels.size());
  std::vector<std::pair<float, size_t>> touched;
  for (size_t index = 0; index < layout.taxels.size(); ++index) {
    const Taxel& taxel = layout.taxels[index];
    const double spacing = index < style.neighbour_distances.size()
                               ? style.neighbour_distances[index]
                               : std::numeric_limits<double>::quiet_NaN();
    screens.push_back(screen_taxel(taxel, geometry.transform, spacing, style.min_taxel_pixels));
    const ScreenTaxel& screen = screens.back();
    // Missing values (a short array) are drawn like NaN, grey, never read past the end.
    const float value =
        index < taxel_values.size() ? taxel_values[index] : std::numeric_limits<float>::quiet_NaN();
    positions[index] = scale_position(value, value_min, value_max);
    fill_taxel(draw, screen, fill_of(index, positions[index]));
    if (screen.extent >= kOutlineMinPixels && screen.points.size() >= 2) {
      draw.AddPolyline(screen.points.data(), static_cast<int>(screen.points.size()), kOutline,
                       ImDrawFlags_Closed, 1.0f);
    }
    if (positions[index] >= kTouchedPosition) touched.emplace_back(positions[index], index);
    if (hovered && point_in_polygon(screen.map_points, geometry.transform.invert(mouse))) {
      result.hovered_taxel = taxel.id;
      hovered_outline = &screen;
    }
  }
  for (const ScreenTaxel& screen : screens) result.taxels.push_back(screen.box);
  // Touched taxels on top of their neighbours, the strongest last.
  std::stable_sort(touched.begin(), touched.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [position, index] : touched) {
    result.taxels[index] =
        draw_touched(draw, screens[index], fill_of(index, position), categories != nullptr);
    result.touched_taxels.push_back(layout.taxels[index].id);
  }
  // Selected taxels: a thick outline, drawn over the fills of their neighbours.
  for (size_t index = 0; index < layout.taxels.size(); ++index) {
    const auto& selected = style.selected_taxels;
    if (std::find(selected.begin(), selected.end(), layout.taxels[index].id) == selected.end())
      continue;
    const ScreenTaxel& screen = screens[index];
    draw.AddPolyline(screen.points.data(), static_cast<int>(screen.points.size()), kSelection,
                     ImDrawFlags_Closed, 3.0f);
  }
  if (hovered_outline) {
    draw.AddPolyline(hovered_outline->points.data(),
                     static_cast<int>(hovered_outline->points.size()), kHighlight,
                     ImDrawFlags_Closed, 2.0f);
  }
  if (style.show_group_names) {
    // Names keep clear of the taxels as drawn untouched, so they do not move with a touch.
    std::vector<SkinViewBox> boxes;
    boxes.reserve(screens.size());
    for (const ScreenTaxel& screen : screens) boxes.push_back(screen.box);
    result.names = skin_parts::draw_names(draw, layout, boxes, SkinViewBox{origin, map_max});
  }
  if (taxel_values.size() != layout.taxels.size()) {
    // Said on screen rather than asserted: a mismatch is the caller's data, not a crash.
    char text[96];
    std::snprintf(text, sizeof text, "%zu values for %zu taxels", taxel_values.size(),
                  layout.taxels.size());
    draw.AddText(ImVec2(geometry.map_min.x + 4.0f, geometry.map_min.y + 4.0f),
                 IM_COL32(255, 90, 90, 255), text);
  }
  draw.PopClipRect();

  if (style.show_legend && categories) {
    result.legend = skin_parts::draw_category_legend(draw, geometry.legend_min,
                                                     geometry.legend_size, *categories);
  } else if (style.show_legend) {
    skin_parts::draw_colour_legend(
        draw, geometry.legend_min, geometry.legend_size, geometry.legend_along_bottom, value_min,
        value_max, style.modality_label.empty() ? layout.display_modality : style.modality_label,
        style.values_are_change);
  }

  if (result.hovered_taxel >= 0) {
    const size_t index = static_cast<size_t>(hovered_outline - screens.data());
    taxel_tooltip(layout, layout.taxels[index],
                  index < taxel_values.size() ? taxel_values[index] : 0.0f,
                  index < taxel_values.size());
    if (clicked) result.clicked_taxel = result.hovered_taxel;
  }

  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(size);
  ImGui::PopID();
  return result;
}

SkinViewResult draw_skin_view(const char* id, const SkinLayout& layout,
                              std::span<const float> taxel_values, ImVec2 size,
                              const SkinViewStyle& style) {
  return draw_skin_view(id, layout, taxel_values, layout.display_min, layout.display_max, size,
                        style);
}

}  // namespace tactile

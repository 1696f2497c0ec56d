#include "tactile/widgets/skin_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <vector>

#include "tactile/widgets/colormap.h"
#include "tactile/widgets/polygon.h"

namespace tactile {

namespace {

constexpr float kMapMargin = 8.0f;
constexpr float kLegendWidth = 76.0f;
constexpr float kLegendBarWidth = 14.0f;
constexpr int kLegendSteps = 32;
constexpr float kOutlineMinPixels = 6.0f;  // smaller taxels: outlines would hide the fill

const ImU32 kOutline = IM_COL32(18, 18, 22, 255);
// Selected taxels: the colour of the time cursor, so "what is selected" reads as one thing.
const ImU32 kSelection = IM_COL32(255, 140, 40, 255);
const ImU32 kHighlight = IM_COL32(255, 255, 255, 255);
const ImU32 kText = IM_COL32(225, 225, 230, 255);
const ImU32 kTextShadow = IM_COL32(0, 0, 0, 200);

// A taxel's outline on screen, clockwise on the y-down screen as ImGui's
// anti-aliased fill wants.
struct ScreenTaxel {
  std::vector<ImVec2> points;
  std::vector<Point2> map_points;
  bool convex = true;
  float extent = 0.0f;  // smaller side of its screen bounding box
};

ScreenTaxel screen_taxel(const Taxel& taxel, const MapTransform& transform) {
  ScreenTaxel screen;
  screen.map_points = taxel_outline(taxel);
  if (signed_area(screen.map_points) < 0) {
    std::reverse(screen.map_points.begin(), screen.map_points.end());
  }
  screen.convex = is_convex(screen.map_points);
  ImVec2 low(std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
  ImVec2 high(-low.x, -low.y);
  for (const Point2& point : screen.map_points) {
    const ImVec2 pixel = transform.apply(point);
    screen.points.push_back(pixel);
    low = ImVec2(std::min(low.x, pixel.x), std::min(low.y, pixel.y));
    high = ImVec2(std::max(high.x, pixel.x), std::max(high.y, pixel.y));
  }
  screen.extent = screen.points.empty() ? 0.0f : std::min(high.x - low.x, high.y - low.y);
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

void shadowed_text(ImDrawList& draw, ImVec2 centre, float font_size, const std::string& text) {
  const ImVec2 extent = ImGui::GetFont()->CalcTextSizeA(font_size, FLT_MAX, 0.0f, text.c_str());
  const ImVec2 at(std::floor(centre.x - 0.5f * extent.x), std::floor(centre.y - 0.5f * extent.y));
  draw.AddText(ImGui::GetFont(), font_size, ImVec2(at.x + 1, at.y + 1), kTextShadow, text.c_str());
  draw.AddText(ImGui::GetFont(), font_size, at, kText, text.c_str());
}

bool is_side_group(const Group& group) { return group.kind == "side"; }
bool is_part_group(const Group& group) {
  return group.kind == "body-part" || group.kind == "location";
}
bool has_side_groups(const SkinLayout& layout) {
  return std::any_of(layout.groups.begin(), layout.groups.end(), is_side_group);
}
const std::string& group_label(const Group& group) {
  return group.name.empty() ? group.id : group.name;
}

// Names of body-part and location groups at the centroid of their taxels, one name
// per side (a body part seen on the front and on the back map is named on both, not
// half-way between), and side names centred above their taxels, so a viewer
// recognises the map.
void draw_group_names(ImDrawList& draw, const SkinLayout& layout, const MapTransform& transform) {
  const float font_size = ImGui::GetFontSize() * 0.85f;
  std::map<int64_t, size_t> side_of;  // taxel id -> index of its side group
  for (size_t index = 0; index < layout.groups.size(); ++index) {
    if (!is_side_group(layout.groups[index])) continue;
    for (int64_t id : layout.groups[index].taxels) side_of.emplace(id, index);
  }
  // Names are placed greedily, biggest group first, and a name that would overlap one
  // already drawn, or (a body part) is wider than its part on screen, is left out: zoom
  // in to see it; the tooltip still names every taxel's groups.
  struct Placed {
    ImVec2 min, max;
  };
  std::vector<Placed> placed;
  auto place = [&](ImVec2 centre, const std::string& text, float max_width) {
    const ImVec2 extent = ImGui::GetFont()->CalcTextSizeA(font_size, FLT_MAX, 0.0f, text.c_str());
    if (extent.x > max_width) return;
    const ImVec2 low(centre.x - 0.5f * extent.x - 2.0f, centre.y - 0.5f * extent.y);
    const ImVec2 high(centre.x + 0.5f * extent.x + 2.0f, centre.y + 0.5f * extent.y);
    for (const Placed& other : placed)
      if (low.x < other.max.x && other.min.x < high.x && low.y < other.max.y &&
          other.min.y < high.y)
        return;
    placed.push_back({low, high});
    shadowed_text(draw, centre, font_size, text);
  };
  std::vector<const Group*> parts;
  for (const Group& group : layout.groups) {
    if (is_side_group(group)) {
      double top = std::numeric_limits<double>::infinity();
      double left = top, right = -top;
      for (int64_t id : group.taxels) {
        const Taxel* taxel = layout.find_taxel(id);
        if (!taxel) continue;
        for (const Point2& point : taxel_outline(*taxel)) {
          top = std::min(top, point.y);
          left = std::min(left, point.x);
          right = std::max(right, point.x);
        }
      }
      if (!std::isfinite(top)) continue;
      const ImVec2 anchor = transform.apply({0.5 * (left + right), top});
      place(ImVec2(anchor.x, anchor.y - 0.6f * ImGui::GetFontSize()), group_label(group), FLT_MAX);
    } else if (is_part_group(group)) {
      parts.push_back(&group);
    }
  }
  std::stable_sort(parts.begin(), parts.end(), [](const Group* a, const Group* b) {
    return a->taxels.size() > b->taxels.size();
  });
  for (const Group* group : parts) {
    struct Part {
      Point2 sum{0.0, 0.0};  // of the members' centres
      int members = 0;
      double left = std::numeric_limits<double>::infinity();
      double right = -std::numeric_limits<double>::infinity();
    };
    std::map<size_t, Part> by_side;  // the part's taxels on each side of the map
    for (int64_t id : group->taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      if (!taxel) continue;
      const auto side = side_of.find(id);
      Part& part = by_side[side == side_of.end() ? SIZE_MAX : side->second];
      part.sum.x += taxel->position.x;
      part.sum.y += taxel->position.y;
      ++part.members;
      part.left = std::min(part.left, taxel->position.x - 0.5 * taxel->size.x);
      part.right = std::max(part.right, taxel->position.x + 0.5 * taxel->size.x);
    }
    for (const auto& [side, part] : by_side) {
      const Point2 centroid{part.sum.x / part.members, part.sum.y / part.members};
      const float width = static_cast<float>((part.right - part.left) * transform.scale);
      // A little wider than the part is still read as its name.
      place(transform.apply(centroid), group_label(*group), 1.2f * width + 8.0f);
    }
  }
}

void draw_legend(ImDrawList& draw, ImVec2 top_left, ImVec2 size, double value_min, double value_max,
                 const std::string& label, bool change) {
  const float line = ImGui::GetTextLineHeight();
  const float bar_left = top_left.x + 8.0f;
  const float bar_top = top_left.y + 1.5f * line + 4.0f;
  const float bar_bottom = top_left.y + size.y - 0.5f * line - 4.0f;
  if (bar_bottom - bar_top < 8.0f) return;
  // Position 1 (value_max) at the top, 0 (value_min) at the bottom.
  for (int step = 0; step < kLegendSteps; ++step) {
    const float upper = 1.0f - static_cast<float>(step) / kLegendSteps;
    const float lower = 1.0f - static_cast<float>(step + 1) / kLegendSteps;
    const float y0 = bar_top + (bar_bottom - bar_top) * (1.0f - upper);
    const float y1 = bar_top + (bar_bottom - bar_top) * (1.0f - lower);
    const ImU32 top_colour = pack_abgr(viridis(upper));
    const ImU32 bottom_colour = pack_abgr(viridis(lower));
    draw.AddRectFilledMultiColor(ImVec2(bar_left, y0), ImVec2(bar_left + kLegendBarWidth, y1),
                                 top_colour, top_colour, bottom_colour, bottom_colour);
  }
  draw.AddRect(ImVec2(bar_left, bar_top), ImVec2(bar_left + kLegendBarWidth, bar_bottom), kOutline);
  char text[32];
  std::snprintf(text, sizeof text, change ? "+%.3g" : "%.3g", value_max);
  draw.AddText(ImVec2(bar_left + kLegendBarWidth + 4.0f, bar_top - 0.5f * line), kText, text);
  if (change)
    std::snprintf(text, sizeof text, "rest");
  else
    std::snprintf(text, sizeof text, "%.3g", value_min);
  draw.AddText(ImVec2(bar_left + kLegendBarWidth + 4.0f, bar_bottom - 0.5f * line), kText, text);
  if (!label.empty()) {
    const ImVec4 clip(top_left.x, top_left.y, top_left.x + size.x, top_left.y + size.y);
    draw.AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(bar_left - 4.0f, top_left.y + 2.0f),
                 kText, label.c_str(), nullptr, 0.0f, &clip);
  }
}

void taxel_tooltip(const SkinLayout& layout, const Taxel& taxel, float value, bool has_value) {
  ImGui::BeginTooltip();
  ImGui::Text("Taxel %lld  %s", static_cast<long long>(taxel.id), taxel.name.c_str());
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
  const auto [low, high] = layout.bounds();
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
  SkinViewGeometry geometry;
  // Side names go above their taxels: keep a line free for them.
  const float label_line =
      style.show_group_names && has_side_groups(layout) ? ImGui::GetFontSize() : 0.0f;
  geometry.map_min = ImVec2(top_left.x, top_left.y + label_line);
  geometry.map_size = ImVec2(std::max(size.x - (style.show_legend ? kLegendWidth : 0.0f), 1.0f),
                             std::max(size.y - label_line, 1.0f));
  geometry.transform = fit_map(layout, geometry.map_min, geometry.map_size, kMapMargin);
  return geometry;
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
  draw.PushClipRect(
      origin,
      ImVec2(geometry.map_min.x + geometry.map_size.x, geometry.map_min.y + geometry.map_size.y),
      true);
  const ScreenTaxel* hovered_outline = nullptr;
  std::vector<ScreenTaxel> screens;
  screens.reserve(layout.taxels.size());
  for (size_t index = 0; index < layout.taxels.size(); ++index) {
    const Taxel& taxel = layout.taxels[index];
    screens.push_back(screen_taxel(taxel, geometry.transform));
    const ScreenTaxel& screen = screens.back();
    // Missing values (a short array) are drawn like NaN, grey, never read past the end.
    const float value =
        index < taxel_values.size() ? taxel_values[index] : std::numeric_limits<float>::quiet_NaN();
    fill_taxel(draw, screen, pack_abgr(viridis(scale_position(value, value_min, value_max))));
    if (screen.extent >= kOutlineMinPixels && screen.points.size() >= 2) {
      draw.AddPolyline(screen.points.data(), static_cast<int>(screen.points.size()), kOutline,
                       ImDrawFlags_Closed, 1.0f);
    }
    if (hovered && point_in_polygon(screen.map_points, geometry.transform.invert(mouse))) {
      result.hovered_taxel = taxel.id;
      hovered_outline = &screen;
    }
  }
  // Selected taxels: a thick white outline, drawn over the fills of their neighbours.
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
  if (style.show_group_names) draw_group_names(draw, layout, geometry.transform);
  if (taxel_values.size() != layout.taxels.size()) {
    // Said on screen rather than asserted: a mismatch is the caller's data, not a crash.
    char text[96];
    std::snprintf(text, sizeof text, "%zu values for %zu taxels", taxel_values.size(),
                  layout.taxels.size());
    draw.AddText(ImVec2(geometry.map_min.x + 4.0f, geometry.map_min.y + 4.0f),
                 IM_COL32(255, 90, 90, 255), text);
  }
  draw.PopClipRect();

  if (style.show_legend) {
    const ImVec2 legend_min(origin.x + geometry.map_size.x, origin.y);
    draw_legend(draw, legend_min, ImVec2(size.x - geometry.map_size.x, size.y), value_min,
                value_max,
                style.modality_label.empty() ? layout.display_modality : style.modality_label,
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

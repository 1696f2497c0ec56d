#pragma once
// SkinView: a skin layout's unwrapped map, each taxel filled with the viridis colour
// of its value, with a colour legend, body-part names and a hover tooltip.

#include <imgui.h>

#include <cstdint>
#include <span>
#include <string>

#include "tactile/layout/skin_layout.h"

namespace tactile {

// Map (mm, y down) to screen pixels: screen = offset + scale * map.
struct MapTransform {
  double scale = 1.0;
  double offset_x = 0.0;
  double offset_y = 0.0;

  ImVec2 apply(Point2 point) const {
    return ImVec2(static_cast<float>(offset_x + scale * point.x),
                  static_cast<float>(offset_y + scale * point.y));
  }
  Point2 invert(ImVec2 screen) const {
    return {(screen.x - offset_x) / scale, (screen.y - offset_y) / scale};
  }
};

// Fits the layout's bounds into the rectangle less `margin` on each side, aspect
// ratio kept, centred.
MapTransform fit_map(const SkinLayout& layout, ImVec2 top_left, ImVec2 size, float margin);

// Zoom and pan of a skin view, kept by the caller between frames: the mouse wheel zooms
// about the pointer, dragging with the right button pans, a double-click resets.
struct SkinViewZoom {
  double zoom = 1.0;   // 1 = the whole layout fitted into the view
  double pan_x = 0.0;  // pixels
  double pan_y = 0.0;
};

struct SkinViewStyle {
  bool show_legend = true;
  bool show_group_names = true;     // names of "body-part", "location" and "side" groups
  std::string modality_label = {};  // legend title; empty: the layout's display modality
  // The values are changes from each taxel's rest level, not readings: the legend's scale
  // reads "rest" at the bottom and "+max" at the top.
  bool values_are_change = false;
  SkinViewZoom* zoom = nullptr;     // interactive zoom and pan when given
  std::span<const int64_t> selected_taxels = {};  // outlined (taxel ids)
};

struct SkinViewResult {
  int64_t hovered_taxel = -1;  // taxel id under the mouse, -1 for none
  int64_t clicked_taxel = -1;  // taxel id clicked this frame, -1 for none
  MapTransform transform;      // where the map was drawn this frame
};

// Where draw_skin_view puts the map inside its rectangle (the legend takes the
// right-hand strip).
struct SkinViewGeometry {
  ImVec2 map_min, map_size;
  MapTransform transform;
};
SkinViewGeometry skin_view_geometry(const SkinLayout& layout, ImVec2 top_left, ImVec2 size,
                                    const SkinViewStyle& style = {});

// Colour scale position of a value: (value - value_min) / (value_max - value_min),
// so value_min > value_max reverses the scale; not clamped; NaN stays NaN.
float scale_position(float value, double value_min, double value_max);

// Draws at the current cursor position of the current window. `taxel_values` is
// in layout.taxels order (NaN: no value, drawn grey); values are mapped through
// [value_min, value_max].
SkinViewResult draw_skin_view(const char* id, const SkinLayout& layout,
                              std::span<const float> taxel_values, double value_min,
                              double value_max, ImVec2 size, const SkinViewStyle& style = {});
// The same with the layout's own display range (display_min, display_max).
SkinViewResult draw_skin_view(const char* id, const SkinLayout& layout,
                              std::span<const float> taxel_values, ImVec2 size,
                              const SkinViewStyle& style = {});

}  // namespace tactile

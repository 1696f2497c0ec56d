#pragma once
// SkinView: a skin layout's unwrapped map over the body's outline, each taxel filled with the
// viridis colour of its value (or the colour of its body region), with a legend, body-part
// names beside their taxels and a hover tooltip.

#include <imgui.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

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

// Fits the layout's bounds and its body outline into the rectangle less `margin` on each
// side, aspect ratio kept, centred.
MapTransform fit_map(const SkinLayout& layout, ImVec2 top_left, ImVec2 size, float margin);

// Zoom and pan of a skin view, kept by the caller between frames: the mouse wheel zooms
// about the pointer, dragging with the right button pans, a double-click resets.
struct SkinViewZoom {
  double zoom = 1.0;   // 1 = the whole layout fitted into the view
  double pan_x = 0.0;  // pixels
  double pan_y = 0.0;
};

// Taxels coloured by category (body regions) instead of by value.
struct SkinViewCategories {
  std::vector<int> of_taxel;       // per taxel (layout order): index into names, -1 for none
  std::vector<std::string> names;  // in legend order
  std::vector<uint32_t> colours;   // per name, packed as IM_COL32
};

struct SkinViewStyle {
  bool show_legend = true;
  // Names of "body-part", "location", "region", "zone" and "layer" groups beside their taxels,
  // of "side" groups above them, and of taxels big enough to hold their name.
  bool show_group_names = true;
  std::string modality_label = {};  // legend title; empty: the layout's display modality
  // The values are changes from each taxel's rest level, not readings: the legend's scale
  // reads "rest" at the bottom and "+max" at the top.
  bool values_are_change = false;
  SkinViewZoom* zoom = nullptr;                   // interactive zoom and pan when given
  std::span<const int64_t> selected_taxels = {};  // outlined (taxel ids)
  // Per taxel (layout order), the distance to its nearest neighbour (nearest_taxel_distances):
  // a taxel smaller than its spacing is drawn larger, up to a pixel short of touching its
  // neighbours, so its drawn size follows the panel. Empty: each taxel at its own size.
  std::span<const double> neighbour_distances = {};
  // Taxels drawn smaller than this many pixels across are drawn this large, about their centres
  // (a somatosensory map's dots); 0: as the layout sizes them.
  float min_taxel_pixels = 0.0f;
  // Fill by category, legend of the categories; the values then show only as a ring around
  // touched taxels. Null: fill by value, colour-scale legend.
  const SkinViewCategories* categories = nullptr;
};

// A rectangle on screen (pixels).
struct SkinViewBox {
  ImVec2 min, max;
};
// A name drawn by the view: a group's (id: the group id), a taxel's (id: its name) or a
// legend entry's (id: the category name; box: its swatch).
struct SkinViewLabel {
  std::string id;
  std::string text;
  SkinViewBox box;
};

struct SkinViewResult {
  int64_t hovered_taxel = -1;           // taxel id under the mouse, -1 for none
  int64_t clicked_taxel = -1;           // taxel id clicked this frame, -1 for none
  MapTransform transform;               // where the map was drawn this frame
  std::vector<SkinViewBox> taxels;      // per taxel (layout order): its drawn box
  std::vector<int64_t> touched_taxels;  // drawn enlarged as touched this frame (ids)
  std::vector<SkinViewLabel> names;     // group and taxel names on the map
  std::vector<SkinViewLabel> legend;    // category legend entries (none for a colour scale)
};

// Where draw_skin_view puts the map and the legend inside its rectangle: the colour scale
// on the right, or along the bottom when that leaves the map larger; a category legend on
// the right.
struct SkinViewGeometry {
  ImVec2 map_min, map_size;
  MapTransform transform;
  ImVec2 legend_min, legend_size;  // empty without a legend
  bool legend_along_bottom = false;
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

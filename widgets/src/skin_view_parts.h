#pragma once
// The skin view's two files share these: skin_view.cpp draws the map (outline, taxels, the
// touched ones, zoom, tooltip), skin_view_labels.cpp the words (names beside the patches,
// the legends).

#include <imgui.h>

#include <span>
#include <string>
#include <vector>

#include "tactile/widgets/skin_view.h"

namespace tactile::skin_parts {

inline constexpr float kLegendWidth = 76.0f;  // the colour scale on the right
inline const ImU32 kText = IM_COL32(225, 225, 230, 255);
inline const ImU32 kTextShadow = IM_COL32(0, 0, 0, 200);
inline const ImU32 kOutline = IM_COL32(18, 18, 22, 255);

// The height of the colour scale laid along the bottom.
float bottom_legend_height();
// The width of a category legend `height` high: its longest name, a swatch and margins, once
// per column (a second column when the names do not fit one above the other).
float category_legend_width(const SkinViewCategories& categories, float height);
// The height of the legend laid under the map in as many columns as `width` holds.
float category_legend_height(const SkinViewCategories& categories, float width);

bool boxes_overlap(const SkinViewBox& a, const SkinViewBox& b);

// Text with a one-pixel shadow, its top left at `at`.
void shadowed_text(ImDrawList& draw, ImVec2 at, const std::string& text, ImU32 colour = kText);

// Side names above their taxels, names of body parts (and locations, regions, zones, layers)
// beside their taxels, never over one, and taxel names inside taxels big enough to hold
// them. `boxes`: each taxel's drawn box (layout order); names stay inside `clip`.
std::vector<SkinViewLabel> draw_names(ImDrawList& draw, const SkinLayout& layout,
                                      std::span<const SkinViewBox> boxes, const SkinViewBox& clip);

// The colour scale: vertical (top = value_max) in a right-hand strip, or horizontal (right =
// value_max) along the bottom.
void draw_colour_legend(ImDrawList& draw, ImVec2 top_left, ImVec2 size, bool horizontal,
                        double value_min, double value_max, const std::string& label, bool change);
// A swatch and a name per category, top to bottom (a second column when they do not fit);
// returns each swatch's box.
std::vector<SkinViewLabel> draw_category_legend(ImDrawList& draw, ImVec2 top_left, ImVec2 size,
                                                const SkinViewCategories& categories);

}  // namespace tactile::skin_parts

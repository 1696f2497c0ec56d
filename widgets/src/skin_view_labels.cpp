// The skin view's words: the names of body parts beside their taxels, of sides above them, of
// big taxels inside them, and the legends (a colour scale, or a list of categories).

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include "skin_view_parts.h"
#include "tactile/widgets/colormap.h"

namespace tactile::skin_parts {

namespace {

constexpr float kNameGap = 4.0f;      // between a patch and its name
constexpr float kClearance = 10.0f;   // a name beside its patch is this much nearer it than others
constexpr float kLeaderStep = 12.0f;  // further out, with a line to the patch, in these steps
constexpr int kLeaderSteps = 5;
constexpr int kMarginCrossings = 4;  // a name in the margin: its line crosses at most this many
const ImU32 kLeader = IM_COL32(200, 200, 210, 150);
constexpr size_t kMostTaxelNames = 64;
constexpr float kLegendBarWidth = 14.0f;
constexpr float kLegendBarHeight = 10.0f;  // the bar of a bottom legend
constexpr int kLegendSteps = 32;
constexpr float kSwatch = 10.0f;

bool is_side_group(const Group& group) { return group.kind == "side"; }
// Groups a viewer knows the body by; modules, sheets and rows are left to the tooltip.
bool is_named_part(const Group& group) {
  return group.kind == "body-part" || group.kind == "location" || group.kind == "region" ||
         group.kind == "zone" || group.kind == "layer";
}
const std::string& name_of_group(const Group& group) {
  return group.name.empty() ? group.id : group.name;
}

SkinViewBox text_box(ImVec2 at, const std::string& text) {
  const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
  return {at, ImVec2(at.x + extent.x, at.y + extent.y)};
}

bool box_inside(const SkinViewBox& inner, const SkinViewBox& outer) {
  return inner.min.x >= outer.min.x && inner.min.y >= outer.min.y && inner.max.x <= outer.max.x &&
         inner.max.y <= outer.max.y;
}

SkinViewBox union_of(const SkinViewBox& a, const SkinViewBox& b) {
  return {ImVec2(std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y)),
          ImVec2(std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y))};
}

// Pixels between two boxes (0 when they overlap).
float box_distance(const SkinViewBox& a, const SkinViewBox& b) {
  const float dx = std::max({0.0f, a.min.x - b.max.x, b.min.x - a.max.x});
  const float dy = std::max({0.0f, a.min.y - b.max.y, b.min.y - a.max.y});
  return std::hypot(dx, dy);
}

// The taxels of one named group on one side of the map.
struct Patch {
  const Group* group;
  SkinViewBox box;
};

// Names placed one by one: a name goes where it stays inside the view and clear of the names
// already placed and (unless it is meant to sit on a taxel) of every taxel.
class NamePlacer {
 public:
  NamePlacer(ImDrawList& draw, std::span<const SkinViewBox> taxels, std::span<const Patch> patches,
             SkinViewBox clip)
      : draw_(draw), taxels_(taxels), patches_(patches), clip_(clip) {}

  bool place(const std::string& id, const std::string& text, ImVec2 at, bool on_taxel = false) {
    const SkinViewBox box = text_box(ImVec2(std::floor(at.x), std::floor(at.y)), text);
    if (!free(box, on_taxel)) return false;
    draw(id, text, box);
    return true;
  }

  // Beside its patch: first away from the map's middle (where the map ends there is room),
  // then above, below, then towards the middle; each centred on the patch's side, then flush
  // with either end of it. A name must lie nearer its own patch than any other part's, so it
  // is not read as theirs.
  bool place_beside(const Patch& patch, const std::string& text) {
    if (share_name(patch, text)) return true;
    for (const ImVec2& at : candidates(patch, text, kNameGap)) {
      const SkinViewBox box = text_box(ImVec2(std::floor(at.x), std::floor(at.y)), text);
      if (free(box, false) && nearest_to_own(box, patch) && !echoes(box, text)) {
        draw(patch.group->id, text, box);
        return true;
      }
    }
    return false;
  }

  // For a part with no room beside it, once every part has had its turn there: further out
  // with a line to the patch, the nearest place whose line crosses no other taxel.
  bool place_with_line(const Patch& patch, const std::string& text) {
    if (share_name(patch, text)) return true;
    const SkinViewBox& own = patch.box;
    for (int step = 1; step <= kLeaderSteps; ++step)
      for (const ImVec2& at :
           candidates(patch, text, kNameGap + kLeaderStep * static_cast<float>(step))) {
        const SkinViewBox box = text_box(ImVec2(std::floor(at.x), std::floor(at.y)), text);
        if (!free(box, false)) continue;
        const auto [from, to] = leader_ends(own, box);
        if (crosses_a_taxel(from, to, patch)) continue;
        draw_.AddLine(from, to, kLeader, 1.0f);
        leaders_.push_back({"",
                            "",
                            {ImVec2(std::min(from.x, to.x), std::min(from.y, to.y)),
                             ImVec2(std::max(from.x, to.x) + 1, std::max(from.y, to.y) + 1)}});
        draw(patch.group->id, text, box);
        return true;
      }
    return place_in_margin(patch, text);
  }

  // Places for a name `away` pixels from its patch, on each side in the order place_beside
  // tries them.
  std::vector<ImVec2> candidates(const Patch& patch, const std::string& text, float away) const {
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    const SkinViewBox& own = patch.box;
    const bool on_the_left = own.min.x + own.max.x < clip_.min.x + clip_.max.x;
    const float middle_y = 0.5f * (own.min.y + own.max.y - extent.y);
    const float middle_x = 0.5f * (own.min.x + own.max.x - extent.x);
    const float left = own.min.x - away - extent.x, right = own.max.x + away;
    const float top = own.min.y - away - extent.y, bottom = own.max.y + away;
    const std::vector<ImVec2> left_side = {
        {left, middle_y}, {left, own.min.y}, {left, own.max.y - extent.y}};
    const std::vector<ImVec2> right_side = {
        {right, middle_y}, {right, own.min.y}, {right, own.max.y - extent.y}};
    const std::vector<ImVec2> above = {
        {middle_x, top}, {own.min.x, top}, {own.max.x - extent.x, top}};
    const std::vector<ImVec2> below = {
        {middle_x, bottom}, {own.min.x, bottom}, {own.max.x - extent.x, bottom}};
    std::vector<ImVec2> all;
    for (const auto* side : {on_the_left ? &left_side : &right_side, &above, &below,
                             on_the_left ? &right_side : &left_side})
      all.insert(all.end(), side->begin(), side->end());
    return all;
  }

  // Last, in the margin left or right of the map, clear of every part, with a line across
  // whatever lies between to a dot in the middle of the patch (as an anatomical chart names
  // what lies inside): the line that crosses the fewest taxels.
  bool place_in_margin(const Patch& patch, const std::string& text) {
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    const SkinViewBox& own = patch.box;
    const ImVec2 centre(0.5f * (own.min.x + own.max.x), 0.5f * (own.min.y + own.max.y));
    std::optional<SkinViewBox> best;
    float best_cost = std::numeric_limits<float>::max();
    const float longest = 0.3f * std::min(clip_.max.x - clip_.min.x, clip_.max.y - clip_.min.y);
    // Left and right of the patch's middle (a line or two up or down), then above and below
    // it (centred, or half a name aside).
    std::vector<ImVec2> places;
    for (float away = 0.0f; away <= longest; away += kLeaderStep) {
      for (const float dy : {0.0f, -1.0f, 1.0f, -2.0f, 2.0f})
        for (const float left : {centre.x - away - extent.x, centre.x + away})
          places.push_back({left, centre.y - 0.5f * extent.y + dy * (extent.y + 2.0f)});
      for (const float dx : {0.0f, -0.5f, 0.5f})
        for (const float top : {centre.y - away - extent.y, centre.y + away})
          places.push_back({centre.x - 0.5f * extent.x + dx * extent.x, top});
    }
    for (const ImVec2& place : places) {
      const SkinViewBox box = text_box(ImVec2(std::floor(place.x), std::floor(place.y)), text);
      if (!free(box, false) || overlaps_a_patch(box)) continue;
      const auto [from, to] = margin_leader(centre, box);
      if (crosses_a_name(from, to)) continue;
      // A taxel crossed costs as much as 40 pixels more of line; a line longer than
      // 0.3 of the view would lead the eye astray (a small view names less).
      const float length = std::hypot(to.x - from.x, to.y - from.y);
      if (length > longest) continue;
      const int crossings = crossed_taxels(from, to, patch);
      const float cost = static_cast<float>(crossings) + length / 40.0f;
      if (crossings <= kMarginCrossings && cost < best_cost) best = box, best_cost = cost;
    }
    if (!best) return false;
    const auto [from, to] = margin_leader(centre, *best);
    draw_.AddLine(from, to, kOutline, 3.0f);
    draw_.AddLine(from, to, kLeader, 1.0f);
    draw_.AddCircleFilled(from, 2.5f, kText);
    leaders_.push_back({"",
                        "",
                        {ImVec2(std::min(from.x, to.x), std::min(from.y, to.y)),
                         ImVec2(std::max(from.x, to.x) + 1, std::max(from.y, to.y) + 1)}});
    draw(patch.group->id, text, *best);
    return true;
  }

  std::vector<SkinViewLabel> take() { return std::move(placed_); }

 private:
  bool free(const SkinViewBox& box, bool on_taxel) const {
    if (!box_inside(box, clip_)) return false;
    // Names keep a pixel apart; taxels may be touched by a name's box, not entered.
    const SkinViewBox spaced{ImVec2(box.min.x - 2, box.min.y - 1),
                             ImVec2(box.max.x + 2, box.max.y + 1)};
    for (const SkinViewLabel& other : placed_)
      if (boxes_overlap(spaced, other.box)) return false;
    if (on_taxel) return true;
    const SkinViewBox inner{ImVec2(box.min.x + 0.5f, box.min.y + 0.5f),
                            ImVec2(box.max.x - 0.5f, box.max.y - 0.5f)};
    for (const SkinViewBox& taxel : taxels_)
      if (boxes_overlap(inner, taxel)) return false;
    for (const SkinViewLabel& leader : leaders_)
      if (boxes_overlap(inner, leader.box)) return false;
    return true;
  }

  // A part seen on the front and on the back whose name, written for one side, lies within a
  // name's width of the other side's patch (between the two figures): a line from this patch to
  // that name, not the name again beside it.
  bool share_name(const Patch& patch, const std::string& text) {
    for (const SkinViewLabel& other : placed_) {
      if (other.id != patch.group->id || other.text != text) continue;
      if (box_distance(other.box, patch.box) > other.box.max.x - other.box.min.x) continue;
      const auto [from, to] = leader_ends(patch.box, other.box);
      // Stopping short of the name, which the line is meant to reach.
      const float length = std::hypot(to.x - from.x, to.y - from.y);
      const float short_of = length > 3.0f ? (length - 3.0f) / length : 0.0f;
      if (crosses_a_taxel(
              from,
              ImVec2(from.x + short_of * (to.x - from.x), from.y + short_of * (to.y - from.y)),
              patch))
        continue;
      draw_.AddLine(from, to, kLeader, 1.0f);
      draw_.AddCircleFilled(from, 2.0f, kText);
      leaders_.push_back({"",
                          "",
                          {ImVec2(std::min(from.x, to.x), std::min(from.y, to.y)),
                           ImVec2(std::max(from.x, to.x) + 1, std::max(from.y, to.y) + 1)}});
      placed_.push_back({patch.group->id, text, other.box});
      return true;
    }
    return false;
  }

  // The same name already written on the same line within a name's width: a part seen on the
  // front and the back named twice between the figures read "left hand left hand".
  bool echoes(const SkinViewBox& box, const std::string& text) const {
    const float width = box.max.x - box.min.x;
    for (const SkinViewLabel& other : placed_)
      if (other.text == text && box.min.y < other.box.max.y && other.box.min.y < box.max.y &&
          box_distance(box, other.box) < width)
        return true;
    return false;
  }

  // The name's middle lies nearer its own patch than any other part's, by kClearance.
  bool nearest_to_own(const SkinViewBox& box, const Patch& own) const {
    const ImVec2 middle(0.5f * (box.min.x + box.max.x), 0.5f * (box.min.y + box.max.y));
    const SkinViewBox point{middle, middle};
    const float distance = box_distance(point, own.box);
    for (const Patch& other : patches_) {
      // A group holding this one (a layer holding a zone), or held by it, is not another part.
      if (other.group == own.group || box_inside(own.box, other.box) ||
          box_inside(other.box, own.box))
        continue;
      if (box_distance(point, other.box) < distance + kClearance) return false;
    }
    return true;
  }

  // A leader runs from the patch's edge, facing the name, to the name's nearest point.
  static std::pair<ImVec2, ImVec2> leader_ends(const SkinViewBox& patch, const SkinViewBox& name) {
    const ImVec2 to(std::clamp(0.5f * (patch.min.x + patch.max.x), name.min.x, name.max.x),
                    std::clamp(0.5f * (patch.min.y + patch.max.y), name.min.y, name.max.y));
    const ImVec2 from(std::clamp(to.x, patch.min.x, patch.max.x),
                      std::clamp(to.y, patch.min.y, patch.max.y));
    return {from, to};
  }

  // Whether a leader would pass through (or within 2 pixels of) a taxel or a part outside its
  // own patch, or through a name already placed: then it would point at the wrong thing.
  bool crosses_a_taxel(ImVec2 from, ImVec2 to, const Patch& own) const {
    const auto crosses = [&](const SkinViewBox& box) {
      return segment_enters(
          from, to, {ImVec2(box.min.x - 2, box.min.y - 2), ImVec2(box.max.x + 2, box.max.y + 2)});
    };
    for (const SkinViewBox& taxel : taxels_)
      if (!box_inside(taxel, own.box) && crosses(taxel)) return true;
    for (const Patch& patch : patches_)
      if (patch.group != own.group && crosses(patch.box)) return true;
    for (const SkinViewLabel& name : placed_)
      if (crosses(name.box)) return true;
    return false;
  }

  // From the patch's middle to the name's nearest point, stopping 2 pixels short of it.
  static std::pair<ImVec2, ImVec2> margin_leader(ImVec2 centre, const SkinViewBox& name) {
    const SkinViewBox around{ImVec2(name.min.x - 2, name.min.y - 2),
                             ImVec2(name.max.x + 2, name.max.y + 2)};
    return {centre, ImVec2(std::clamp(centre.x, around.min.x, around.max.x),
                           std::clamp(centre.y, around.min.y, around.max.y))};
  }

  bool overlaps_a_patch(const SkinViewBox& box) const {
    for (const Patch& patch : patches_)
      if (boxes_overlap(box, {ImVec2(patch.box.min.x - 3, patch.box.min.y - 3),
                              ImVec2(patch.box.max.x + 3, patch.box.max.y + 3)}))
        return true;
    return false;
  }

  bool crosses_a_name(ImVec2 from, ImVec2 to) const {
    for (const SkinViewLabel& name : placed_)
      if (segment_enters(from, to, name.box)) return true;
    return false;
  }

  int crossed_taxels(ImVec2 from, ImVec2 to, const Patch& own) const {
    int crossed = 0;
    for (const SkinViewBox& taxel : taxels_)
      crossed += !box_inside(taxel, own.box) && segment_enters(from, to, taxel);
    return crossed;
  }

  // Liang-Barsky: whether the segment from -> to passes through the box.
  static bool segment_enters(ImVec2 from, ImVec2 to, const SkinViewBox& box) {
    float enter = 0.0f, leave = 1.0f;
    for (const auto& [step, low, high] :
         {std::tuple{to.x - from.x, box.min.x - from.x, box.max.x - from.x},
          std::tuple{to.y - from.y, box.min.y - from.y, box.max.y - from.y}}) {
      if (step == 0.0f) {
        if (low > 0.0f || high < 0.0f) return false;
        continue;
      }
      enter = std::max(enter, std::min(low / step, high / step));
      leave = std::min(leave, std::max(low / step, high / step));
    }
    return enter < leave;
  }

  void draw(const std::string& id, const std::string& text, const SkinViewBox& box) {
    shadowed_text(draw_, box.min, text);
    placed_.push_back({id, text, box});
  }

  ImDrawList& draw_;
  std::span<const SkinViewBox> taxels_;
  std::span<const Patch> patches_;
  SkinViewBox clip_;
  std::vector<SkinViewLabel> placed_;
  std::vector<SkinViewLabel> leaders_;
};

// Where a name goes inside a taxel's box: centred, in its upper part, so the middle of the
// taxel keeps showing its colour. None when the box is too small for it.
bool inside_position(const SkinViewBox& box, const std::string& text, ImVec2& at) {
  const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
  const float width = box.max.x - box.min.x, height = box.max.y - box.min.y;
  if (extent.x > 0.7f * width || 3.0f * extent.y > height) return false;
  at = ImVec2(box.min.x + 0.5f * (width - extent.x), box.min.y + 0.15f * height);
  return true;
}

}  // namespace

bool boxes_overlap(const SkinViewBox& a, const SkinViewBox& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

void shadowed_text(ImDrawList& draw, ImVec2 at, const std::string& text, ImU32 colour) {
  draw.AddText(ImVec2(at.x + 1, at.y + 1), kTextShadow, text.c_str());
  draw.AddText(at, colour, text.c_str());
}

//---- Names

std::vector<SkinViewLabel> draw_names(ImDrawList& draw, const SkinLayout& layout,
                                      std::span<const SkinViewBox> boxes, const SkinViewBox& clip) {
  std::map<int64_t, size_t> index_of;  // taxel id -> layout index
  for (size_t index = 0; index < layout.taxels.size() && index < boxes.size(); ++index)
    index_of.emplace(layout.taxels[index].id, index);
  std::map<int64_t, size_t> side_of;  // taxel id -> index of its side group
  for (size_t group = 0; group < layout.groups.size(); ++group) {
    if (!is_side_group(layout.groups[group])) continue;
    for (int64_t id : layout.groups[group].taxels) side_of.emplace(id, group);
  }
  // The patch of a group's taxels on each side of the map (a body part seen on the front and
  // on the back is named on both, not half-way between).
  const auto patches_of = [&](const Group& group, bool by_side) {
    std::map<size_t, SkinViewBox> patches;
    for (int64_t id : group.taxels) {
      const auto found = index_of.find(id);
      if (found == index_of.end()) continue;
      const auto side = side_of.find(id);
      const size_t key = by_side && side != side_of.end() ? side->second : SIZE_MAX;
      const SkinViewBox& box = boxes[found->second];
      const auto [place, inserted] = patches.emplace(key, box);
      if (!inserted) place->second = union_of(place->second, box);
    }
    return patches;
  };
  // Parts, biggest first.
  std::vector<const Group*> parts;
  for (const Group& group : layout.groups)
    if (is_named_part(group)) parts.push_back(&group);
  std::stable_sort(parts.begin(), parts.end(), [](const Group* a, const Group* b) {
    return a->taxels.size() > b->taxels.size();
  });
  std::vector<Patch> patches;
  for (const Group* group : parts)
    for (const auto& [side, box] : patches_of(*group, true)) patches.push_back({group, box});
  NamePlacer placer(draw, boxes, patches, clip);
  std::vector<bool> named_inside(boxes.size(), false);
  std::vector<const Patch*> crowded;  // no room beside them

  // Side names centred above their taxels, in the line the view keeps free for them.
  for (const Group& group : layout.groups) {
    if (!is_side_group(group)) continue;
    for (const auto& [side, patch] : patches_of(group, false)) {
      const ImVec2 extent = ImGui::CalcTextSize(name_of_group(group).c_str());
      placer.place(
          group.id, name_of_group(group),
          ImVec2(0.5f * (patch.min.x + patch.max.x - extent.x), patch.min.y - extent.y - 2.0f),
          true);
    }
  }
  // A part of one taxel big enough to hold its name (a flux zone) is named on it; the others
  // beside their patches. A part with no room near it is left out: zoom in to see it; the
  // tooltip names every taxel's groups.
  for (const Patch& patch : patches) {
    const Group& group = *patch.group;
    const std::string& text = name_of_group(group);
    if (group.taxels.size() == 1) {
      const auto found = index_of.find(group.taxels.front());
      ImVec2 at;
      if (found != index_of.end() && inside_position(boxes[found->second], text, at) &&
          placer.place(group.id, text, at, true)) {
        named_inside[found->second] = true;
        continue;
      }
    }
    if (!placer.place_beside(patch, text)) crowded.push_back(&patch);
  }
  for (const Patch* patch : crowded) placer.place_with_line(*patch, name_of_group(*patch->group));
  // Taxels big enough to hold their names (a grid's r3c14, a flux stripe's y2) name themselves,
  // on a skin of a few: more names than that are a texture, not something read.
  if (layout.taxels.size() > kMostTaxelNames) return placer.take();
  for (size_t index = 0; index < boxes.size() && index < layout.taxels.size(); ++index) {
    ImVec2 at;
    const std::string& name = layout.taxels[index].name;
    if (!named_inside[index] && inside_position(boxes[index], name, at))
      placer.place(name, name, at, true);
  }
  return placer.take();
}

//---- Legends

float bottom_legend_height() { return ImGui::GetTextLineHeight() + kLegendBarHeight + 14.0f; }

void draw_colour_legend(ImDrawList& draw, ImVec2 top_left, ImVec2 size, bool horizontal,
                        double value_min, double value_max, const std::string& label, bool change) {
  const float line = ImGui::GetTextLineHeight();
  char high_text[32], low_text[32];
  std::snprintf(high_text, sizeof high_text, change ? "+%.3g" : "%.3g", value_max);
  if (change)
    std::snprintf(low_text, sizeof low_text, "rest");
  else
    std::snprintf(low_text, sizeof low_text, "%.3g", value_min);
  const ImVec4 clip(top_left.x, top_left.y, top_left.x + size.x, top_left.y + size.y);
  if (horizontal) {
    // value_min on the left, value_max on the right; the label before the bar.
    const float label_width = label.empty() ? 0.0f : ImGui::CalcTextSize(label.c_str()).x + 10.0f;
    const float bar_left = top_left.x + 8.0f + label_width;
    const float bar_right = top_left.x + size.x - 8.0f;
    const float bar_top = top_left.y + 6.0f;
    if (bar_right - bar_left < 24.0f) return;
    for (int step = 0; step < kLegendSteps; ++step) {
      const float from = static_cast<float>(step) / kLegendSteps;
      const float to = static_cast<float>(step + 1) / kLegendSteps;
      const ImU32 left_colour = pack_abgr(viridis(from));
      const ImU32 right_colour = pack_abgr(viridis(to));
      draw.AddRectFilledMultiColor(
          ImVec2(bar_left + (bar_right - bar_left) * from, bar_top),
          ImVec2(bar_left + (bar_right - bar_left) * to, bar_top + kLegendBarHeight), left_colour,
          right_colour, right_colour, left_colour);
    }
    draw.AddRect(ImVec2(bar_left, bar_top), ImVec2(bar_right, bar_top + kLegendBarHeight),
                 kOutline);
    const float text_top = bar_top + kLegendBarHeight + 2.0f;
    draw.AddText(ImVec2(bar_left, text_top), kText, low_text);
    draw.AddText(ImVec2(bar_right - ImGui::CalcTextSize(high_text).x, text_top), kText, high_text);
    if (!label.empty())
      draw.AddText(ImGui::GetFont(), ImGui::GetFontSize(),
                   ImVec2(top_left.x + 8.0f, bar_top + 0.5f * (kLegendBarHeight - line)), kText,
                   label.c_str(), nullptr, 0.0f, &clip);
    return;
  }
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
  draw.AddText(ImVec2(bar_left + kLegendBarWidth + 4.0f, bar_top - 0.5f * line), kText, high_text);
  draw.AddText(ImVec2(bar_left + kLegendBarWidth + 4.0f, bar_bottom - 0.5f * line), kText,
               low_text);
  if (!label.empty()) {
    draw.AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(bar_left - 4.0f, top_left.y + 2.0f),
                 kText, label.c_str(), nullptr, 0.0f, &clip);
  }
}

namespace {

// A legend row: a line of text and two pixels, so Robovie's 21 parts fit a 720 px window.
float category_line() { return ImGui::GetTextLineHeight() + 2.0f; }

// Rows of a category legend `height` high, and the width of one column.
std::pair<size_t, float> category_legend_columns(const SkinViewCategories& categories,
                                                 float height) {
  const float line = category_line();
  const auto rows = static_cast<size_t>(std::max(1.0f, std::floor((height - 8.0f) / line)));
  float widest = 0.0f;
  for (const std::string& name : categories.names)
    widest = std::max(widest, ImGui::CalcTextSize(name.c_str()).x);
  return {rows, widest + kSwatch + 18.0f};
}

}  // namespace

float category_legend_width(const SkinViewCategories& categories, float height) {
  const auto [rows, column_width] = category_legend_columns(categories, height);
  const size_t columns = std::max<size_t>(1, (categories.names.size() + rows - 1) / rows);
  return static_cast<float>(columns) * column_width + 8.0f;
}

float category_legend_height(const SkinViewCategories& categories, float width) {
  const auto [unused, column_width] = category_legend_columns(categories, 0.0f);
  const auto columns =
      static_cast<size_t>(std::max(1.0f, std::floor((width - 8.0f) / column_width)));
  const size_t rows = (categories.names.size() + columns - 1) / columns;
  return static_cast<float>(rows) * category_line() + 8.0f;
}

std::vector<SkinViewLabel> draw_category_legend(ImDrawList& draw, ImVec2 top_left, ImVec2 size,
                                                const SkinViewCategories& categories) {
  const auto [rows, column_width] = category_legend_columns(categories, size.y);
  const float line = category_line();
  const ImVec4 clip(top_left.x, top_left.y, top_left.x + size.x, top_left.y + size.y);
  std::vector<SkinViewLabel> swatches;
  for (size_t k = 0; k < categories.names.size(); ++k) {
    const ImVec2 row(top_left.x + 8.0f + static_cast<float>(k / rows) * column_width,
                     top_left.y + 4.0f + static_cast<float>(k % rows) * line);
    const SkinViewBox swatch{ImVec2(row.x, row.y + 0.5f * (line - kSwatch)),
                             ImVec2(row.x + kSwatch, row.y + 0.5f * (line + kSwatch))};
    if (swatch.max.x > clip.z || swatch.max.y > clip.w) break;
    draw.AddRectFilled(swatch.min, swatch.max,
                       k < categories.colours.size() ? categories.colours[k] : kText);
    draw.AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(row.x + kSwatch + 5.0f, row.y),
                 kText, categories.names[k].c_str(), nullptr, 0.0f, &clip);
    swatches.push_back({categories.names[k], categories.names[k], swatch});
  }
  return swatches;
}

}  // namespace tactile::skin_parts

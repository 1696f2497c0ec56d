// validate_layout: every rule a SkinLayout must satisfy, each failure naming the entry.

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// "taxel 7", or "taxel 3 "c03"" when the name says more than the id.
std::string describe(const Taxel& taxel) {
  std::string text = "taxel " + std::to_string(taxel.id);
  if (!taxel.name.empty() && taxel.name != std::to_string(taxel.id))
    text.append(" ").append(in_quotes(taxel.name));
  return text;
}

// "NaN", "infinite" or "" (finite).
std::string non_finite(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return "infinite";
  return "";
}

void check_header(const SkinLayout& layout, const std::string& where) {
  if (layout.id.empty()) throw Error(where, "layout id is empty");
  if (!non_finite(layout.sample_rate_hz).empty() || layout.sample_rate_hz < 0.0) {
    throw Error(where, "sample_rate_hz must be a finite number >= 0");
  }
  if (layout.modalities.empty()) throw Error(where, "no modalities");
  std::set<std::string> seen;
  for (const std::string& modality : layout.modalities) {
    if (modality.empty()) throw Error(where, "modalities: empty name");
    if (!seen.insert(modality).second)
      throw Error(where, "modalities: duplicate " + in_quotes(modality));
  }
  if (layout.modality_index(layout.display_modality) < 0) {
    throw Error(where, "display: unknown modality " + in_quotes(layout.display_modality));
  }
  if (!non_finite(layout.display_min).empty() || !non_finite(layout.display_max).empty()) {
    throw Error(where, "display: min and max must be finite numbers");
  }
  if (layout.display_min == layout.display_max) {
    throw Error(where, "display: min and max are equal (" + std::to_string(layout.display_min) +
                           "), the colour scale would be empty");
  }
  std::set<std::string> classes;
  for (const std::string& name : layout.classes) {
    if (name.empty()) throw Error(where, "classes: empty class name");
    if (!classes.insert(name).second) throw Error(where, "classes: duplicate " + in_quotes(name));
  }
}

void check_channels(const SkinLayout& layout, const std::string& where) {
  if (layout.channels.empty()) throw Error(where, "no channels");
  std::unordered_map<std::string, size_t> seen;
  for (size_t index = 0; index < layout.channels.size(); ++index) {
    const Channel& channel = layout.channels[index];
    const std::string entry = "channel " + std::to_string(index);
    if (channel.name.empty()) throw Error(where, entry + ": empty name");
    if (!seen.emplace(channel.name, index).second) {
      throw Error(where,
                  "channel " + in_quotes(channel.name) + ": duplicate channel name (columns " +
                      std::to_string(seen[channel.name]) + " and " + std::to_string(index) + ")");
    }
    if (layout.modality_index(channel.modality) < 0) {
      throw Error(where, "channel " + in_quotes(channel.name) + ": unknown modality " +
                             in_quotes(channel.modality));
    }
  }
}

void check_taxel_geometry(const Taxel& taxel, const std::string& where) {
  const std::string entry = describe(taxel);
  for (double coordinate : {taxel.position.x, taxel.position.y}) {
    const std::string problem = non_finite(coordinate);
    if (!problem.empty()) throw Error(where, entry + ": position is " + problem);
  }
  for (double extent : {taxel.size.x, taxel.size.y}) {
    if (!non_finite(extent).empty() || extent <= 0.0) {
      throw Error(where, entry + ": size must be positive (w " + std::to_string(taxel.size.x) +
                             ", h " + std::to_string(taxel.size.y) + ")");
    }
  }
  if (!non_finite(taxel.area).empty() || taxel.area <= 0.0) {
    throw Error(where, entry + ": area must be positive (got " + std::to_string(taxel.area) + ")");
  }
  if (taxel.shape == TaxelShape::kPolygon && taxel.outline.size() < 3) {
    throw Error(where, entry + ": a polygon needs an outline of at least 3 points");
  }
  for (size_t index = 0; index < taxel.outline.size(); ++index) {
    const Point2& vertex = taxel.outline[index];
    if (!non_finite(vertex.x).empty() || !non_finite(vertex.y).empty()) {
      throw Error(where, entry + ": outline point " + std::to_string(index) + " is " +
                             non_finite(std::isfinite(vertex.x) ? vertex.y : vertex.x));
    }
  }
}

void check_taxels(const SkinLayout& layout, const std::string& where) {
  if (layout.taxels.empty()) throw Error(where, "no taxels");
  std::set<int64_t> ids;
  std::set<std::string> names;
  std::vector<const Taxel*> owner(layout.channels.size(), nullptr);
  for (const Taxel& taxel : layout.taxels) {
    const std::string entry = describe(taxel);
    if (taxel.id < 0) throw Error(where, entry + ": id must be >= 0");
    if (!ids.insert(taxel.id).second) throw Error(where, entry + ": duplicate id");
    if (taxel.name.empty()) throw Error(where, entry + ": empty name");
    if (!names.insert(taxel.name).second) throw Error(where, entry + ": duplicate name");
    check_taxel_geometry(taxel, where);
    if (taxel.channels.size() != layout.modalities.size()) {
      throw Error(where, entry + ": has " + std::to_string(taxel.channels.size()) +
                             " channel slots, the layout has " +
                             std::to_string(layout.modalities.size()) + " modalities");
    }
    bool has_channel = false;
    for (size_t slot = 0; slot < taxel.channels.size(); ++slot) {
      const int channel = taxel.channels[slot];
      if (channel == -1) continue;
      if (channel < 0 || static_cast<size_t>(channel) >= layout.channels.size()) {
        throw Error(where, entry + ": channel index " + std::to_string(channel) + " out of range");
      }
      const Channel& named = layout.channels[static_cast<size_t>(channel)];
      if (named.modality != layout.modalities[slot]) {
        throw Error(where, entry + ": channel " + in_quotes(named.name) + " has modality " +
                               in_quotes(named.modality) + ", not " +
                               in_quotes(layout.modalities[slot]));
      }
      if (owner[static_cast<size_t>(channel)] != nullptr) {
        throw Error(where, entry + ": channel " + in_quotes(named.name) + " already belongs to " +
                               describe(*owner[static_cast<size_t>(channel)]));
      }
      owner[static_cast<size_t>(channel)] = &taxel;
      has_channel = true;
    }
    if (!has_channel) throw Error(where, entry + ": has no channel");
  }
}

void check_groups(const SkinLayout& layout, const std::string& where) {
  std::set<int64_t> taxel_ids;
  for (const Taxel& taxel : layout.taxels) taxel_ids.insert(taxel.id);
  std::set<std::string> group_ids;
  for (const Group& group : layout.groups) {
    const std::string entry = "group " + in_quotes(group.id);
    if (group.id.empty()) throw Error(where, "group with an empty id");
    if (!group_ids.insert(group.id).second) throw Error(where, entry + ": duplicate group id");
    if (group.kind.empty()) throw Error(where, entry + ": empty kind");
    if (group.taxels.empty()) throw Error(where, entry + ": has no taxels");
    std::set<int64_t> members;
    for (int64_t member : group.taxels) {
      if (taxel_ids.count(member) == 0) {
        throw Error(where, entry + ": unknown taxel " + std::to_string(member));
      }
      if (!members.insert(member).second) {
        throw Error(where, entry + ": lists taxel " + std::to_string(member) + " twice");
      }
    }
  }
  std::set<std::string> disjoint_kinds;
  for (const std::string& kind : layout.disjoint_kinds) {
    if (!disjoint_kinds.insert(kind).second) {
      throw Error(where, "disjoint_kinds: duplicate " + in_quotes(kind));
    }
    std::map<int64_t, const Group*> holder;
    bool any_group = false;
    for (const Group& group : layout.groups) {
      if (group.kind != kind) continue;
      any_group = true;
      for (int64_t member : group.taxels) {
        const auto [place, inserted] = holder.emplace(member, &group);
        if (!inserted) {
          throw Error(where, "groups " + in_quotes(place->second->id) + " and " +
                                 in_quotes(group.id) + " (kind " + in_quotes(kind) +
                                 ", declared disjoint) share taxel " + std::to_string(member));
        }
      }
    }
    if (!any_group) throw Error(where, "disjoint_kinds: no group of kind " + in_quotes(kind));
  }
}

void check_body_outline(const SkinLayout& layout, const std::string& where) {
  for (size_t index = 0; index < layout.body_outline.size(); ++index) {
    const std::string entry = "outline[" + std::to_string(index) + "]";
    const std::vector<Point2>& polygon = layout.body_outline[index];
    if (polygon.size() < 3) {
      throw Error(where, entry + ": a polygon needs at least 3 points (got " +
                             std::to_string(polygon.size()) + ")");
    }
    for (size_t point = 0; point < polygon.size(); ++point) {
      const Point2& vertex = polygon[point];
      if (!non_finite(vertex.x).empty() || !non_finite(vertex.y).empty()) {
        throw Error(where, entry + ": point " + std::to_string(point) + " is " +
                               non_finite(std::isfinite(vertex.x) ? vertex.y : vertex.x));
      }
    }
  }
}

}  // namespace

void validate_layout(const SkinLayout& layout, const std::string& where) {
  check_header(layout, where);
  check_channels(layout, where);
  check_taxels(layout, where);
  check_groups(layout, where);
  check_body_outline(layout, where);
}

}  // namespace tactile

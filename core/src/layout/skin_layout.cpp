// SkinLayout lookups, taxel outlines, and finding a layout by id (asset file or generic).

#include "tactile/layout/skin_layout.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <set>

#include "tactile/error.h"

namespace tactile {

//---- Lookups ----------------------------------------------------------------------------------

int SkinLayout::channel_index(const std::string& channel) const {
  for (size_t index = 0; index < channels.size(); ++index) {
    if (channels[index].name == channel) return static_cast<int>(index);
  }
  return -1;
}

int SkinLayout::modality_index(const std::string& modality) const {
  for (size_t index = 0; index < modalities.size(); ++index) {
    if (modalities[index] == modality) return static_cast<int>(index);
  }
  return -1;
}

const Taxel* SkinLayout::find_taxel(int64_t taxel_id) const {
  for (const Taxel& taxel : taxels) {
    if (taxel.id == taxel_id) return &taxel;
  }
  return nullptr;
}

const Group* SkinLayout::find_group(const std::string& group_id) const {
  for (const Group& group : groups) {
    if (group.id == group_id) return &group;
  }
  return nullptr;
}

std::vector<const Group*> SkinLayout::groups_of(int64_t taxel_id, const std::string& kind) const {
  std::vector<const Group*> result;
  for (const Group& group : groups) {
    if (!kind.empty() && group.kind != kind) continue;
    if (std::find(group.taxels.begin(), group.taxels.end(), taxel_id) != group.taxels.end()) {
      result.push_back(&group);
    }
  }
  return result;
}

std::pair<Point2, Point2> SkinLayout::bounds() const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Point2 low{kInfinity, kInfinity};
  Point2 high{-kInfinity, -kInfinity};
  for (const Taxel& taxel : taxels) {
    for (const Point2& vertex : taxel_outline(taxel)) {
      low.x = std::min(low.x, vertex.x);
      low.y = std::min(low.y, vertex.y);
      high.x = std::max(high.x, vertex.x);
      high.y = std::max(high.y, vertex.y);
    }
  }
  if (low.x > high.x) return {Point2{}, Point2{}};  // no taxels: an empty box at the origin
  return {low, high};
}

// A sweep over the centres sorted by x: a candidate further away in x than the best so far
// ends the search on that side, so rows of taxels cost about their length.
std::vector<double> nearest_taxel_distances(const SkinLayout& layout) {
  const size_t count = layout.taxels.size();
  std::vector<size_t> by_x(count);
  for (size_t index = 0; index < count; ++index) by_x[index] = index;
  std::sort(by_x.begin(), by_x.end(), [&layout](size_t a, size_t b) {
    return layout.taxels[a].position.x < layout.taxels[b].position.x;
  });
  std::vector<double> nearest(count, std::numeric_limits<double>::infinity());
  for (size_t rank = 0; rank < count; ++rank) {
    const Point2& centre = layout.taxels[by_x[rank]].position;
    double& best = nearest[by_x[rank]];
    const auto consider = [&](size_t other) {
      const Point2& point = layout.taxels[by_x[other]].position;
      if (std::abs(point.x - centre.x) >= best) return false;
      best = std::min(best, std::hypot(point.x - centre.x, point.y - centre.y));
      return true;
    };
    for (size_t other = rank + 1; other < count && consider(other); ++other) {
    }
    for (size_t other = rank; other-- > 0 && consider(other);) {
    }
  }
  return nearest;
}

//---- Shapes -----------------------------------------------------------------------------------

const char* taxel_shape_name(TaxelShape shape) {
  switch (shape) {
    case TaxelShape::kRectangle:
      return "rect";
    case TaxelShape::kHexagon:
      return "hex";
    case TaxelShape::kStripe:
      return "stripe";
    case TaxelShape::kPolygon:
      return "polygon";
    case TaxelShape::kCircle:
      return "circle";
  }
  return "rect";
}

std::vector<Point2> taxel_outline(const Taxel& taxel) {
  if (!taxel.outline.empty()) return taxel.outline;
  const double x = taxel.position.x;
  const double y = taxel.position.y;
  const double half_width = taxel.size.x / 2.0;
  const double half_height = taxel.size.y / 2.0;
  switch (taxel.shape) {
    case TaxelShape::kHexagon:
      if (taxel.size.y >= taxel.size.x) {
        // Pointy-top: corners at top and bottom; the box width is flat-to-flat.
        return {{x, y - half_height},
                {x + half_width, y - half_height / 2.0},
                {x + half_width, y + half_height / 2.0},
                {x, y + half_height},
                {x - half_width, y + half_height / 2.0},
                {x - half_width, y - half_height / 2.0}};
      }
      // Flat-top: corners at left and right; the box height is flat-to-flat.
      return {{x - half_width, y},
              {x - half_width / 2.0, y - half_height},
              {x + half_width / 2.0, y - half_height},
              {x + half_width, y},
              {x + half_width / 2.0, y + half_height},
              {x - half_width / 2.0, y + half_height}};
    case TaxelShape::kCircle: {
      // 24 vertices keep a 5 mm pad round on screen and its polygon area within 1.2 %.
      constexpr int kVertices = 24;
      std::vector<Point2> vertices;
      vertices.reserve(kVertices);
      for (int index = 0; index < kVertices; ++index) {
        const double angle = 2.0 * std::numbers::pi * index / kVertices;
        vertices.push_back({x + half_width * std::cos(angle), y + half_height * std::sin(angle)});
      }
      return vertices;
    }
    case TaxelShape::kRectangle:
    case TaxelShape::kStripe:
    case TaxelShape::kPolygon:  // a polygon without an outline fails validation; draw its box
      break;
  }
  return {{x - half_width, y - half_height},
          {x + half_width, y - half_height},
          {x + half_width, y + half_height},
          {x - half_width, y + half_height}};
}

//---- Finding layouts --------------------------------------------------------------------------

namespace {

struct AddedLayouts {
  std::mutex mutex;
  std::map<std::string, SkinLayout> layouts;
};

AddedLayouts& added_layouts() {
  static AddedLayouts added;
  return added;
}

SkinLayout build_generic_layout(const std::string& id);

// Layout ids name files, so they may not walk out of the layouts directory.
bool is_plain_layout_name(const std::string& id) {
  if (id.empty()) return false;
  return std::all_of(id.begin(), id.end(), [](char character) {
    return std::isalnum(static_cast<unsigned char>(character)) != 0 || character == '_' ||
           character == '-';
  });
}

}  // namespace

void add_layout(SkinLayout layout) {
  const std::string where = "layout " + layout.id;
  if (!is_plain_layout_name(layout.id))
    throw Error(where, "invalid layout id (letters, digits, '-' and '_' only)");
  validate_layout(layout, where);
  AddedLayouts& added = added_layouts();
  const std::lock_guard lock(added.mutex);
  added.layouts[layout.id] = std::move(layout);
}

// The folders a layout file is looked for in: TACTILE_LAYOUT_PATH's (':'-separated, first
// match wins), then the assets' layouts/.
std::vector<std::filesystem::path> layout_folders() {
  std::vector<std::filesystem::path> folders;
  if (const char* path = std::getenv("TACTILE_LAYOUT_PATH")) {
    std::string list = path;
    for (size_t start = 0; start <= list.size();) {
      const size_t end = std::min(list.find(':', start), list.size());
      if (end > start) folders.emplace_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  folders.push_back(std::filesystem::path(asset_dir()) / "layouts");
  return folders;
}

std::vector<std::string> known_layout_ids() {
  std::set<std::string> ids;
  {
    AddedLayouts& added = added_layouts();
    const std::lock_guard lock(added.mutex);
    for (const auto& entry : added.layouts) ids.insert(entry.first);
  }
  for (const std::filesystem::path& folder : layout_folders()) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(folder, error))
      if (entry.path().extension() == ".json") ids.insert(entry.path().stem().string());
  }
  return {ids.begin(), ids.end()};
}

SkinLayout load_layout(const std::string& id) {
  const std::string where = "layout " + id;
  if (is_generic_layout_id(id)) return build_generic_layout(id);
  if (!is_plain_layout_name(id)) {
    throw Error(where,
                "invalid layout id (letters, digits, '-' and '_' only, or grid:RxC, strip:N)");
  }
  {
    AddedLayouts& added = added_layouts();
    const std::lock_guard lock(added.mutex);
    const auto found = added.layouts.find(id);
    if (found != added.layouts.end()) return found->second;
  }
  std::filesystem::path path;
  std::string looked;
  for (const std::filesystem::path& folder : layout_folders()) {
    std::error_code error;
    if (std::filesystem::is_regular_file(folder / (id + ".json"), error)) {
      path = folder / (id + ".json");
      break;
    }
    looked += (looked.empty() ? "" : ", ") + (folder / (id + ".json")).string();
  }
  if (path.empty()) {
    std::string known;
    for (const std::string& name : known_layout_ids()) known += name + ", ";
    throw Error(where,
                "unknown layout: no file " + looked + " (known: " + known + "grid:RxC, strip:N)");
  }
  SkinLayout layout = load_layout_file(path.string());
  if (layout.id != id) {
    throw Error(path.string(), "declares id \"" + layout.id + "\", expected \"" + id + "\"");
  }
  return layout;
}

namespace {

SkinLayout build_generic_layout(const std::string& id) {
  // A decimal count that must fill its whole field; more than 18 digits could overflow int64
  // and is far beyond the size limit anyway.
  const auto parse_count = [&id](const std::string& text, const std::string& what) -> int64_t {
    const bool digits_only = !text.empty() && std::all_of(text.begin(), text.end(), [](char digit) {
      return digit >= '0' && digit <= '9';
    });
    if (!digits_only) {
      throw Error("layout " + id, what + " \"" + text + "\" is not a positive whole number");
    }
    if (text.size() > 18) {
      throw Error("layout " + id, what + " " + text + " is too large (at most " +
                                      std::to_string(kMaxGenericTaxels) + " taxels)");
    }
    return std::stoll(text);
  };
  if (id.rfind("grid:", 0) == 0) {
    const std::string shape = id.substr(5);
    const size_t separator = shape.find('x');
    if (separator == std::string::npos) {
      throw Error("layout " + id, "expected grid:RxC (rows x columns), e.g. grid:4x4");
    }
    const int64_t rows = parse_count(shape.substr(0, separator), "rows");
    const int64_t columns = parse_count(shape.substr(separator + 1), "columns");
    return make_grid_layout(rows, columns, id);
  }
  const int64_t count = parse_count(id.substr(6), "taxel count");
  return make_strip_layout(count, id);
}

}  // namespace

}  // namespace tactile

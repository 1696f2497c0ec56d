#pragma once
// SkinLayout: where each taxel sits on the body and on an unwrapped 2-D map, which
// channels it owns, and the groups (body parts, modules, sheets, layers) it belongs to.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tactile {

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

// JSON names: "rect", "hex", "stripe", "polygon", "circle". A hexagon is regular in its box
// when the long side is 2/sqrt(3) of the short one; pointy-top when taller than wide, else
// flat-top. A circle (or ellipse) fills its box.
enum class TaxelShape { kRectangle, kHexagon, kStripe, kPolygon, kCircle };

struct Taxel {
  int64_t id = 0;
  std::string name;
  std::string body_part;
  Point2 position;    // centre on the unwrapped map, in map units (mm)
  Point2 size;        // width and height on the map (mm); for hexagons, the flat-to-flat box
  double area = 0.0;  // physical sensing area (mm^2)
  TaxelShape shape = TaxelShape::kRectangle;
  std::vector<Point2> outline;  // explicit outline on the map; empty -> derived from shape and size
  // Channel indices into SkinLayout::channels, one per modality of the layout (in
  // SkinLayout::modalities order). -1 where this taxel lacks that modality.
  std::vector<int> channels;
};

struct Group {
  std::string id;               // unique within the layout, e.g. "front", "module-07", "left-arm"
  std::string kind;             // e.g. "side", "module", "sheet", "body-part", "layer"
  std::string name;             // human-readable
  std::vector<int64_t> taxels;  // taxel ids
};

struct Channel {
  std::string name;      // column name in recordings, e.g. "c01.f2"
  std::string unit;      // e.g. "N", "g", "mm", "degC", "counts"
  std::string modality;  // e.g. "force", "accel", "proximity", "capacitance"
};

struct SkinLayout {
  std::string id;    // "nao", "tsa", "fur", "robovie", "flux", "grid:4x4", "strip:8"
  std::string name;  // human-readable
  std::string description;
  std::string map_unit = "mm";
  double sample_rate_hz = 0.0;          // the device's native rate; 0 when unknown
  std::vector<std::string> modalities;  // per-taxel channel slots, e.g. {"ax","ay",...}
  std::string display_modality;         // modality a skin view colours by default
  // Value range a skin view maps to [0, 1] by default; min > max is allowed and
  // reverses the scale (proximity: 200 mm dark, 0 mm bright).
  double display_min = 0.0;
  double display_max = 1.0;
  std::vector<Channel> channels;  // every channel, in recording column order
  std::vector<Taxel> taxels;
  std::vector<Group> groups;
  std::vector<std::string> disjoint_kinds;  // group kinds whose groups may not share taxels
  std::vector<std::string> classes;         // the paper's class vocabulary
  // The body's silhouette on the map (JSON "outline"): closed polygons in map units (head,
  // torso, limbs) that a skin view draws under the taxels; empty when the layout has none.
  std::vector<std::vector<Point2>> body_outline;

  int channel_index(const std::string& channel) const;    // -1 when absent
  int modality_index(const std::string& modality) const;  // -1 when absent
  const Taxel* find_taxel(int64_t taxel_id) const;
  const Group* find_group(const std::string& group_id) const;
  // Groups of the given kind that contain the taxel ("" kind: all groups).
  std::vector<const Group*> groups_of(int64_t taxel_id, const std::string& kind = {}) const;
  // Map bounding box over all taxel outlines: {min, max} (the body outline left out).
  std::pair<Point2, Point2> bounds() const;
};

// The outline of a taxel on the map (explicit, or derived from shape, position, size).
std::vector<Point2> taxel_outline(const Taxel& taxel);

// The JSON name of a shape ("rect", "hex", ...).
const char* taxel_shape_name(TaxelShape shape);

// Generic layouts built in code. grid: rows x columns taxels, r-major, ids 0..R*C-1, channels
// ch0.., modality "value", 10 mm pitch, one group of kind "row" per row. strip: count taxels in
// a row along x. Throw tactile::Error (naming `id`) when empty or over kMaxGenericTaxels.
constexpr int64_t kMaxGenericTaxels = 65536;
SkinLayout make_grid_layout(int64_t rows, int64_t columns, const std::string& id = {});
SkinLayout make_strip_layout(int64_t count, const std::string& id = {});
// True for ids of the form "grid:..." or "strip:..." (valid or not).
bool is_generic_layout_id(const std::string& id);
// A strip:N layout with its taxels laid `columns` to a row, row after row at the strip's pitch
// (a long strip drawn in a panel taller than one row); ids, names, channels unchanged. Throws
// tactile::Error for a layout that is not a strip or columns < 1.
SkinLayout strip_in_rows(const SkinLayout& strip, int64_t columns);
// The number of columns that gives `count` square cells the largest size in width x height.
int64_t strip_columns_to_fit(int64_t count, double width, double height);

// Per taxel (layout order), the distance between its centre and the nearest other taxel's
// centre; infinity for a layout of one taxel. What "neighbours" means to a drawing.
std::vector<double> nearest_taxel_distances(const SkinLayout& layout);

// A layout added by add_layout, else assets/layouts/<id>.json, or a generic grid:RxC /
// strip:N layout. Throws tactile::Error naming the file and the entry on any invalid content.
SkinLayout load_layout(const std::string& id);
// Makes a layout that has no file (a skin registered by a program or a test) known to
// load_layout by its id, replacing an earlier one of the same id. Validates it first.
void add_layout(SkinLayout layout);
SkinLayout load_layout_file(const std::string& path);
SkinLayout parse_layout_json(const std::string& text, const std::string& where);
// Checks ids, channels, positions and disjoint groups; throws tactile::Error.
void validate_layout(const SkinLayout& layout, const std::string& where);
// The directory holding layouts/ (TACTILE_ASSETS env var, else the build-time default).
std::string asset_dir();
// The ids load_layout knows by name: the added layouts and the files in assets/layouts,
// sorted (grid:RxC and strip:N aside).
std::vector<std::string> known_layout_ids();

}  // namespace tactile

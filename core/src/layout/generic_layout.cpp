// Generic layouts built in code: grid:RxC and strip:N, for recordings of any rectangular sensor.

#include <algorithm>
#include <string>

#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

namespace {

constexpr double kPitchMillimetres = 10.0;

// The parts every generic layout shares: one "value" modality, channels ch0.., taxels on a
// 10 mm grid, r-major.
SkinLayout make_generic(int64_t rows, int64_t columns, const std::string& id,
                        const std::string& name) {
  SkinLayout layout;
  layout.id = id;
  layout.name = name;
  layout.description = "Generic layout built in code: " + std::to_string(rows) + " x " +
                       std::to_string(columns) +
                       " square taxels at 10 mm pitch, one channel per taxel (ch0.. row-major), "
                       "modality 'value' in [0, 1].";
  layout.modalities = {"value"};
  layout.display_modality = "value";
  layout.display_min = 0.0;
  layout.display_max = 1.0;
  const int64_t count = rows * columns;
  layout.channels.reserve(static_cast<size_t>(count));
  layout.taxels.reserve(static_cast<size_t>(count));
  for (int64_t index = 0; index < count; ++index) {
    const int64_t row = index / columns;
    const int64_t column = index % columns;
    const std::string channel_name = "ch" + std::to_string(index);
    layout.channels.push_back({channel_name, "", "value"});
    Taxel taxel;
    taxel.id = index;
    taxel.name =
        rows == 1 ? channel_name : "r" + std::to_string(row) + "c" + std::to_string(column);
    taxel.position = {(static_cast<double>(column) + 0.5) * kPitchMillimetres,
                      (static_cast<double>(row) + 0.5) * kPitchMillimetres};
    taxel.size = {kPitchMillimetres, kPitchMillimetres};
    taxel.area = kPitchMillimetres * kPitchMillimetres;
    taxel.shape = TaxelShape::kRectangle;
    taxel.channels = {static_cast<int>(index)};
    layout.taxels.push_back(std::move(taxel));
  }
  return layout;
}

void check_size(int64_t rows, int64_t columns, const std::string& id) {
  if (rows < 1 || columns < 1) {
    throw Error("layout " + id, "needs at least one taxel (got " + std::to_string(rows) + " x " +
                                    std::to_string(columns) + ")");
  }
  if (rows > kMaxGenericTaxels || columns > kMaxGenericTaxels ||
      rows * columns > kMaxGenericTaxels) {
    throw Error("layout " + id, "too large: " + std::to_string(rows) + " x " +
                                    std::to_string(columns) + " taxels (at most " +
                                    std::to_string(kMaxGenericTaxels) + ")");
  }
}

}  // namespace

bool is_generic_layout_id(const std::string& id) {
  return id.rfind("grid:", 0) == 0 || id.rfind("strip:", 0) == 0;
}

SkinLayout make_grid_layout(int64_t rows, int64_t columns, const std::string& id) {
  const std::string layout_id =
      id.empty() ? "grid:" + std::to_string(rows) + "x" + std::to_string(columns) : id;
  check_size(rows, columns, layout_id);
  SkinLayout layout = make_generic(
      rows, columns, layout_id, "Grid " + std::to_string(rows) + " x " + std::to_string(columns));
  layout.groups.reserve(static_cast<size_t>(rows));
  for (int64_t row = 0; row < rows; ++row) {
    Group group;
    group.id = "row" + std::to_string(row);
    group.kind = "row";
    group.name = "row " + std::to_string(row);
    for (int64_t column = 0; column < columns; ++column)
      group.taxels.push_back(row * columns + column);
    layout.groups.push_back(std::move(group));
  }
  layout.disjoint_kinds = {"row"};
  return layout;
}

SkinLayout strip_in_rows(const SkinLayout& strip, int64_t columns) {
  if (strip.id.rfind("strip:", 0) != 0) {
    throw Error("layout " + strip.id, "only a strip:N layout can be laid out in rows");
  }
  if (columns < 1) {
    throw Error("layout " + strip.id,
                "needs at least one column (got " + std::to_string(columns) + ")");
  }
  SkinLayout rows = strip;
  for (size_t index = 0; index < rows.taxels.size(); ++index) {
    Taxel& taxel = rows.taxels[index];
    const auto place = static_cast<int64_t>(index);
    taxel.position = {(static_cast<double>(place % columns) + 0.5) * kPitchMillimetres,
                      (static_cast<double>(place / columns) + 0.5) * kPitchMillimetres};
  }
  return rows;
}

int64_t strip_columns_to_fit(int64_t count, double width, double height) {
  int64_t best_columns = std::max<int64_t>(count, 1);
  double best_cell = 0.0;
  for (int64_t columns = 1; columns <= count; ++columns) {
    const int64_t rows = (count + columns - 1) / columns;
    const double cell =
        std::min(width / static_cast<double>(columns), height / static_cast<double>(rows));
    // Ties go to more columns: fewer rows read more like the strip they are.
    if (cell >= best_cell) {
      best_cell = cell;
      best_columns = columns;
    }
  }
  return best_columns;
}

SkinLayout make_strip_layout(int64_t count, const std::string& id) {
  const std::string layout_id = id.empty() ? "strip:" + std::to_string(count) : id;
  check_size(1, count, layout_id);
  return make_generic(1, count, layout_id, "Strip of " + std::to_string(count));
}

}  // namespace tactile

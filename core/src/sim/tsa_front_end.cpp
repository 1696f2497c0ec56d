// The `tsa` front end: a hand footprint over round pads -> capacitance -> 12-bit counts.
//
// Filter stage modelled: the counts are the raw capacitance-to-digital words of each scan,
// before the IIR smoothing of spec §2.2 eq (3). The workbench's tsa pipeline applies eq (3)
// once (N = 4) in preprocessing, which yields what the paper's modules transmit; filtering
// here as well would smooth twice and bury one-frame taps. The only smoothing simulated is
// the converter's own: each word averages the pad's capacitance over its conversion window.

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "tactile/error.h"
#include "tactile/sim/tsa_sim.h"

namespace tactile::sim::tsa {

namespace {

constexpr double kVacuumPermittivity = 8.854e-12;  // F/m
constexpr double kShellPermittivity = 2.9;         // relative permittivity of ABS
constexpr double kCountStep = 5e-15;  // F per count: the module's 5 fF sensitivity (Sec. II-D)
// The FDC2114 converts 4 channels at once; a 4x8 multiplexer steps through 8 positions per
// frame (Sec. II-C), 4 per sheet, so a module's 32 pads are read in 8 slots of 1/64 s.
constexpr int kPositionsPerSheet = 4;
constexpr int kScanSlots = 8;
constexpr double kConversionShare = 0.8;  // of a slot; the rest is settling after switching
constexpr int kConversionSamples = 3;     // points averaged over one conversion window

const Group* group_holding(const SkinLayout& layout, int64_t taxel_id, const std::string& kind) {
  const std::vector<const Group*> groups = layout.groups_of(taxel_id, kind);
  return groups.empty() ? nullptr : groups.front();
}

}  // namespace

//---- Sheets from the layout ------------------------------------------------------------------

std::vector<Sheet> layout_sheets(const SkinLayout& layout) {
  if (layout.modalities.empty()) throw Error(layout.id, "tsa simulator: layout has no modality");
  std::map<int64_t, int> index_of_id;
  for (size_t k = 0; k < layout.taxels.size(); ++k)
    index_of_id[layout.taxels[k].id] = static_cast<int>(k);

  std::vector<Sheet> sheets;
  std::vector<std::string> module_of_sheet;
  for (const Group& group : layout.groups) {
    if (group.kind != "sheet") continue;
    if (group.taxels.empty()) throw Error(layout.id, "sheet \"" + group.id + "\" has no taxels");
    Sheet sheet;
    sheet.id = group.id;
    const Group* location = group_holding(layout, group.taxels.front(), "location");
    const Group* module = group_holding(layout, group.taxels.front(), "module");
    if (location == nullptr || module == nullptr)
      throw Error(layout.id, "sheet \"" + group.id +
                                 "\" needs to lie in a group of kind \"location\" and one of kind "
                                 "\"module\"");
    sheet.location = location->id;
    module_of_sheet.push_back(module->id);
    double sum_x = 0.0, sum_y = 0.0;
    for (int64_t id : group.taxels) {
      const auto found = index_of_id.find(id);
      if (found == index_of_id.end())
        throw Error(layout.id, "sheet \"" + group.id + "\": unknown taxel " + std::to_string(id));
      const Taxel& taxel = layout.taxels[found->second];
      if (taxel.channels.empty() || taxel.channels.front() < 0)
        throw Error(layout.id, "taxel \"" + taxel.name + "\" has no capacitance channel");
      sheet.taxels.push_back(found->second);
      sheet.columns.push_back(taxel.channels.front());
      sheet.pad_centres.push_back(taxel.position);
      sum_x += taxel.position.x;
      sum_y += taxel.position.y;
    }
    const double count = static_cast<double>(sheet.taxels.size());
    sheet.centre = {sum_x / count, sum_y / count};
    const Taxel& first = layout.taxels[sheet.taxels.front()];
    sheet.pad_radius = 0.5 * std::min(first.size.x, first.size.y);
    double nearest = 0.0;
    for (size_t a = 0; a < sheet.pad_centres.size(); ++a)
      for (size_t b = a + 1; b < sheet.pad_centres.size(); ++b) {
        const Point2 p = sheet.pad_centres[a];
        const Point2 q = sheet.pad_centres[b];
        const double distance = std::hypot(p.x - q.x, p.y - q.y);
        if (nearest == 0.0 || distance < nearest) nearest = distance;
      }
    if (nearest > 0.0) sheet.pitch = nearest;
    sheets.push_back(std::move(sheet));
  }
  if (sheets.empty())
    throw Error(layout.id, "tsa simulator: layout has no group of kind \"sheet\"");

  // Scan timing. The converter reads 4 pads at once and the multiplexer steps 4 positions per
  // sheet, one sheet after the other. We assume each position reads the same corner of the
  // four 2x2 quadrants of a sheet, so a touch that starts mid-frame shows spread over the
  // sheet rather than as a row sweep (the paper does not give the wiring).
  std::map<std::string, int> sheets_in_module;
  std::vector<int> order_in_module;
  for (const std::string& module : module_of_sheet)
    order_in_module.push_back(sheets_in_module[module]++);
  for (size_t s = 0; s < sheets.size(); ++s) {
    Sheet& sheet = sheets[s];
    double left = sheet.pad_centres.front().x, top = sheet.pad_centres.front().y;
    for (const Point2& pad : sheet.pad_centres) {
      left = std::min(left, pad.x);
      top = std::min(top, pad.y);
    }
    const int slots = kPositionsPerSheet * sheets_in_module[module_of_sheet[s]];
    for (const Point2& pad : sheet.pad_centres) {
      const auto row = static_cast<int>(std::lround((pad.y - top) / sheet.pitch));
      const auto column = static_cast<int>(std::lround((pad.x - left) / sheet.pitch));
      const int slot = order_in_module[s] * kPositionsPerSheet + (row % 2) * 2 + column % 2;
      sheet.scan_offsets.push_back(slot * kFramePeriod / slots);
    }
  }
  return sheets;
}

//---- Contact geometry ------------------------------------------------------------------------

double pad_coverage(const Point2& pad, double sensing_radius, const Footprint& footprint) {
  const double dx = pad.x - footprint.centre.x;
  const double dy = pad.y - footprint.centre.y;
  const double along = dx * std::cos(footprint.angle) + dy * std::sin(footprint.angle);
  const double across = -dx * std::sin(footprint.angle) + dy * std::cos(footprint.angle);
  const double distance = std::hypot(along, across);
  const double a = footprint.half_length;
  const double b = footprint.half_width;
  // Radius of the ellipse in the direction of the pad; depth of the pad centre inside it.
  double edge = std::min(a, b);
  if (distance > 1e-9) {
    const double c = along / distance;
    const double s = across / distance;
    edge = a * b / std::sqrt(b * b * c * c + a * a * s * s);
  }
  const double h = std::clamp((edge - distance) / sensing_radius, -1.0, 1.0);
  // Share of a disc on the inner side of a chord at signed distance h (in radii) from its centre.
  const double share = 0.5 + (h * std::sqrt(1.0 - h * h) + std::asin(h)) / std::numbers::pi;
  // A footprint smaller than the pad cannot cover more than its own area.
  const double area_bound = (a * b) / (sensing_radius * sensing_radius);
  return std::min(share, area_bound);
}

namespace {}  // namespace

Footprint footprint_at(const Touch& touch, double t) {
  const double span = touch.contact_end - touch.contact_start;
  const double progress = minimum_jerk(span > 0.0 ? (t - touch.contact_start) / span : 0.0);
  Footprint footprint = touch.shape;
  if (touch.direction == Direction::kClockwise || touch.direction == Direction::kCounterClockwise) {
    const double angle = touch.start_angle + touch.sweep * progress;
    footprint.centre = {touch.start.x + touch.radius * std::cos(angle),
                        touch.start.y + touch.radius * std::sin(angle)};
    return footprint;
  }
  const double dx = touch.end.x - touch.start.x;
  const double dy = touch.end.y - touch.start.y;
  const double length = std::hypot(dx, dy);
  // Sideways bow of a stroke: the arm swings about the elbow, so straight strokes curve.
  const double side = touch.bow * std::sin(std::numbers::pi * progress);
  const double normal_x = length > 1e-9 ? -dy / length : 0.0;
  const double normal_y = length > 1e-9 ? dx / length : 0.0;
  footprint.centre = {touch.start.x + dx * progress + normal_x * side,
                      touch.start.y + dy * progress + normal_y * side};
  return footprint;
}

double coupling_at(const Touch& touch, double t) {
  // The field reaches through the shell before the skin touches it (proximity), and the
  // skin flattens over the first instants of contact: a raised-cosine ramp centred on the
  // contact's start and end.
  return contact_envelope(t, touch.contact_start - touch.approach,
                          touch.contact_end - touch.contact_start + 2.0 * touch.approach,
                          2.0 * touch.approach, 2.0 * touch.approach);
}

//---- Device ----------------------------------------------------------------------------------

Device make_device(const SkinLayout& layout, const std::vector<Sheet>& sheets, uint64_t seed) {
  Random random(derive_engine(seed, "tsa-device"));
  const size_t columns = layout.channels.size();
  Device device;
  device.offset_counts.assign(columns, 0.0);
  device.gain.assign(columns, 1.0);
  device.temperature_coefficient.assign(columns, 0.0);
  device.noise_counts.assign(columns, 1.0);
  device.module_of_column.assign(columns, 0);

  std::map<std::string, int> module_index;
  for (const Group& group : layout.groups) {
    if (group.kind != "module") continue;
    const int index = static_cast<int>(module_index.size());
    module_index[group.id] = index;
    for (int64_t id : group.taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      if (taxel != nullptr && !taxel->channels.empty() && taxel->channels.front() >= 0)
        device.module_of_column[taxel->channels.front()] = index;
    }
  }
  device.module_count = std::max<int>(1, static_cast<int>(module_index.size()));

  for (size_t column = 0; column < columns; ++column) {
    // Pad plus trace capacitance above the converter's reference, in 5 fF steps.
    device.offset_counts[column] = random.uniform(380.0, 560.0);
    device.gain[column] = random.truncated_normal(1.0, 0.06);
    device.temperature_coefficient[column] = random.uniform(-4.0, 4.0);
    device.noise_counts[column] = random.uniform(1.0, 1.6);
  }

  // Shell thickness per location (moulded parts differ) and an air gap per sheet where the
  // flexible sheet does not follow the shell's curve (the paper's Sec. V names this loss).
  std::map<std::string, double> shell_thickness;
  for (const Sheet& sheet : sheets)
    if (!shell_thickness.count(sheet.location))
      shell_thickness[sheet.location] = random.uniform(2.0, 3.0) * 1e-3;
  for (const Sheet& sheet : sheets) {
    const double thickness = shell_thickness[sheet.location];
    const double air_gap = random.uniform(0.0, 0.4) * 1e-3;
    // The fringe field widens a pad's sensing area by about a third of the shell's thickness.
    const double radius = sheet.pad_radius + 0.3 * thickness * 1e3;
    const double area = std::numbers::pi * radius * radius * 1e-6;
    // Parallel plates, ABS and air in series: C = e0 A / (t / er + gap).
    const double capacitance =
        kVacuumPermittivity * area / (thickness / kShellPermittivity + air_gap);
    device.full_cover_counts.push_back(capacitance / kCountStep);
    device.sensing_radius.push_back(radius);
  }
  return device;
}

//---- Rendering -------------------------------------------------------------------------------

void render_front_end(const std::vector<Sheet>& sheets, const Device& device,
                      const std::vector<Touch>& touches, double coupling_scale, Random& noise,
                      SampleMatrix& samples) {
  const Eigen::Index frames = samples.rows();
  const Eigen::Index columns = samples.cols();
  samples.setZero();

  // Capacitance the hand adds, in counts, accumulated per pad and frame.
  const double slot = kFramePeriod / kScanSlots;
  for (const Touch& touch : touches) {
    const double first_time = touch.contact_start - touch.approach;
    const double last_time = touch.contact_end + touch.approach;
    const Eigen::Index first_frame =
        std::max<Eigen::Index>(0, static_cast<Eigen::Index>(std::floor(first_time / kFramePeriod)));
    const Eigen::Index last_frame = std::min<Eigen::Index>(
        frames - 1, static_cast<Eigen::Index>(std::floor(last_time / kFramePeriod)));
    const std::string& location = sheets[touch.sheet].location;
    // A palm near a sheet's edge reaches the next sheet of the same body part.
    for (size_t s = 0; s < sheets.size(); ++s) {
      const Sheet& sheet = sheets[s];
      if (sheet.location != location) continue;
      const double full = device.full_cover_counts[s] * coupling_scale;
      for (size_t pad = 0; pad < sheet.taxels.size(); ++pad) {
        const int column = sheet.columns[pad];
        for (Eigen::Index frame = first_frame; frame <= last_frame; ++frame) {
          double sum = 0.0;
          for (int k = 0; k < kConversionSamples; ++k) {
            const double t = static_cast<double>(frame) * kFramePeriod + sheet.scan_offsets[pad] +
                             (k + 0.5) / kConversionSamples * kConversionShare * slot;
            const double coupling = coupling_at(touch, t);
            if (coupling <= 0.0) continue;
            sum += coupling * pad_coverage(sheet.pad_centres[pad], device.sensing_radius[s],
                                           footprint_at(touch, t));
          }
          samples(frame, column) +=
              static_cast<float>(full * device.gain[column] * sum / kConversionSamples);
        }
      }
    }
  }

  // Board temperature per module: a warm-up towards a settled offset plus a slow random walk.
  std::vector<double> temperature(static_cast<size_t>(device.module_count * frames), 0.0);
  for (int module = 0; module < device.module_count; ++module) {
    const double warm_up = noise.uniform(0.0, 0.6);
    const double time_constant = noise.uniform(60.0, 240.0);
    double walk = 0.0;
    for (Eigen::Index frame = 0; frame < frames; ++frame) {
      walk += noise.normal(0.0, 0.004);
      const double t = static_cast<double>(frame) * kFramePeriod;
      temperature[module * frames + frame] = warm_up * (1.0 - std::exp(-t / time_constant)) + walk;
    }
  }

  for (Eigen::Index column = 0; column < columns; ++column) {
    const double offset = device.offset_counts[column];
    const double coefficient = device.temperature_coefficient[column];
    const double sigma = device.noise_counts[column];
    const double* board = &temperature[device.module_of_column[column] * frames];
    float* values = samples.col(column).data();
    for (Eigen::Index frame = 0; frame < frames; ++frame) {
      const double count =
          offset + coefficient * board[frame] + values[frame] + noise.normal(0.0, sigma);
      values[frame] = quantize(count, 0.0, kCountMax, 12);
    }
  }
}

}  // namespace tactile::sim::tsa

#include "fur_sensor.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tactile/error.h"

namespace tactile::sim::fur {

namespace {

// Sub-points per cell side: the pressure under a cell is sampled on a 4 x 4 grid.
constexpr int kSubpointsPerSide = 4;
constexpr int kSubpoints = kSubpointsPerSide * kSubpointsPerSide;
// 1 cm of plush plus the stiff carrier spread a contact over a wider patch (§2.1).
constexpr double kSpreadMm = 8.0;
// Velostat contact: conductance grows with the square of the local pressure above the
// electrodes' permanent contact (steep at light touch, paper 002 Fig 5).
constexpr double kPressureScaleKpa = 0.25;
constexpr double kPressureExponent = 2.0;
// Resting conductance of the smallest cell relative to the pull-up (>40 kOhm against the
// ATmega32's ~35 kOhm pull-up: about half the ADC range at rest).
constexpr double kRestConductance = 0.9;
// A fully pressed patch falls to about 5 Ohm: 35 kOhm / 5 Ohm.
constexpr double kMaxConductance = 7000.0;
constexpr double kFullScale = 1023.0;
// The ADC's offset error: inputs under three counts read 0, the floor of a saturated cell.
constexpr double kAdcOffsetCounts = 3.0;
// The microcontroller's low-pass over its 1 kHz samples before sending 15 Hz frames.
constexpr double kLowPassSeconds = 0.015;
// Sneak paths of the resistor matrix: a pressed cell lowers the reading of the cells
// sharing its row (next columns), its column (next rows) and its ADC line (diode partner).
// A sneak path runs through unpressed cells in series, so its conductance stays below
// theirs however hard the neighbour is pressed: the crosstalk is minor (§2.1).
constexpr double kRowCoupling = 0.15;
constexpr double kColumnCoupling = 0.1;
constexpr double kLineCoupling = 0.06;
constexpr double kSneakLimit = 1.0;
// Settling of fur, foam and fleece: a pressed cell keeps a residual compression that
// recovers over seconds, and a small part of it stays (the resting resistance changes
// after a contact, §2.1). Both are far slower than the 0.2 Hz high-pass of spec §3.2.
constexpr double kResidualPerKpa = 0.03;
constexpr double kResidualMax = 0.1;
constexpr double kResidualRiseSeconds = 1.5;
constexpr double kResidualRecoverySeconds = 12.0;
constexpr double kPermanentPerKpaSecond = 0.0015;
constexpr double kPermanentMax = 0.15;

}  // namespace

FurSensor::FurSensor(const SkinLayout& layout, Random& device) {
  int modality = layout.modality_index("pressure");
  if (modality < 0) modality = 0;
  double smallest_area = 0.0;
  for (const Taxel& taxel : layout.taxels) {
    if (modality >= static_cast<int>(taxel.channels.size()) || taxel.channels[modality] < 0)
      continue;
    Cell cell;
    cell.centre = taxel.position;
    cell.half_size = {taxel.size.x / 2, taxel.size.y / 2};
    cell.area = taxel.area > 0 ? taxel.area : taxel.size.x * taxel.size.y;
    cell.channel = taxel.channels[modality];
    cell.taxel_id = taxel.id;
    if (cell.area <= 0)
      throw Error("layout " + layout.id + " taxel " + taxel.name, "a fur cell needs an area");
    smallest_area = smallest_area == 0.0 ? cell.area : std::min(smallest_area, cell.area);
    cells_.push_back(cell);
  }
  if (cells_.empty()) throw Error("layout " + layout.id, "has no pressure cells");

  // A cell's conductance is its pressed area in parallel: the gain follows the area, with
  // the spread of hand-quilted electrodes (why each cell is calibrated, §2.1).
  for (Cell& cell : cells_) {
    cell.gain = cell.area / smallest_area * std::exp(device.truncated_normal(0.0, 0.1, 2.0));
    cell.rest_conductance = kRestConductance * cell.area / smallest_area *
                            std::exp(device.truncated_normal(0.0, 0.12, 2.0));
  }

  // Matrix rows: cells sharing a map row; columns: their order along it.
  std::vector<int> order(cells_.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return cells_[a].centre.y < cells_[b].centre.y; });
  std::vector<std::vector<int>> rows;
  for (int k : order) {
    if (rows.empty() || cells_[k].centre.y - cells_[rows.back().front()].centre.y > 1.0)
      rows.emplace_back();
    rows.back().push_back(k);
  }
  for (auto& row : rows)
    std::sort(row.begin(), row.end(),
              [&](int a, int b) { return cells_[a].centre.x < cells_[b].centre.x; });
  for (size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const size_t columns = row.size();
    for (size_t c = 0; c < columns; ++c) {
      auto& neighbours = cells_[row[c]].neighbours;
      if (c > 0) neighbours.push_back({row[c - 1], kRowCoupling});
      if (c + 1 < columns) neighbours.push_back({row[c + 1], kRowCoupling});
      if (columns % 2 == 0) neighbours.push_back({row[(c + columns / 2) % columns], kLineCoupling});
      for (size_t other : {r - 1, r + 1})
        if (other < rows.size() && rows[other].size() == columns)
          neighbours.push_back({rows[other][c], kColumnCoupling});
    }
  }

  const size_t count = cells_.size();
  pressure_.assign(count * kSubpoints, 0.0f);
  touched_.assign(count, 0);
  jitter_.assign(count, 1.0);
  touch_.assign(count, 0.0);
  residual_.assign(count, 0.0);
  permanent_.assign(count, 0.0);
  cell_force_.assign(count, 0.0);
  filtered_.resize(count);
  for (size_t k = 0; k < count; ++k) filtered_[k] = rest_reading(static_cast<int>(k));
}

void FurSensor::clear_pressure() {
  for (size_t k = 0; k < cells_.size(); ++k) {
    if (!touched_[k]) continue;
    std::fill_n(pressure_.begin() + static_cast<std::ptrdiff_t>(k * kSubpoints), kSubpoints, 0.0f);
    touched_[k] = 0;
  }
}

void FurSensor::press(const ContactPart& part) {
  const double along = part.half_length + kSpreadMm, across = part.half_width + kSpreadMm;
  if (part.force <= 0.0) return;
  // Paraboloid pressure over the spread ellipse: peak 2F / (pi a b), in kPa (N/mm^2 * 1000).
  const double peak = 2.0 * part.force / (std::numbers::pi * along * across) * 1000.0;
  const double c = std::cos(part.angle), s = std::sin(part.angle);
  const double reach = std::max(along, across);
  for (size_t k = 0; k < cells_.size(); ++k) {
    const Cell& cell = cells_[k];
    const double dx = cell.centre.x - part.centre.x, dy = cell.centre.y - part.centre.y;
    if (std::abs(dx) > reach + cell.half_size.x || std::abs(dy) > reach + cell.half_size.y)
      continue;
    float* pressure = &pressure_[k * kSubpoints];
    for (int i = 0; i < kSubpointsPerSide; ++i) {
      const double px = dx + cell.half_size.x * ((i + 0.5) * 2.0 / kSubpointsPerSide - 1.0);
      for (int j = 0; j < kSubpointsPerSide; ++j) {
        const double py = dy + cell.half_size.y * ((j + 0.5) * 2.0 / kSubpointsPerSide - 1.0);
        const double u = (px * c + py * s) / along, v = (-px * s + py * c) / across;
        const double radius = u * u + v * v;
        if (radius < 1.0) pressure[i * kSubpointsPerSide + j] += float(peak * (1.0 - radius));
      }
    }
    touched_[k] = 1;
  }
}

void FurSensor::draw_contact_jitter(Random& random) {
  for (double& factor : jitter_) factor = std::exp(random.normal(0.0, 0.05));
}

double FurSensor::touch_conductance(int cell) const {
  const float* pressure = &pressure_[static_cast<size_t>(cell) * kSubpoints];
  double sum = 0.0;
  for (int i = 0; i < kSubpoints; ++i)
    sum += std::pow(pressure[i] / kPressureScaleKpa, kPressureExponent);
  return cells_[cell].gain * sum / kSubpoints;
}

double FurSensor::adc_reading(double conductance) const {
  // Pull-up divider: raw = full scale * R_cell / (R_cell + R_pullup).
  const double divider = kFullScale / (1.0 + std::min(conductance, kMaxConductance));
  return std::clamp(divider - kAdcOffsetCounts, 0.0, kFullScale);
}

void FurSensor::advance(double dt) {
  const double smoothing = 1.0 - std::exp(-dt / kLowPassSeconds);
  const size_t count = cells_.size();
  for (size_t k = 0; k < count; ++k) {
    if (!touched_[k]) {
      touch_[k] = 0.0;
      cell_force_[k] = 0.0;
      continue;
    }
    touch_[k] = touch_conductance(static_cast<int>(k)) * jitter_[k];
    const float* pressure = &pressure_[k * kSubpoints];
    double mean_pressure = 0.0;
    for (int i = 0; i < kSubpoints; ++i) mean_pressure += pressure[i];
    mean_pressure /= kSubpoints;
    cell_force_[k] = mean_pressure * cells_[k].area / 1000.0;
  }
  for (size_t k = 0; k < count; ++k) {
    const Cell& cell = cells_[k];
    const double load = cell_force_[k] * 1000.0 / cell.area;  // mean pressure, kPa
    const double target = std::min(kResidualPerKpa * load, kResidualMax);
    if (target > residual_[k])
      residual_[k] += (target - residual_[k]) * dt / kResidualRiseSeconds;
    else
      residual_[k] -= residual_[k] * dt / kResidualRecoverySeconds;
    permanent_[k] = std::min(kPermanentMax, permanent_[k] + kPermanentPerKpaSecond * load * dt);

    double conductance =
        cell.rest_conductance * (1.0 + residual_[k] + permanent_[k]) * drift_ + touch_[k];
    for (const Neighbour& neighbour : cell.neighbours) {
      const double pressed = touch_[neighbour.cell];
      conductance += neighbour.coupling * kSneakLimit * pressed / (pressed + kSneakLimit);
    }
    filtered_[k] += smoothing * (adc_reading(conductance) - filtered_[k]);
  }
}

double FurSensor::rest_reading(int cell) const {
  return adc_reading(cells_[cell].rest_conductance * drift_);
}

double FurSensor::reading_under_reference(int cell, double force, double diameter) {
  clear_pressure();
  press({cells_[cell].centre, diameter / 2, diameter / 2, 0.0, force});
  const double reading =
      adc_reading(cells_[cell].rest_conductance * drift_ + touch_conductance(cell));
  clear_pressure();
  return reading;
}

}  // namespace tactile::sim::fur

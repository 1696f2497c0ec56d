#include "tactile/sim/flux_sensor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tactile/error.h"

namespace tactile::sim {

namespace {

// Paper 004 §3.2: a 1 mm cover over the top serpentines and 1 mm of insulation between the two
// sensing layers (whose own thickness is a fraction of a millimetre).
constexpr double kCoverDepth = 1.0;    // mm
constexpr double kLayerSpacing = 1.1;  // mm
// Widening of a load with depth in the soft cover: a point load spreads over about its depth.
constexpr double kSpreadPerDepth = 1.0;  // mm of standard deviation per mm of depth
// Lateral stretch: share of the load felt by a serpentine right under the finger through the
// silicone's in-plane strain, and the distance over which that strain fades.
constexpr double kStretchShare = 0.30;
constexpr double kStretchLength = 9.0;  // mm
// The calibration in Ohm/kPa refers to a fingertip-sized indenter (paper §4.1 does not give its
// area; 100 mm^2 is a fingertip's contact): a serpentine's resistance follows the load on its
// path, so its effective pressure is that load over this area.
constexpr double kIndenterArea = 100.0;  // mm^2
// Drive and read-out (paper §3.3 gives the topology, not the values): 1 mA through the
// serpentine, amplifier gain 3.67, 10-bit ADC on 5 V, so a 520-560 Ohm serpentine rests near
// 400 counts and the top 600 counts are left for the touch.
constexpr double kDriveCurrent = 1.0e-3;  // A
constexpr double kAmplifierGain = 3.67;
constexpr double kAdcReference = 5.0;  // V

// Share of a Gaussian N(centre, spread^2) inside [low, high].
double interval_share(double low, double high, double centre, double spread) {
  const double scale = 1.0 / (std::sqrt(2.0) * spread);
  return 0.5 * (std::erf((high - centre) * scale) - std::erf((low - centre) * scale));
}

}  // namespace

//---- Geometry

FluxGeometry flux_geometry(const SkinLayout& layout) {
  const std::string where = "layout " + layout.id;
  std::vector<const Group*> layers;
  for (const Group& group : layout.groups)
    if (group.kind == "layer") layers.push_back(&group);
  if (layers.empty()) throw Error(where, "no group of kind \"layer\" to place the serpentines");

  FluxGeometry geometry;
  for (size_t layer = 0; layer < layers.size(); ++layer) {
    double min_x = std::numeric_limits<double>::max(), min_y = min_x;
    double max_x = -min_x, max_y = -min_x;
    std::vector<const Taxel*> taxels;
    for (int64_t id : layers[layer]->taxels) {
      const Taxel* taxel = layout.find_taxel(id);
      if (taxel == nullptr)
        throw Error(where,
                    "layer \"" + layers[layer]->id + "\": unknown taxel " + std::to_string(id));
      if (taxel->channels.empty() || taxel->channels[0] < 0)
        throw Error(where + " taxel " + std::to_string(id), "serpentine without a channel");
      taxels.push_back(taxel);
      min_x = std::min(min_x, taxel->position.x - taxel->size.x / 2);
      max_x = std::max(max_x, taxel->position.x + taxel->size.x / 2);
      min_y = std::min(min_y, taxel->position.y - taxel->size.y / 2);
      max_y = std::max(max_y, taxel->position.y + taxel->size.y / 2);
    }
    if (taxels.empty() || max_x <= min_x || max_y <= min_y)
      throw Error(where, "layer \"" + layers[layer]->id + "\" covers no area");
    if (layer == 0) {
      geometry.width = max_x - min_x;
      geometry.height = max_y - min_y;
    }
    const double scale_u = geometry.width / (max_x - min_x);
    const double scale_v = geometry.height / (max_y - min_y);
    for (const Taxel* taxel : taxels) {
      Serpentine serpentine;
      serpentine.taxel_id = taxel->id;
      serpentine.layout_channel = taxel->channels[0];
      serpentine.layer = static_cast<int>(layer);
      serpentine.u0 = (taxel->position.x - taxel->size.x / 2 - min_x) * scale_u;
      serpentine.u1 = (taxel->position.x + taxel->size.x / 2 - min_x) * scale_u;
      serpentine.v0 = (taxel->position.y - taxel->size.y / 2 - min_y) * scale_v;
      serpentine.v1 = (taxel->position.y + taxel->size.y / 2 - min_y) * scale_v;
      serpentine.depth = kCoverDepth + kLayerSpacing * static_cast<double>(layer);
      geometry.serpentines.push_back(serpentine);
    }
  }
  return geometry;
}

//---- Mechanics

void serpentine_pressures(const FluxGeometry& geometry, const FingerContact& contact,
                          double* pressures) {
  // Marginal spreads of the rotated elliptical footprint along u and v.
  const double cosine = std::cos(contact.angle), sine = std::sin(contact.angle);
  const double along = contact.spread_along * contact.spread_along;
  const double across = contact.spread_across * contact.spread_across;
  const double variance_u = along * cosine * cosine + across * sine * sine;
  const double variance_v = along * sine * sine + across * cosine * cosine;
  const double load = std::max(contact.force, 0.0) * 1000.0 / kIndenterArea;  // N/mm^2 -> kPa

  for (size_t k = 0; k < geometry.serpentines.size(); ++k) {
    const Serpentine& serpentine = geometry.serpentines[k];
    const double widening = kSpreadPerDepth * serpentine.depth;
    const double spread_u = std::sqrt(variance_u + widening * widening);
    const double spread_v = std::sqrt(variance_v + widening * widening);
    const double direct = interval_share(serpentine.u0, serpentine.u1, contact.u, spread_u) *
                          interval_share(serpentine.v0, serpentine.v1, contact.v, spread_v);
    const double outside_u = std::max({serpentine.u0 - contact.u, contact.u - serpentine.u1, 0.0});
    const double outside_v = std::max({serpentine.v0 - contact.v, contact.v - serpentine.v1, 0.0});
    const double distance = std::hypot(outside_u, outside_v);
    const double stretch = kStretchShare * std::exp(-distance / kStretchLength);
    pressures[k] = load * (direct + stretch);
  }
}

ViscoelasticSerpentine::ViscoelasticSerpentine(double rate_hz, double relaxation_s)
    : elastic_rate_(1.0 - std::exp(-1.0 / (rate_hz * kElasticTime))),
      creep_rate_(1.0 - std::exp(-1.0 / (rate_hz * kCreepTime))),
      relax_rate_(1.0 - std::exp(-1.0 / (rate_hz * relaxation_s))) {}

//---- Electronics and temperature

double flux_baseline_ohm(double temperature_c) { return 519.6 + 1.03 * (temperature_c - 10.0); }

double flux_gain_ohm_per_kpa(double temperature_c) {
  return 4.67 + (15.99 - 4.67) / 40.0 * (temperature_c - 10.0);
}

double flux_counts_per_ohm() {
  return kDriveCurrent * kAmplifierGain * kFluxAdcMax / kAdcReference;
}

}  // namespace tactile::sim

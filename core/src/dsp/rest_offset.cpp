#include "tactile/dsp/rest_offset.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tactile/stats/statistics.h"

namespace tactile {

float rest_offset(const Eigen::Ref<const Eigen::VectorXf>& force,
                  const Eigen::Ref<const Eigen::VectorXf>& proximity_mm, double contact_mm) {
  std::vector<float> resting;
  float smallest = std::numeric_limits<float>::infinity();
  const Eigen::Index count = std::min(force.size(), proximity_mm.size());
  for (Eigen::Index t = 0; t < count; ++t) {
    if (!std::isfinite(force[t])) continue;
    smallest = std::min(smallest, force[t]);
    if (std::isfinite(proximity_mm[t]) && proximity_mm[t] >= contact_mm)
      resting.push_back(force[t]);
  }
  if (resting.empty()) return std::isfinite(smallest) ? smallest : 0.0f;
  // The median resists the odd spike a hand hovering just beyond contact_mm may cause.
  return stats::median(std::move(resting));
}

}  // namespace tactile

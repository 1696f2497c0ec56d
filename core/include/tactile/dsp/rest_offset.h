#pragma once
// Rest offset of a force sensor (spec §1.3, §1.10): the adapted baselines' max and threshold
// features need force referenced to what the sensor reads with nothing on it (the silicone's
// preload), not the zero-mean signal of the proposed descriptor.

#include <Eigen/Core>

namespace tactile {

// The median of `force` over the samples whose `proximity_mm` is >= contact_mm (nothing near
// the cell); the minimum of `force` when there is no such sample; 0 for an empty signal.
// Non-finite samples are ignored. Both vectors have one entry per sample.
float rest_offset(const Eigen::Ref<const Eigen::VectorXf>& force,
                  const Eigen::Ref<const Eigen::VectorXf>& proximity_mm, double contact_mm);

}  // namespace tactile

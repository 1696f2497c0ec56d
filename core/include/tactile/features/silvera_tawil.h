#pragma once
// Silvera-Tawil et al.'s features as adapted by Kaboli et al. (spec §1.12, eqs. 18-21), on the
// force elements of the touched NAO body part: maximum intensity, spatial resolution, mean
// intensity, contact time and rate of intensity change.
//
// Parameters: threshold_mm (50), f_thresh (0.05 N), elements (ALL | CONTACT),
// sr_mode (TEXT = elements >= half the maximum intensity at its time | LITERAL = eq. 19, half the
// peak total load at its time), roi_mode (ABSOLUTE = Σ|second difference| | SIGNED = eq. 21 as
// printed, which telescopes).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

enum class SpatialResolutionMode { kText, kLiteral };
enum class IntensityChangeMode { kAbsolute, kSigned };
using SilveraTawilDescriptor = std::array<double, 5>;

// [I_max, SR, MOI, CT (s), ROI] of a T x E force matrix (one column per element).
SilveraTawilDescriptor silvera_tawil_descriptor(
    const Eigen::MatrixXd& force, double force_threshold, double rate_hz,
    SpatialResolutionMode resolution_mode = SpatialResolutionMode::kText,
    IntensityChangeMode change_mode = IntensityChangeMode::kAbsolute);

std::vector<FeatureColumn> silvera_tawil_columns();
std::unique_ptr<FeatureExtractor> make_silvera_tawil_extractor(const Parameters& parameters);

}  // namespace tactile

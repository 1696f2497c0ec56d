#pragma once
// Naya et al.'s features as adapted by Kaboli et al. (spec §1.11, eqs. 13-17), on the force
// elements of the touched NAO body part: peak total load, contact area, and how much load and
// area changed into the peak.
//
// Parameters: threshold_mm (50), f_thresh (0.05 N), elements (ALL | CONTACT),
// naya_area (MAX = max over time, eq. 14 | AT_TMAX = area at the peak load, the text's reading).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

enum class NayaArea { kMaxOverTime, kAtPeakLoad };
using NayaDescriptor = std::array<double, 4>;

// [w_peak, a_peak, δw_peak, δa_peak] of a T x E force matrix (one column per element), with
// contact b_e(t) = F_e(t) >= force_threshold and the sample before t = 0 taken as F = 0, b = 0.
NayaDescriptor naya_descriptor(const Eigen::MatrixXd& force, double force_threshold,
                               NayaArea area_mode = NayaArea::kMaxOverTime);

std::vector<FeatureColumn> naya_columns();
std::unique_ptr<FeatureExtractor> make_naya_extractor(const Parameters& parameters);

}  // namespace tactile

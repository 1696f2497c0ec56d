#pragma once
// Koo et al.'s features as adapted by Kaboli et al. (spec §1.13, eqs. 22-23): variance of a
// representative acceleration, contact time, and the number of contact-area changes.
//
// Parameters: threshold_mm (50), f_thresh (0.05 N), elements (ALL | CONTACT),
// cac_mode (ABSOLUTE = on/off transitions | SIGNED = eq. 23 as printed, which telescopes).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

enum class ContactChangeMode { kAbsolute, kSigned };
using KooDescriptor = std::array<double, 3>;

// Spec §1.13: A_rep(t) = (1/|C|) Σ_c sqrt(ax_c² + ay_c² + az_c²), from a T x 3|C| matrix whose
// columns are ax, ay, az of each cell in turn (raw, not zero-mean). Empty input: empty output.
Eigen::VectorXd koo_representative_acceleration(const Eigen::MatrixXd& acceleration);

// [F_total, CT (s), CAC] from A_rep and a T x E force matrix (one column per element).
KooDescriptor koo_descriptor(const Eigen::VectorXd& representative_acceleration,
                             const Eigen::MatrixXd& force, double force_threshold, double rate_hz,
                             ContactChangeMode change_mode = ContactChangeMode::kAbsolute);

std::vector<FeatureColumn> koo_columns();
std::unique_ptr<FeatureExtractor> make_koo_extractor(const Parameters& parameters);

}  // namespace tactile

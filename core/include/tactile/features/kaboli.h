#pragma once
// Kaboli et al. (spec §1.2-1.8): the 16-value Hjorth and correlation descriptor of one NAO body
// part. Per cell in contact: Pearson and Spearman correlations between the accelerometer axes,
// Hjorth Activity, Mobility and Complexity of each axis, and the mean force Activity; summed
// over the contacted cells and divided by the cells of the body part (or the contacted ones).
//
// Parameters: threshold_mm (50, the contact distance of eq. 1), norm_mode (BODY_PART | CONTACT),
// ncorr_mode (RANKS = Pearson of average ranks | EQ6 = eq. 6 as printed), motion_hz (cut-off of
// the high-pass that takes the robot's own motion out of the accelerometers; 0 = none, as
// printed in the paper; see kDefaultMotionCutoffHz), motion_order (that high-pass's order:
// 2, 4, 6 or 8; see kDefaultMotionOrder).

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

constexpr int kKaboliValues = 16;
// Not in the paper (spec §1.3 only removes the mean): a moving NAO turns gravity by up to half a
// g through its cells' accelerometers while it sits down or stands up, a hundred times the
// variance a push adds, so no descriptor of the raw axes can be invariant to its motion.
// Butterworth high-pass of this order at this cut-off, over the window and the second before
// it: the gait (steps at up to about 2 Hz) falls 42 dB below 7 Hz, a touch's torso sway
// (3-9 Hz) and plate ringing (15-75 Hz) mostly pass. docs/SIMULATION.md has the scan.
constexpr double kDefaultMotionCutoffHz = 7.0;
constexpr int kDefaultMotionOrder = 4;
using KaboliDescriptor = std::array<double, kKaboliValues>;

enum class NcorrMode { kRanks, kEq6 };
enum class AreaNormalisation { kBodyPart, kContact };

// Spec §1.7: one cell's descriptor, in the order
// Lcorr(ax,ay), Lcorr(ax,az), Lcorr(ay,az), Ncorr(same pairs), Act/Mob/Comp of ax, ay, az,
// (1/N_f) Σ_f Act(F_f). Every value is invariant to a constant offset of its signals.
KaboliDescriptor kaboli_cell_descriptor(std::span<const double> ax, std::span<const double> ay,
                                        std::span<const double> az,
                                        const std::vector<std::span<const double>>& forces,
                                        NcorrMode ncorr_mode = NcorrMode::kRanks);

// Kaboli et al. eqs. (7)-(12): (1/N_c) Σ_c ζ_c p_c, given the descriptors of the contacted
// cells (ζ = 1) of a body part of `body_part_cells` cells; kContact divides by Σζ instead.
// No contacted cell gives the zero vector.
KaboliDescriptor kaboli_area_descriptor(std::span<const KaboliDescriptor> contacted_cells,
                                        int64_t body_part_cells, AreaNormalisation normalisation);

// Column names and descriptions, in descriptor order.
std::vector<FeatureColumn> kaboli_columns();

std::unique_ptr<FeatureExtractor> make_kaboli_extractor(const Parameters& parameters);

}  // namespace tactile

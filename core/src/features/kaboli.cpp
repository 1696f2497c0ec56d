#include "tactile/features/kaboli.h"

#include <Eigen/Core>
#include <sstream>

#include "tactile/dsp/butterworth.h"
#include "tactile/dsp/zero_mean.h"
#include "tactile/error.h"
#include "tactile/segment/nao_window.h"
#include "tactile/stats/statistics.h"

namespace tactile {

//---- Descriptors

KaboliDescriptor kaboli_cell_descriptor(std::span<const double> ax, std::span<const double> ay,
                                        std::span<const double> az,
                                        const std::vector<std::span<const double>>& forces,
                                        NcorrMode ncorr_mode) {
  KaboliDescriptor p{};
  // Kaboli et al. eq. (5): Lcorr = Pearson correlation between two axes.
  p[0] = stats::pearson(ax, ay);
  p[1] = stats::pearson(ax, az);
  p[2] = stats::pearson(ay, az);
  // Kaboli et al. eq. (6): Ncorr = Spearman rank correlation between two axes.
  if (ncorr_mode == NcorrMode::kEq6) {
    p[3] = stats::spearman_eq6(ax, ay);
    p[4] = stats::spearman_eq6(ax, az);
    p[5] = stats::spearman_eq6(ay, az);
  } else {
    // stats::spearman is Pearson of average ranks; each axis is ranked once, not once per pair
    // (ranking is the costliest step of the descriptor).
    const std::vector<double> rank_x = stats::rank(ax), rank_y = stats::rank(ay),
                              rank_z = stats::rank(az);
    p[3] = stats::pearson(rank_x, rank_y);
    p[4] = stats::pearson(rank_x, rank_z);
    p[5] = stats::pearson(rank_y, rank_z);
  }
  // Kaboli et al. eqs. (2)-(4): Hjorth Activity, Mobility, Complexity per axis.
  const std::array<std::span<const double>, 3> axes = {ax, ay, az};
  for (size_t axis = 0; axis < 3; ++axis) {
    const stats::Hjorth hjorth = stats::hjorth(axes[axis]);
    p[6 + 3 * axis] = hjorth.activity;
    p[7 + 3 * axis] = hjorth.mobility;
    p[8 + 3 * axis] = hjorth.complexity;
  }
  // Kaboli et al. Sec 5.4: force Activity averaged over the cell's N_f sensors.
  double force_activity = 0.0;
  for (std::span<const double> force : forces) force_activity += stats::variance(force);
  p[15] = forces.empty() ? 0.0 : force_activity / static_cast<double>(forces.size());
  return p;
}

KaboliDescriptor kaboli_area_descriptor(std::span<const KaboliDescriptor> contacted_cells,
                                        int64_t body_part_cells, AreaNormalisation normalisation) {
  KaboliDescriptor area{};
  if (contacted_cells.empty()) return area;
  // Kaboli et al. eqs. (7)-(12): Lc_k = (1/N_c) Σ_c ζ_c p_c[k]; cells with ζ = 0 add nothing.
  for (const KaboliDescriptor& cell : contacted_cells)
    for (int k = 0; k < kKaboliValues; ++k) area[k] += cell[k];
  const int64_t divisor = normalisation == AreaNormalisation::kContact
                              ? static_cast<int64_t>(contacted_cells.size())
                              : body_part_cells;
  if (divisor <= 0) return KaboliDescriptor{};
  for (double& value : area) value /= static_cast<double>(divisor);
  return area;
}

std::vector<FeatureColumn> kaboli_columns() {
  std::vector<FeatureColumn> columns = {
      {"lcorr_ax_ay", "Pearson correlation of ax and ay, Kaboli eq. (5)"},
      {"lcorr_ax_az", "Pearson correlation of ax and az, Kaboli eq. (5)"},
      {"lcorr_ay_az", "Pearson correlation of ay and az, Kaboli eq. (5)"},
      {"ncorr_ax_ay", "Spearman rank correlation of ax and ay, Kaboli eq. (6)"},
      {"ncorr_ax_az", "Spearman rank correlation of ax and az, Kaboli eq. (6)"},
      {"ncorr_ay_az", "Spearman rank correlation of ay and az, Kaboli eq. (6)"},
  };
  for (const char* axis : {"ax", "ay", "az"}) {
    const std::string name(axis);
    columns.push_back(
        {"activity_" + name, "Hjorth Activity of " + name + " (g^2), Kaboli eq. (2)"});
    columns.push_back(
        {"mobility_" + name, "Hjorth Mobility of " + name + " (per sample), Kaboli eq. (3)"});
    columns.push_back({"complexity_" + name, "Hjorth Complexity of " + name + ", Kaboli eq. (4)"});
  }
  columns.push_back(
      {"force_activity", "mean Activity of the normal-force sensors (N^2), Kaboli Sec 5.4"});
  for (FeatureColumn& column : columns)
    column.description += "; sum over contacted cells / cells of the body part, eqs. (7)-(12)";
  return columns;
}

//---- Extractor

namespace {

class KaboliExtractor : public FeatureExtractor {
 public:
  explicit KaboliExtractor(const Parameters& parameters) {
    parameters.expect_only(
        {"threshold_mm", "norm_mode", "ncorr_mode", "motion_hz", "motion_order"});
    contact_mm_ = positive_parameter(parameters, "threshold_mm", kDefaultContactDistanceMm);
    motion_hz_ = parameters.number("motion_hz", kDefaultMotionCutoffHz);
    if (!(motion_hz_ >= 0.0) || !std::isfinite(motion_hz_))
      throw Error("motion_hz", "must be 0 (keep the robot's motion) or a cut-off in Hz");
    const int64_t order = parameters.integer("motion_order", kDefaultMotionOrder);
    if (order < 2 || order > 8 || !dsp::is_butterworth_order(static_cast<int>(order)))
      throw Error("motion_order",
                  std::to_string(order) + ": the high-pass order must be 2, 4, 6 or 8");
    motion_order_ = static_cast<int>(order);
    normalisation_ =
        parameter_choice(parameters, "norm_mode", {"BODY_PART", "CONTACT"}) == "CONTACT"
            ? AreaNormalisation::kContact
            : AreaNormalisation::kBodyPart;
    ncorr_mode_ = parameter_choice(parameters, "ncorr_mode", {"RANKS", "EQ6"}) == "EQ6"
                      ? NcorrMode::kEq6
                      : NcorrMode::kRanks;
  }

  std::string name() const override { return "kaboli"; }
  std::string description() const override {
    std::ostringstream text;
    text << "Kaboli et al.: 16 Hjorth and correlation values of the touched body part, over the "
            "cells whose proximity came closer than "
         << contact_mm_ << " mm";
    if (motion_hz_ > 0.0)
      text << "; accelerometers high-passed at " << motion_hz_ << " Hz, order " << motion_order_
           << " (the robot's own motion)";
    return text.str();
  }
  std::vector<FeatureColumn> columns(const SkinLayout&) const override { return kaboli_columns(); }

  FeatureResult extract(const SegmentInput& input) const override {
    const NaoSkin skin = locate_nao_skin(input.recording, input.layout);
    // Hjorth Complexity needs a second difference: three samples.
    const ContactWindow window = contact_window(skin, input.segment, contact_mm_, 3);
    if (!window.skip_reason.empty()) return FeatureResult::skip(window.skip_reason);

    const Stream& stream = *skin.stream;
    const BodyPart& part = skin.body_parts[static_cast<size_t>(window.body_part)];
    if (motion_hz_ > 0.0 && !(motion_hz_ < 0.5 * stream.rate_hz))
      throw Error("motion_hz", "cut-off " + std::to_string(motion_hz_) +
                                   " Hz is not below half the stream's rate (" +
                                   std::to_string(0.5 * stream.rate_hz) + " Hz)");
    const std::vector<dsp::Biquad> motion_filter =
        motion_hz_ > 0.0 ? dsp::butterworth_high_pass(motion_hz_, stream.rate_hz, motion_order_)
                         : std::vector<dsp::Biquad>{};
    std::vector<KaboliDescriptor> contacted;
    contacted.reserve(static_cast<size_t>(window.contacted_cells));
    // One T x (3 + N_f) block per cell, reused: each signal a contiguous column.
    Eigen::MatrixXd signals;
    std::vector<int> columns;
    for (size_t c = 0; c < part.cells.size(); ++c) {
      // Cells with ζ = 0 contribute nothing to eqs. (7)-(12): skip them (the paper's saving).
      if (!window.contact[c]) continue;
      const CellColumns& cell = part.cells[c];
      columns.assign(cell.acceleration.begin(), cell.acceleration.end());
      columns.insert(columns.end(), cell.force.begin(), cell.force.end());
      // The robot's own motion leaves the accelerometers through a high-pass that starts a
      // second before the window, so it has settled when the window begins.
      const int64_t lead =
          motion_hz_ > 0.0 ? std::min<int64_t>(window.first, std::llround(stream.rate_hz)) : 0;
      const std::string bad =
          find_non_finite(stream, columns, window.first - lead, window.count + lead);
      if (!bad.empty()) return FeatureResult::skip(bad);
      signals.resize(window.count, static_cast<Eigen::Index>(columns.size()));
      for (size_t k = 0; k < columns.size(); ++k) {
        const Eigen::VectorXd raw = stream.samples.col(columns[k])
                                        .segment(window.first - lead, window.count + lead)
                                        .cast<double>();
        if (k < 3 && motion_hz_ > 0.0)
          signals.col(static_cast<Eigen::Index>(k)) =
              dsp::filter(motion_filter, raw).tail(window.count);
        else
          signals.col(static_cast<Eigen::Index>(k)) = raw.tail(window.count);
      }
      zero_mean_columns(signals);  // Kaboli et al. Sec 5.2
      const auto signal = [&](size_t k) {
        return std::span<const double>(signals.col(static_cast<Eigen::Index>(k)).data(),
                                       static_cast<size_t>(window.count));
      };
      std::vector<std::span<const double>> forces;
      for (size_t f = 0; f < cell.force.size(); ++f) forces.push_back(signal(3 + f));
      contacted.push_back(
          kaboli_cell_descriptor(signal(0), signal(1), signal(2), forces, ncorr_mode_));
    }
    const KaboliDescriptor area =
        kaboli_area_descriptor(contacted, static_cast<int64_t>(part.cells.size()), normalisation_);
    FeatureResult result;
    result.values.assign(area.begin(), area.end());
    return result;
  }

 private:
  double contact_mm_ = kDefaultContactDistanceMm;
  double motion_hz_ = kDefaultMotionCutoffHz;
  int motion_order_ = kDefaultMotionOrder;
  AreaNormalisation normalisation_ = AreaNormalisation::kBodyPart;
  NcorrMode ncorr_mode_ = NcorrMode::kRanks;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_kaboli_extractor(const Parameters& parameters) {
  return std::make_unique<KaboliExtractor>(parameters);
}

}  // namespace tactile

#include "tactile/features/silvera_tawil.h"

#include <span>

#include "nao_baseline.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

std::span<const double> as_span(const Eigen::VectorXd& vector) {
  return {vector.data(), static_cast<size_t>(vector.size())};
}

}  // namespace

SilveraTawilDescriptor silvera_tawil_descriptor(const Eigen::MatrixXd& force,
                                                double force_threshold, double rate_hz,
                                                SpatialResolutionMode resolution_mode,
                                                IntensityChangeMode change_mode) {
  SilveraTawilDescriptor result{};
  const int64_t samples = force.rows();
  const int64_t elements = force.cols();
  if (samples == 0 || elements == 0) return result;

  // f1: I_max = max_{e,t} F_e(t); t* = the first sample at which some element reaches it.
  const Eigen::VectorXd sample_maximum = force.rowwise().maxCoeff();
  const int64_t peak_time = stats::argmax(as_span(sample_maximum));
  const double maximum_intensity = sample_maximum[peak_time];
  result[0] = maximum_intensity;

  // Kaboli et al. eqs. (18)-(19): SR = (1/E) Σ_e [F_e(t) >= level], the text's level being
  // half of I_max at t*, eq. (19)'s half of the peak total load at its time.
  if (resolution_mode == SpatialResolutionMode::kText) {
    if (maximum_intensity > 0.0)
      result[1] =
          static_cast<double>((force.row(peak_time).array() >= 0.5 * maximum_intensity).count()) /
          static_cast<double>(elements);
  } else {
    const Eigen::VectorXd total = force.rowwise().sum();
    const int64_t peak_load_time = stats::argmax(as_span(total));
    if (total[peak_load_time] > 0.0)
      result[1] = static_cast<double>(
                      (force.row(peak_load_time).array() >= 0.5 * total[peak_load_time]).count()) /
                  static_cast<double>(elements);
  }

  // Kaboli et al. eq. (20): MOI = (1/(T E)) Σ_t Σ_e F_e(t), over the T samples of the window.
  result[2] = force.mean();

  // Contact time: (1/fs) #{t : some element >= f_thresh}.
  result[3] = contact_time(force, force_threshold, rate_hz);

  // Kaboli et al. eq. (21): g_e(t) = |F_e(t) - F_e(t-1)|, h_e(t) = g_e(t+1) - 2 g_e(t) + g_e(t-1),
  // ROI = Σ_e Σ_t |h_e(t)| (per-sample units).
  if (samples >= 4) {
    const Eigen::ArrayXXd change =
        (force.bottomRows(samples - 1) - force.topRows(samples - 1)).array().abs();
    const int64_t rows = samples - 3;
    const Eigen::ArrayXXd second =
        change.bottomRows(rows) - 2.0 * change.middleRows(1, rows) + change.topRows(rows);
    result[4] = change_mode == IntensityChangeMode::kSigned ? second.sum() : second.abs().sum();
  }
  return result;
}

std::vector<FeatureColumn> silvera_tawil_columns() {
  return {{"max_intensity", "I_max: largest force of any element (N), Kaboli Sec 6.2 f1"},
          {"spatial_resolution",
           "SR: share of elements >= I_max / 2 at its time, Kaboli eqs. (18)-(19)"},
          {"mean_intensity", "MOI: mean force over samples and elements (N), Kaboli eq. (20)"},
          {"contact_time", "CT: samples with some element >= f_thresh, divided by fs (s)"},
          {"intensity_change_rate",
           "ROI: Σ |second difference of |ΔF|| (N per sample^2), Kaboli eq. (21)"}};
}

namespace {

class SilveraTawilExtractor : public FeatureExtractor {
 public:
  explicit SilveraTawilExtractor(const Parameters& parameters) {
    std::vector<std::string> keys = BaselineSettings::keys();
    keys.push_back("sr_mode");
    keys.push_back("roi_mode");
    parameters.expect_only(keys);
    settings_ = BaselineSettings::parse(parameters);
    resolution_mode_ = parameter_choice(parameters, "sr_mode", {"TEXT", "LITERAL"}) == "LITERAL"
                           ? SpatialResolutionMode::kLiteral
                           : SpatialResolutionMode::kText;
    change_mode_ = parameter_choice(parameters, "roi_mode", {"ABSOLUTE", "SIGNED"}) == "SIGNED"
                       ? IntensityChangeMode::kSigned
                       : IntensityChangeMode::kAbsolute;
  }
  std::string name() const override { return "silvera_tawil"; }
  std::string description() const override {
    return "Adapted Silvera-Tawil (Kaboli eqs. 18-21): intensity, spatial resolution, contact time "
           "and "
           "rate of intensity change; " +
           settings_.describe();
  }
  std::vector<FeatureColumn> columns(const SkinLayout&) const override {
    return silvera_tawil_columns();
  }
  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return remove_force_rest_offsets(recording, layout, settings_.contact_mm);
  }
  FeatureResult extract(const SegmentInput& input) const override {
    const BaselineWindow window = baseline_window(input, settings_);
    if (!window.skip_reason.empty()) return FeatureResult::skip(window.skip_reason);
    const SilveraTawilDescriptor values =
        silvera_tawil_descriptor(window.force, settings_.force_threshold,
                                 window.skin.stream->rate_hz, resolution_mode_, change_mode_);
    return {{values.begin(), values.end()}, {}};
  }

 private:
  BaselineSettings settings_;
  SpatialResolutionMode resolution_mode_ = SpatialResolutionMode::kText;
  IntensityChangeMode change_mode_ = IntensityChangeMode::kAbsolute;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_silvera_tawil_extractor(const Parameters& parameters) {
  return std::make_unique<SilveraTawilExtractor>(parameters);
}

}  // namespace tactile

#include "tactile/features/naya.h"

#include <span>

#include "nao_baseline.h"
#include "tactile/stats/statistics.h"

namespace tactile {

NayaDescriptor naya_descriptor(const Eigen::MatrixXd& force, double force_threshold,
                               NayaArea area_mode) {
  NayaDescriptor result{};
  if (force.rows() == 0 || force.cols() == 0) return result;
  const Eigen::VectorXd total = force.rowwise().sum();  // W(t)
  const Eigen::ArrayXXd contact = contact_elements(force, force_threshold);
  const Eigen::VectorXd area = contact.rowwise().sum().matrix();  // a(t)
  const int64_t peak =
      stats::argmax(std::span<const double>(total.data(), static_cast<size_t>(total.size())));
  // Before the window the skin is at rest: F = 0, b = 0.
  const Eigen::RowVectorXd force_before =
      peak > 0 ? Eigen::RowVectorXd(force.row(peak - 1)) : Eigen::RowVectorXd::Zero(force.cols());
  const Eigen::RowVectorXd contact_before = peak > 0
                                                ? Eigen::RowVectorXd(contact.row(peak - 1).matrix())
                                                : Eigen::RowVectorXd::Zero(force.cols());
  // Kaboli et al. eq. (13): w_peak = W(t_max).
  result[0] = total[peak];
  // Kaboli et al. eq. (14): a_peak = max_t a(t) (or a(t_max), the text's reading).
  result[1] = area_mode == NayaArea::kAtPeakLoad ? area[peak] : area.maxCoeff();
  // Kaboli et al. eq. (16): δw_peak = Σ_e |F_e(t_max) - F_e(t_max - 1)| / W(t_max).
  if (total[peak] > 0.0)
    result[2] = (force.row(peak) - force_before).cwiseAbs().sum() / total[peak];
  // Kaboli et al. eq. (17): δa_peak = Σ_e |b_e(t_max) - b_e(t_max - 1)| / a(t_max).
  if (area[peak] > 0.0)
    result[3] = (contact.row(peak).matrix() - contact_before).cwiseAbs().sum() / area[peak];
  return result;
}

std::vector<FeatureColumn> naya_columns() {
  return {{"peak_load", "w_peak: maximum over time of the total force (N), Kaboli eq. (13)"},
          {"peak_contact_area",
           "a_peak: maximum number of force elements >= f_thresh, Kaboli eq. (14)"},
          {"peak_load_change", "δw_peak: Σ|F(t_max) - F(t_max-1)| / w_peak, Kaboli eq. (16)"},
          {"peak_area_change", "δa_peak: Σ|b(t_max) - b(t_max-1)| / a(t_max), Kaboli eq. (17)"}};
}

namespace {

class NayaExtractor : public FeatureExtractor {
 public:
  explicit NayaExtractor(const Parameters& parameters) {
    std::vector<std::string> keys = BaselineSettings::keys();
    keys.push_back("naya_area");
    parameters.expect_only(keys);
    settings_ = BaselineSettings::parse(parameters);
    area_mode_ = parameter_choice(parameters, "naya_area", {"MAX", "AT_TMAX"}) == "AT_TMAX"
                     ? NayaArea::kAtPeakLoad
                     : NayaArea::kMaxOverTime;
  }
  std::string name() const override { return "naya"; }
  std::string description() const override {
    return "Adapted Naya (Kaboli eqs. 13-17): peak load, contact area and their change; " +
           settings_.describe();
  }
  std::vector<FeatureColumn> columns(const SkinLayout&) const override { return naya_columns(); }
  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return remove_force_rest_offsets(recording, layout, settings_.contact_mm);
  }
  FeatureResult extract(const SegmentInput& input) const override {
    const BaselineWindow window = baseline_window(input, settings_);
    if (!window.skip_reason.empty()) return FeatureResult::skip(window.skip_reason);
    const NayaDescriptor values =
        naya_descriptor(window.force, settings_.force_threshold, area_mode_);
    return {{values.begin(), values.end()}, {}};
  }

 private:
  BaselineSettings settings_;
  NayaArea area_mode_ = NayaArea::kMaxOverTime;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_naya_extractor(const Parameters& parameters) {
  return std::make_unique<NayaExtractor>(parameters);
}

}  // namespace tactile

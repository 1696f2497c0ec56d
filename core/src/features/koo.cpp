#include "tactile/features/koo.h"

#include <span>

#include "nao_baseline.h"
#include "tactile/stats/statistics.h"

namespace tactile {

Eigen::VectorXd koo_representative_acceleration(const Eigen::MatrixXd& acceleration) {
  const int64_t cells = acceleration.cols() / 3;
  if (cells == 0 || acceleration.rows() == 0) return Eigen::VectorXd();
  Eigen::ArrayXd sum = Eigen::ArrayXd::Zero(acceleration.rows());
  for (int64_t c = 0; c < cells; ++c)
    sum += acceleration.middleCols(3 * c, 3).rowwise().norm().array();
  return (sum / static_cast<double>(cells)).matrix();
}

KooDescriptor koo_descriptor(const Eigen::VectorXd& representative_acceleration,
                             const Eigen::MatrixXd& force, double force_threshold, double rate_hz,
                             ContactChangeMode change_mode) {
  KooDescriptor result{};
  // Kaboli et al. eq. (22): F_total = var(A_rep), population variance.
  result[0] = stats::variance(std::span<const double>(
      representative_acceleration.data(), static_cast<size_t>(representative_acceleration.size())));
  result[1] = contact_time(force, force_threshold, rate_hz);
  // Kaboli et al. eq. (23): CAC = Σ_e Σ_{t>=1} |b_e(t) - b_e(t-1)|, the on/off transitions.
  const int64_t samples = force.rows();
  if (samples >= 2 && force.cols() > 0) {
    const Eigen::ArrayXXd contact = contact_elements(force, force_threshold);
    const Eigen::ArrayXXd change = contact.bottomRows(samples - 1) - contact.topRows(samples - 1);
    result[2] = change_mode == ContactChangeMode::kSigned ? change.sum() : change.abs().sum();
  }
  return result;
}

std::vector<FeatureColumn> koo_columns() {
  return {
      {"acceleration_variance",
       "F_total: variance of the mean acceleration magnitude of the contacted cells (g^2), Kaboli "
       "eq. (22)"},
      {"contact_time", "CT: samples with some element >= f_thresh, divided by fs (s)"},
      {"contact_area_changes", "CAC: on/off transitions of the force elements, Kaboli eq. (23)"}};
}

namespace {

class KooExtractor : public FeatureExtractor {
 public:
  explicit KooExtractor(const Parameters& parameters) {
    std::vector<std::string> keys = BaselineSettings::keys();
    keys.push_back("cac_mode");
    parameters.expect_only(keys);
    settings_ = BaselineSettings::parse(parameters);
    change_mode_ = parameter_choice(parameters, "cac_mode", {"ABSOLUTE", "SIGNED"}) == "SIGNED"
                       ? ContactChangeMode::kSigned
                       : ContactChangeMode::kAbsolute;
  }
  std::string name() const override { return "koo"; }
  std::string description() const override {
    return "Adapted Koo (Kaboli eqs. 22-23): acceleration variance, contact time, contact-area "
           "changes; " +
           settings_.describe();
  }
  std::vector<FeatureColumn> columns(const SkinLayout&) const override { return koo_columns(); }
  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return remove_force_rest_offsets(recording, layout, settings_.contact_mm);
  }
  FeatureResult extract(const SegmentInput& input) const override {
    const BaselineWindow window = baseline_window(input, settings_);
    if (!window.skip_reason.empty()) return FeatureResult::skip(window.skip_reason);
    const Stream& stream = *window.skin.stream;
    const BodyPart& part = window.body_part();
    // C = cells with ζ = 1; contact_window guarantees there is at least one.
    std::vector<int> columns;
    for (size_t c = 0; c < part.cells.size(); ++c)
      if (window.window.contact[c])
        columns.insert(columns.end(), part.cells[c].acceleration.begin(),
                       part.cells[c].acceleration.end());
    const std::string bad =
        find_non_finite(stream, columns, window.window.first, window.window.count);
    if (!bad.empty()) return FeatureResult::skip(bad);
    Eigen::MatrixXd acceleration(window.window.count, static_cast<Eigen::Index>(columns.size()));
    for (size_t k = 0; k < columns.size(); ++k)
      acceleration.col(static_cast<Eigen::Index>(k)) =
          window_column(stream, columns[k], window.window.first, window.window.count);
    const KooDescriptor values =
        koo_descriptor(koo_representative_acceleration(acceleration), window.force,
                       settings_.force_threshold, stream.rate_hz, change_mode_);
    return {{values.begin(), values.end()}, {}};
  }

 private:
  BaselineSettings settings_;
  ContactChangeMode change_mode_ = ContactChangeMode::kAbsolute;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_koo_extractor(const Parameters& parameters) {
  return std::make_unique<KooExtractor>(parameters);
}

}  // namespace tactile

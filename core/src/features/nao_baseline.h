#pragma once
// What the three adapted baselines of Kaboli et al. (Naya, Silvera-Tawil, Koo; spec §1.10-1.13)
// share: force referenced to each sensor's rest, the contact threshold f_thresh, and the force
// elements of the touched body part's window.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/segment/nao_window.h"

namespace tactile {

// Spec §1.10: f_thresh is never given in the paper; 0.05 N is about 1.7 % of the 3 N range.
constexpr double kDefaultForceThreshold = 0.05;

// Parameters every baseline takes: threshold_mm (ζ, eq. 1), f_thresh (N), elements (ALL: every
// force element of the body part, as printed | CONTACT: only cells with ζ = 1).
struct BaselineSettings {
  double contact_mm = kDefaultContactDistanceMm;
  double force_threshold = kDefaultForceThreshold;
  bool contacted_only = false;
  static std::vector<std::string> keys() { return {"threshold_mm", "f_thresh", "elements"}; }
  static BaselineSettings parse(const Parameters& parameters);
  std::string describe() const;
};

// The window and force elements of one segment, or the reason it has none.
struct BaselineWindow {
  NaoSkin skin;
  ContactWindow window;
  Eigen::MatrixXd force;  // T x E, baseline-referenced (after preprocess)
  std::string skip_reason;
  const BodyPart& body_part() const {
    return skin.body_parts[static_cast<size_t>(window.body_part)];
  }
};

BaselineWindow baseline_window(const SegmentInput& input, const BaselineSettings& settings);

}  // namespace tactile

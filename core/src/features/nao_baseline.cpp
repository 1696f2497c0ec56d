#include "nao_baseline.h"

#include <sstream>

namespace tactile {

BaselineSettings BaselineSettings::parse(const Parameters& parameters) {
  BaselineSettings settings;
  settings.contact_mm = positive_parameter(parameters, "threshold_mm", kDefaultContactDistanceMm);
  settings.force_threshold = positive_parameter(parameters, "f_thresh", kDefaultForceThreshold);
  settings.contacted_only =
      parameter_choice(parameters, "elements", {"ALL", "CONTACT"}) == "CONTACT";
  return settings;
}

std::string BaselineSettings::describe() const {
  std::ostringstream text;
  text << "f_thresh = " << force_threshold << " N (fixed), contact distance " << contact_mm
       << " mm, force elements of " << (contacted_only ? "contacted cells" : "every cell")
       << " of the body part, force minus each sensor's rest offset";
  return text.str();
}

BaselineWindow baseline_window(const SegmentInput& input, const BaselineSettings& settings) {
  BaselineWindow result;
  result.skin = locate_nao_skin(input.recording, input.layout);
  const NaoSkin& skin = result.skin;
  result.window = contact_window(skin, input.segment, settings.contact_mm, 1);
  if (!result.window.skip_reason.empty()) {
    result.skip_reason = result.window.skip_reason;
    return result;
  }
  const BodyPart& part = result.body_part();
  std::vector<int> columns;
  for (size_t c = 0; c < part.cells.size(); ++c)
    if (!settings.contacted_only || result.window.contact[c])
      columns.insert(columns.end(), part.cells[c].force.begin(), part.cells[c].force.end());
  result.skip_reason =
      find_non_finite(*skin.stream, columns, result.window.first, result.window.count);
  if (!result.skip_reason.empty()) return result;
  result.force = force_elements(skin, result.window, settings.contacted_only);
  return result;
}

}  // namespace tactile

#include "tactile/labels/suggestions.h"

#include <algorithm>

#include "tactile/labels/agreement.h"

namespace tactile {

size_t drop_rejected(std::vector<Label>& segments, const std::vector<Rejection>& rejections,
                     double iou) {
  const size_t before = segments.size();
  std::erase_if(segments, [&](const Label& segment) {
    return std::any_of(rejections.begin(), rejections.end(), [&](const Rejection& rejection) {
      if (rejection.recording != segment.recording || rejection.method != segment.annotator)
        return false;
      Label rejected;
      rejected.t0 = rejection.t0;
      rejected.t1 = rejection.t1;
      return time_iou(segment, rejected) >= iou;
    });
  });
  return before - segments.size();
}

}  // namespace tactile

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

SegmenterRun segmenter_run(const LabelStore& store, const std::string& recording,
                           const std::string& method, std::vector<Label> segments, bool replace) {
  SegmenterRun run;
  run.annotator = "segmenter:" + method;
  for (Label& segment : segments)
    if (segment.class_name.empty()) segment.class_name = kUnknownClass;
  run.rejected = drop_rejected(segments, store.rejections(recording));
  if (replace) {
    LabelFilter earlier;
    earlier.recording = recording;
    earlier.source = LabelSource::kSegmenter;
    earlier.annotator = run.annotator;
    for (const Label& label : store.list(earlier)) run.edit.remove.push_back(ref_of(label));
    run.replaced = run.edit.remove.size();
  }
  run.edit.add = std::move(segments);
  return run;
}

}  // namespace tactile

#include "tactile/labelstore/label.h"

#include "tactile/error.h"

namespace tactile {

const char* to_string(LabelSource source) {
  switch (source) {
    case LabelSource::kManual:
      return "manual";
    case LabelSource::kSegmenter:
      return "segmenter";
    case LabelSource::kModel:
      return "model";
    case LabelSource::kGroundTruth:
      return "ground-truth";
  }
  return "manual";  // unreachable: every enumerator is handled above
}

LabelSource parse_label_source(const std::string& name) {
  for (LabelSource source : {LabelSource::kManual, LabelSource::kSegmenter, LabelSource::kModel,
                             LabelSource::kGroundTruth}) {
    if (name == to_string(source)) return source;
  }
  throw Error("label source",
              "unknown source '" + name + "' (expected manual, segmenter, model or ground-truth)");
}

}  // namespace tactile

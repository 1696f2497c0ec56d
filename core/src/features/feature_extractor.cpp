#include "tactile/features/feature_extractor.h"

namespace tactile {

Recording FeatureExtractor::preprocess(const Recording& recording, const SkinLayout&) const {
  return recording;
}

std::string FeatureExtractor::layout_note(const SkinLayout&) const { return {}; }

}  // namespace tactile

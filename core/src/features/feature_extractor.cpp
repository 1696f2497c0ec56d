#include "tactile/features/feature_extractor.h"

namespace tactile {

Recording FeatureExtractor::preprocess(const Recording& recording, const SkinLayout&) const {
  return recording;
}

}  // namespace tactile

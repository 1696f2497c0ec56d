#include "tactile/features/feature_extractor.h"

namespace tactile {

Recording FeatureExtractor::preprocess(const Recording& recording, const SkinLayout&) const {
  return recording;
}

FeatureExtractor::Segments FeatureExtractor::extract_segments(
    const Recording& raw, const SkinLayout& layout, const std::vector<Label>& segments,
    const std::function<void(size_t)>& each) const {
  const Recording recording = preprocess(raw, layout);
  Segments extracted;
  extracted.metadata = recording.metadata;
  extracted.results.reserve(segments.size());
  for (const Label& segment : segments) {
    extracted.results.push_back(extract(SegmentInput{recording, layout, segment}));
    if (each) each(extracted.results.size());
  }
  return extracted;
}
std::string FeatureExtractor::layout_note(const SkinLayout&) const { return {}; }

}  // namespace tactile

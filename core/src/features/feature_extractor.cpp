#include "tactile/features/feature_extractor.h"

#include <algorithm>
#include <cmath>

namespace tactile {

Recording FeatureExtractor::preprocess(const Recording& recording, const SkinLayout&) const {
  return recording;
}

std::pair<int64_t, int64_t> sample_range(const Stream& stream, double t0, double t1) {
  const int64_t count = stream.sample_count();
  if (count == 0 || !(t1 > t0)) return {0, 0};
  int64_t first = 0;
  int64_t last = 0;
  if (!stream.timestamps.empty()) {
    first = std::lower_bound(stream.timestamps.begin(), stream.timestamps.end(), t0) -
            stream.timestamps.begin();
    last = std::lower_bound(stream.timestamps.begin(), stream.timestamps.end(), t1) -
           stream.timestamps.begin();
  } else {
    // Sample k covers time start + k / rate; it is inside [t0, t1) when its time is.
    first = static_cast<int64_t>(std::ceil((t0 - stream.start_time) * stream.rate_hz - 1e-9));
    last = static_cast<int64_t>(std::ceil((t1 - stream.start_time) * stream.rate_hz - 1e-9));
  }
  first = std::clamp<int64_t>(first, 0, count);
  last = std::clamp<int64_t>(last, first, count);
  return {first, last};
}

}  // namespace tactile

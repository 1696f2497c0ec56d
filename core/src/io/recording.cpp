#include "tactile/io/recording.h"

#include <algorithm>
#include <cmath>

namespace tactile {

double Stream::duration() const {
  const int64_t count = sample_count();
  if (count == 0) return 0.0;
  if (!timestamps.empty())
    return timestamps.back() - timestamps.front() + (rate_hz > 0 ? 1.0 / rate_hz : 0.0);
  return rate_hz > 0 ? static_cast<double>(count) / rate_hz : 0.0;
}

double Stream::time_of(int64_t index) const {
  if (!timestamps.empty()) return timestamps[static_cast<size_t>(index)];
  return start_time + (rate_hz > 0 ? static_cast<double>(index) / rate_hz : 0.0);
}

int64_t Stream::index_at(double t) const {
  const int64_t count = sample_count();
  if (count == 0) return 0;
  int64_t index = 0;
  if (!timestamps.empty()) {
    auto it = std::upper_bound(timestamps.begin(), timestamps.end(), t);
    index = static_cast<int64_t>(it - timestamps.begin()) - 1;
  } else if (rate_hz > 0) {
    index = static_cast<int64_t>(std::floor((t - start_time) * rate_hz + 1e-9));
  }
  return std::clamp<int64_t>(index, 0, count - 1);
}

const Stream* Recording::find_stream(const std::string& name) const {
  for (const Stream& stream : streams)
    if (stream.name == name) return &stream;
  return nullptr;
}

double Recording::duration() const {
  double longest = 0.0;
  for (const Stream& stream : streams) longest = std::max(longest, stream.duration());
  return longest;
}

}  // namespace tactile

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

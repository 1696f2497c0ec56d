#pragma once
// Recording = streams + layout id + metadata. Stream = one sampled signal set.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tactile {

// Samples as float32, one column per channel; column-major, so each channel is
// contiguous in memory (and matches the on-disk [channels][samples] layout).
using SampleMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor>;

struct Stream {
  std::string name;  // e.g. "skin"
  double rate_hz = 0.0;
  double start_time = 0.0;  // seconds, time of sample 0
  std::vector<std::string> channels;
  std::vector<std::string> units;  // one per channel (may be empty strings)
  SampleMatrix samples;            // rows: samples, columns: channels
  std::vector<double> timestamps;  // empty for regular sampling, else one per sample (s)

  int64_t sample_count() const { return samples.rows(); }
  int64_t channel_count() const { return samples.cols(); }
  double duration() const;  // seconds covered
  double time_of(int64_t index) const;
  // Index of the last sample at or before time t, clamped to [0, count-1].
  int64_t index_at(double t) const;
};

// Well-known metadata keys: subject, session, side, condition, trial; any other
// free key/value pairs may be stored too.
using Metadata = std::map<std::string, std::string>;

// Sample index range [first, last) of a stream covered by [t0, t1), clamped to the stream.
std::pair<int64_t, int64_t> sample_range(const Stream& stream, double t0, double t1);

struct Recording {
  std::string id;         // recording id used by labels (usually the file stem)
  std::string layout_id;  // "nao", "grid:4x4", ...
  Metadata metadata;
  std::vector<Stream> streams;

  const Stream* find_stream(const std::string& name) const;
  double duration() const;  // longest stream
};

}  // namespace tactile

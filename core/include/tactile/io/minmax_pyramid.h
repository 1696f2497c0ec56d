#pragma once
// Min/max pyramid of one channel: per-bucket minima and maxima at bucket sizes
// 16, 256, 4096, ... samples, so a plot can ask for the exact min and max of
// every pixel column at a cost that depends on the number of columns, not on the
// length of the recording.

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace tactile {

// Minimum and maximum of a set of samples. An empty set (no samples, or only NaN)
// is a gap: min = +inf, max = -inf, which is also the identity of merge().
struct MinMax {
  float min = std::numeric_limits<float>::infinity();
  float max = -std::numeric_limits<float>::infinity();

  bool empty() const { return !(min <= max); }
  void add(float value) {
    // NaN fails both comparisons, so it never enters the range.
    if (value < min) min = value;
    if (value > max) max = value;
  }
  void merge(const MinMax& other) {
    if (other.min < min) min = other.min;
    if (other.max > max) max = other.max;
  }
  bool operator==(const MinMax&) const = default;
};

// Reads raw samples [first, first + out.size()) of the channel into `out`.
// May throw tactile::Error (a file that turns out to be truncated, ...).
using RawSampleReader = std::function<void(int64_t first, std::span<float> out)>;

class MinMaxPyramid {
 public:
  // Block size of the coarse overview recordings store on disk.
  static constexpr int64_t kOverviewBlock = 256;

  MinMaxPyramid() = default;

  // Builds every level from samples held in memory. The pyramid does not copy
  // them: `samples` must outlive it (it reads them at column edges and when zoomed in).
  explicit MinMaxPyramid(std::span<const float> samples);

  // Builds from a stored overview of per-block minima and maxima of
  // kOverviewBlock samples (ceil(sample_count / 256) entries; a block of only NaN
  // stores NaN, or +inf/-inf, for both) plus a reader for raw samples, so a long
  // file is never read whole: raw samples are read only at column edges that are
  // not on a block boundary, and in one piece when the view is zoomed in to less
  // than a block per column. Throws tactile::Error naming `where` ("overview block
  // 17") when the overview has the wrong length or a block has min > max or NaN on
  // one side only.
  MinMaxPyramid(int64_t sample_count, std::span<const float> overview_min,
                std::span<const float> overview_max, RawSampleReader reader,
                const std::string& where);

  int64_t sample_count() const { return sample_count_; }

  // Min/max of each column c over samples [edges[c], edges[c + 1]); `out` has
  // edges.size() - 1 entries. Edges must not decrease; samples outside
  // [0, sample_count) do not exist, so a column wholly outside is a gap.
  void query_edges(std::span<const int64_t> edges, std::span<MinMax> out) const;

  // `columns` equal columns over [first, last): column c covers
  // [first + c * (last - first) / columns, first + (c + 1) * (last - first) / columns).
  std::vector<MinMax> query(int64_t first, int64_t last, int columns) const;

  // Min/max of one range [first, last).
  MinMax range(int64_t first, int64_t last) const;

  // Smallest stored bucket size: column edges on multiples of it need no raw samples.
  int64_t finest_bucket() const;
  // Bytes held by the levels (raw samples are not counted: they are not owned).
  int64_t memory_bytes() const;
  // Raw samples read through the reader (or from memory) since construction;
  // lets tests and the plot check that a query stays bounded.
  int64_t raw_samples_read() const { return raw_samples_read_; }

 private:
  struct Level {
    int64_t bucket = 0;           // samples per bucket, a power of two
    int shift = 0;                // log2(bucket)
    std::vector<MinMax> buckets;  // min and max side by side: one cache line, not two
  };

  void add_coarser_levels();
  // Merges raw samples [first, last) (already clipped to the data) into `result`.
  void merge_raw(int64_t first, int64_t last, MinMax& result) const;
  // Exact min/max over [first, last), clipped to the data.
  MinMax range_clipped(int64_t first, int64_t last) const;

  int64_t sample_count_ = 0;
  std::span<const float> samples_;  // in-memory mode
  RawSampleReader reader_;          // overview mode
  std::vector<Level> levels_;       // finest first
  mutable int64_t raw_samples_read_ = 0;
};

}  // namespace tactile

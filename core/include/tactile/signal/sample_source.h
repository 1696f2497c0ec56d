#pragma once
// SampleSource: the one seam every view reads samples through. A view never opens a
// file and never holds a whole Recording: it asks a source for the min/max of pixel
// columns over a time range, the values of all channels at one instant (the skin), or
// a sample range of a few channels (features of a selection).
//
// Three kinds stand behind it: samples in memory (tests, the simulator), a recording
// file read chunk by chunk through a bounded cache, and (live mode) a ring buffer.
// A source may grow while it is read: sample_count() is the number of samples that
// exist now, and every query is answered against the count at the time of the call.
// Calls are safe from several threads; the UI thread and a job may share a source.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/minmax_pyramid.h"
#include "tactile/io/recording.h"

namespace tactile {

// What a source carries, fixed for its life.
struct SourceInfo {
  std::string recording_id;
  std::string layout_id;
  std::string stream;  // stream name, e.g. "skin"
  double rate_hz = 0.0;
  double start_time = 0.0;  // seconds, time of sample 0
  std::vector<std::string> channels;
  std::vector<std::string> units;
  Metadata metadata;
};

class SampleSource {
 public:
  SampleSource() = default;
  virtual ~SampleSource() = default;
  // Sources are shared by pointer; an in-memory one points into its own samples.
  SampleSource(const SampleSource&) = delete;
  SampleSource& operator=(const SampleSource&) = delete;

  virtual const SourceInfo& info() const = 0;
  // Samples that exist now; grows for a live source.
  virtual int64_t sample_count() const = 0;

  // Min/max of channel `channel` over samples [edges[c], edges[c + 1]) into out[c];
  // out has edges.size() - 1 entries, edges do not decrease, samples outside
  // [0, sample_count) are gaps. Throws tactile::Error when the data cannot be read.
  virtual void minmax(int channel, std::span<const int64_t> edges, std::span<MinMax> out) const = 0;
  // Every channel's value at sample `index` (NaN when outside the data).
  virtual std::vector<float> values_at(int64_t index) const = 0;
  // Samples [first, first + count) of the given channels: rows = samples, columns =
  // the channels in the order given. Throws tactile::Error outside the data.
  virtual SampleMatrix read(std::span<const int> channels, int64_t first, int64_t count) const = 0;

  // Samples whose min/max a source answers without reading raw samples: column edges
  // on multiples of it are free. 1 for a source that holds everything in memory.
  virtual int64_t coarse_block() const { return 1; }
  // Bytes the source holds now (caches, pyramids, overview; the samples of an
  // in-memory source are counted too).
  virtual int64_t memory_bytes() const = 0;
  // Time of each sample for an irregularly sampled stream; null when regular.
  virtual const std::vector<double>* timestamps() const { return nullptr; }
  // Places of the data found damaged so far and read as gaps (NaN) instead, each
  // "FILE:PLACE: what"; empty for a source that throws instead (the default).
  virtual std::vector<std::string> damage() const { return {}; }
  // Why the data cannot be read now ("" when it can): a recording file deleted or moved, or on
  // a network share or USB stick that went away. Views show what is cached meanwhile (the
  // rest as gaps); the source reopens the file when it is back.
  virtual std::string unavailable() const { return ""; }

  //---- Helpers over the virtual calls
  int channel_count() const { return static_cast<int>(info().channels.size()); }
  double rate_hz() const { return info().rate_hz; }
  double start_time() const { return info().start_time; }
  double duration() const;  // seconds covered by the samples that exist now
  double end_time() const { return start_time() + duration(); }
  double time_of(int64_t index) const;
  // Index of the last sample at or before t, clamped to [0, sample_count - 1] (0 when empty).
  int64_t index_at(double t) const;
  // Index of the first sample at or after t, clamped to [-1, sample_count + 1] so that
  // edges outside the data stay outside.
  int64_t first_index_at_or_after(double t) const;
  int channel_index(const std::string& name) const;  // -1 when absent

  // `columns` equal time columns over [t0, t1). When a column spans at least half a
  // coarse block, edges snap to the nearest block multiple (an error under a pixel), so a
  // zoomed-out view never reads a raw sample; zoomed in, the samples are read.
  std::vector<MinMax> minmax_over_time(int channel, double t0, double t1, int columns) const;
  // Min/max of a whole channel (from the coarse data: no raw read on a file).
  MinMax channel_extent(int channel) const;
  std::vector<float> values_at_time(double t) const { return values_at(index_at(t)); }
};

// Every sample of the source as a recording of one stream (its info, units, timestamps), read
// in blocks of about a million values; `step(fraction)` is called after each block, so a job
// reports its progress there and ends there when cancelled (the callback throws).
Recording read_all(const SampleSource& source, const std::function<void(double)>& step = {});
// Samples [first, first + count) of every channel, as a recording of the source's stream whose
// sample 0 is the source's sample `first` (its time, or its time stamps). Throws as read().
Recording read_window(const SampleSource& source, int64_t first, int64_t count);

//---- Samples held in memory

class MemorySampleSource final : public SampleSource {
 public:
  // Takes one stream of a recording; the recording's id and layout go into info().
  MemorySampleSource(const Recording& recording, const Stream& stream);
  explicit MemorySampleSource(Stream stream, std::string layout_id = {},
                              std::string recording_id = {});

  const SourceInfo& info() const override { return info_; }
  int64_t sample_count() const override { return stream_.sample_count(); }
  void minmax(int channel, std::span<const int64_t> edges, std::span<MinMax> out) const override;
  std::vector<float> values_at(int64_t index) const override;
  SampleMatrix read(std::span<const int> channels, int64_t first, int64_t count) const override;
  int64_t memory_bytes() const override;
  const std::vector<double>* timestamps() const override {
    return stream_.timestamps.empty() ? nullptr : &stream_.timestamps;
  }

  const Stream& stream() const { return stream_; }

 private:
  void build_pyramids();

  SourceInfo info_;
  Stream stream_;
  std::vector<MinMaxPyramid> pyramids_;  // one per channel, over stream_'s columns
};

//---- A recording file, read on demand

struct FileSourceOptions {
  std::string stream;                       // "" = the first stream
  int64_t cache_bytes = int64_t{32} << 20;  // raw-sample chunk cache limit
  // A chunk that fails its checksum reads as NaN (a gap, never numbers) and is
  // listed by damage(), instead of throwing: a viewer keeps showing the rest of a
  // damaged file and names the damage.
  bool damaged_chunks_as_gaps = false;
  // A read of the file waits at most this long: a file that stops answering (a hung network
  // share) makes the source unavailable() instead of holding its caller (the UI's frame).
  double read_budget_seconds = 0.5;
  // While unavailable, the file is looked for again at most this often.
  double retry_seconds = 1.0;
  // Called on the reading thread before each read of the file: a fault injected by tests and
  // benchmarks (it may block, or throw tactile::Error as a failing disk would).
  std::function<void()> before_read;
};

class FileSampleSource final : public SampleSource {
 public:
  // Opens the file, reads its attributes and the min/max overview of the stream; no
  // samples are read until asked for. Throws tactile::Error naming file and dataset.
  explicit FileSampleSource(const std::string& path, const FileSourceOptions& options = {});
  ~FileSampleSource() override;

  const SourceInfo& info() const override { return info_; }
  int64_t sample_count() const override { return sample_count_; }
  void minmax(int channel, std::span<const int64_t> edges, std::span<MinMax> out) const override;
  std::vector<float> values_at(int64_t index) const override;
  SampleMatrix read(std::span<const int> channels, int64_t first, int64_t count) const override;
  int64_t coarse_block() const override { return overview_block_; }
  int64_t memory_bytes() const override;
  const std::vector<double>* timestamps() const override {
    return timestamps_.empty() ? nullptr : &timestamps_;
  }

  // The streams the file holds, to offer a choice.
  const std::vector<std::string>& stream_names() const { return stream_names_; }
  int64_t cache_limit_bytes() const { return cache_limit_; }
  int64_t chunk_samples() const { return chunk_samples_; }
  // Chunks read from the file since opening (cache misses), for tests and benchmarks.
  int64_t chunks_read() const;
  std::vector<std::string> damage() const override;
  std::string unavailable() const override;

 private:
  struct Cache;
  class Reader;
  // Samples [first, first + count) of channels [channel_first, +channels) through the reader:
  // true with `out` filled, false when the file is unavailable (why in unavailable_). Throws
  // tactile::Error when the data is damaged. Caller holds mutex_.
  bool read_file(int channel_first, int channels, int64_t first, int64_t count,
                 SampleMatrix& out) const;
  // Copies samples [first, first + out.size()) of one channel out of the cache,
  // reading missing chunks. Caller holds mutex_.
  void copy_samples(int channel, int64_t first, std::span<float> out) const;
  const MinMaxPyramid& pyramid(int channel) const;  // built on first use; caller holds mutex_

  SourceInfo info_;
  std::vector<std::string> stream_names_;
  int64_t sample_count_ = 0;
  int64_t overview_block_ = 256;
  int64_t chunk_samples_ = 8192;
  int64_t cache_limit_ = 0;
  bool damaged_as_gaps_ = false;
  std::vector<double> timestamps_;
  std::unique_ptr<Cache> cache_;
  std::string path_;
  double read_budget_ = 0.5, retry_seconds_ = 1.0;
  std::function<void()> before_read_;
  std::unique_ptr<Reader> reader_;
  mutable std::string unavailable_;  // guarded by mutex_
  mutable double last_look_ = 0.0;   // steady seconds of the last look for the file
  mutable std::mutex mutex_;
};

// A file-backed source for a path (the workbench's way to open a recording).
std::unique_ptr<SampleSource> open_sample_source(const std::string& path,
                                                 const FileSourceOptions& options = {});

}  // namespace tactile

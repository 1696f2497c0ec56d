// The file-backed SampleSource: attributes and the min/max overview on open, raw
// samples chunk by chunk on demand through a least-recently-used cache of bounded size.
#include <algorithm>
#include <cstring>
#include <limits>
#include <list>
#include <unordered_map>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

namespace {

// Cache unit when the file's samples are not chunked (empty or tiny streams).
constexpr int64_t kDefaultChunk = 8192;
// Chunks the reader keeps at the least, whatever the limit, so one query can finish.
constexpr int64_t kMinimumChunks = 4;

}  // namespace

struct FileSampleSource::Cache {
  struct Entry {
    std::vector<float> samples;
    std::list<uint64_t>::iterator age;  // position in `recent`
  };
  RecordingFile file;
  std::vector<MinMaxPyramid> pyramids;  // from the overview, one per channel
  std::unordered_map<uint64_t, Entry> entries;
  std::list<uint64_t> recent;  // most recently used first
  int64_t bytes = 0;
  int64_t misses = 0;
  std::vector<std::string> damage;  // chunks that failed, read as NaN

  explicit Cache(const std::string& path) : file(path) {}

  static uint64_t key(int channel, int64_t chunk) {
    return (static_cast<uint64_t>(channel) << 40) | static_cast<uint64_t>(chunk);
  }
  const std::vector<float>* find(uint64_t k) {
    const auto found = entries.find(k);
    if (found == entries.end()) return nullptr;
    recent.splice(recent.begin(), recent, found->second.age);
    return &found->second.samples;
  }
  const std::vector<float>& insert(uint64_t k, std::vector<float> samples, int64_t limit) {
    const auto existing = entries.find(k);
    if (existing != entries.end()) {
      // Already held (a chunk row read over channels some of which were cached): replace.
      bytes -= static_cast<int64_t>(existing->second.samples.size() * sizeof(float));
      recent.erase(existing->second.age);
      entries.erase(existing);
    }
    bytes += static_cast<int64_t>(samples.size() * sizeof(float));
    recent.push_front(k);
    Entry& entry = entries[k];
    entry.samples = std::move(samples);
    entry.age = recent.begin();
    while (bytes > limit && static_cast<int64_t>(entries.size()) > kMinimumChunks) {
      const uint64_t oldest = recent.back();
      recent.pop_back();
      const auto found = entries.find(oldest);
      bytes -= static_cast<int64_t>(found->second.samples.size() * sizeof(float));
      entries.erase(found);
    }
    return entry.samples;
  }
};

FileSampleSource::FileSampleSource(const std::string& path, const FileSourceOptions& options)
    : cache_limit_(std::max<int64_t>(options.cache_bytes, 0)),
      damaged_as_gaps_(options.damaged_chunks_as_gaps),
      cache_(std::make_unique<Cache>(path)) {
  const RecordingFile& file = cache_->file;
  if (file.streams().empty()) throw Error(path, "the recording has no stream");
  for (const StreamInfo& stream : file.streams()) stream_names_.push_back(stream.name);
  const StreamInfo& stream =
      options.stream.empty() ? file.streams().front() : file.stream(options.stream);
  info_.recording_id = file.recording_id();
  info_.layout_id = file.layout_id();
  info_.stream = stream.name;
  info_.rate_hz = stream.rate_hz;
  info_.start_time = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
  info_.channels = stream.channels;
  info_.units = stream.units;
  info_.metadata = file.metadata();
  sample_count_ = stream.sample_count;
  overview_block_ = file.overview_block();
  const int64_t stored_chunk = file.chunk_samples(stream.name);
  chunk_samples_ = stored_chunk > 0 ? stored_chunk : kDefaultChunk;
  if (stream.has_timestamps) timestamps_ = file.read_timestamps(stream.name);

  const auto [minima, maxima] = file.read_overview(stream.name);
  const std::string where = path + ":/streams/" + stream.name + "/overview";
  cache_->pyramids.reserve(stream.channels.size());
  for (int channel = 0; channel < channel_count(); ++channel) {
    RawSampleReader reader = [this, channel](int64_t first, std::span<float> out) {
      copy_samples(channel, first, out);
    };
    cache_->pyramids.emplace_back(
        sample_count_,
        std::span<const float>(minima.col(channel).data(), static_cast<size_t>(minima.rows())),
        std::span<const float>(maxima.col(channel).data(), static_cast<size_t>(maxima.rows())),
        std::move(reader), where + " channel " + stream.channels[static_cast<size_t>(channel)]);
  }
}

FileSampleSource::~FileSampleSource() = default;

void FileSampleSource::copy_samples(int channel, int64_t first, std::span<float> out) const {
  Cache& cache = *cache_;
  int64_t done = 0;
  const auto total = static_cast<int64_t>(out.size());
  while (done < total) {
    const int64_t index = first + done;
    const int64_t chunk = index / chunk_samples_;
    const uint64_t k = Cache::key(channel, chunk);
    const std::vector<float>* samples = cache.find(k);
    if (!samples) {
      const int64_t chunk_first = chunk * chunk_samples_;
      const int64_t chunk_count = std::min(chunk_samples_, sample_count_ - chunk_first);
      ++cache.misses;
      std::vector<float> read;
      try {
        read = cache.file.read_channel(info_.stream, channel, chunk_first, chunk_count);
      } catch (const Error& error) {
        if (!damaged_as_gaps_) throw;
        // Kept as a gap in the cache, so a damaged chunk is read (and named) once.
        read.assign(static_cast<size_t>(chunk_count), std::numeric_limits<float>::quiet_NaN());
        cache.damage.push_back(std::string(error.what()) + " (channel " +
                               info_.channels[static_cast<size_t>(channel)] + ", samples " +
                               std::to_string(chunk_first) + " to " +
                               std::to_string(chunk_first + chunk_count) + ")");
      }
      samples = &cache.insert(k, std::move(read), cache_limit_);
    }
    const int64_t offset = index - chunk * chunk_samples_;
    const int64_t n = std::min(total - done, static_cast<int64_t>(samples->size()) - offset);
    std::memcpy(out.data() + done, samples->data() + offset, static_cast<size_t>(n) * sizeof(float));
    done += n;
  }
}

void FileSampleSource::minmax(int channel, std::span<const int64_t> edges,
                              std::span<MinMax> out) const {
  if (channel < 0 || channel >= channel_count())
    throw Error(cache_->file.path(), "no channel " + std::to_string(channel));
  std::lock_guard lock(mutex_);
  cache_->pyramids[static_cast<size_t>(channel)].query_edges(edges, out);
}

std::vector<float> FileSampleSource::values_at(int64_t index) const {
  const int channels = channel_count();
  std::vector<float> values(static_cast<size_t>(channels), std::numeric_limits<float>::quiet_NaN());
  if (index < 0 || index >= sample_count_) return values;
  std::lock_guard lock(mutex_);
  Cache& cache = *cache_;
  const int64_t chunk = index / chunk_samples_;
  const int64_t offset = index - chunk * chunk_samples_;
  int missing = 0;
  for (int channel = 0; channel < channels; ++channel)
    if (!cache.entries.count(Cache::key(channel, chunk))) ++missing;
  if (missing > channels / 2) {
    // One read of the chunk row of every channel instead of one read per channel.
    const int64_t chunk_first = chunk * chunk_samples_;
    const int64_t chunk_count = std::min(chunk_samples_, sample_count_ - chunk_first);
    SampleMatrix block;
    try {
      block = cache.file.read_channels(info_.stream, 0, channels, chunk_first, chunk_count);
    } catch (const Error&) {
      if (!damaged_as_gaps_) throw;
      block.resize(0, 0);  // some chunk is damaged: channel by channel below names it
    }
    if (block.size() == 0) {
      for (int channel = 0; channel < channels; ++channel)
        copy_samples(channel, index, std::span<float>(&values[static_cast<size_t>(channel)], 1));
      return values;
    }
    cache.misses += channels;
    for (int channel = 0; channel < channels; ++channel) {
      const float* column = block.col(channel).data();
      values[static_cast<size_t>(channel)] = column[offset];
      cache.insert(Cache::key(channel, chunk),
                   std::vector<float>(column, column + chunk_count), cache_limit_);
    }
    return values;
  }
  for (int channel = 0; channel < channels; ++channel)
    copy_samples(channel, index, std::span<float>(&values[static_cast<size_t>(channel)], 1));
  return values;
}

SampleMatrix FileSampleSource::read(std::span<const int> channels, int64_t first,
                                    int64_t count) const {
  if (first < 0 || count < 0 || first + count > sample_count_)
    throw Error(cache_->file.path() + ":/streams/" + info_.stream,
                "samples [" + std::to_string(first) + ", " + std::to_string(first + count) +
                    ") outside [0, " + std::to_string(sample_count_) + ")");
  SampleMatrix out(count, static_cast<Eigen::Index>(channels.size()));
  std::lock_guard lock(mutex_);
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] < 0 || channels[k] >= channel_count())
      throw Error(cache_->file.path(), "no channel " + std::to_string(channels[k]));
    copy_samples(channels[k], first,
                 std::span<float>(out.col(static_cast<Eigen::Index>(k)).data(),
                                  static_cast<size_t>(count)));
  }
  return out;
}

int64_t FileSampleSource::memory_bytes() const {
  std::lock_guard lock(mutex_);
  int64_t bytes = cache_->bytes + static_cast<int64_t>(timestamps_.size() * sizeof(double));
  for (const MinMaxPyramid& pyramid : cache_->pyramids) bytes += pyramid.memory_bytes();
  return bytes;
}

std::vector<std::string> FileSampleSource::damage() const {
  std::lock_guard lock(mutex_);
  return cache_->damage;
}

int64_t FileSampleSource::chunks_read() const {
  std::lock_guard lock(mutex_);
  return cache_->misses;
}

std::unique_ptr<SampleSource> open_sample_source(const std::string& path,
                                                 const FileSourceOptions& options) {
  return std::make_unique<FileSampleSource>(path, options);
}

}  // namespace tactile

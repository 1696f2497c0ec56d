// The file-backed SampleSource: attributes and the min/max overview on open, raw
// samples chunk by chunk on demand through a least-recently-used cache of bounded size.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <limits>
#include <list>
#include <optional>
#include <thread>
#include <unordered_map>
#include <utility>

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
  std::vector<MinMaxPyramid> pyramids;  // from the overview, one per channel
  std::unordered_map<uint64_t, Entry> entries;
  std::list<uint64_t> recent;  // most recently used first
  int64_t bytes = 0;
  int64_t misses = 0;
  std::vector<std::string> damage;  // chunks that failed, read as NaN

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

// The file's reads on a thread of their own. A caller waits for its read at most a budget; a
// read that takes longer (a hung network share) is left to finish alone, and until it does
// every caller is told at once that the reader is busy. The thread and the file it reads are
// shared with the source, so a source closed meanwhile never waits for a read that hangs.
class FileSampleSource::Reader {
 public:
  using Job = std::function<SampleMatrix(std::optional<RecordingFile>&)>;
  enum class Outcome { kDone, kFailed, kBusy };

  Reader(RecordingFile file, std::function<void()> before_read)
      : state_(std::make_shared<State>()) {
    state_->file.emplace(std::move(file));
    state_->before_read = std::move(before_read);
    thread_ = std::thread([state = state_] { run(*state); });
  }
  ~Reader() {
    bool busy;
    {
      std::lock_guard lock(state_->mutex);
      state_->stop = true;
      busy = state_->busy;
    }
    state_->wake.notify_all();
    // A read that hangs keeps its thread; it ends by itself when the read does.
    if (busy)
      thread_.detach();
    else
      thread_.join();
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  // Runs `job` on the reader's thread, waiting up to `budget` seconds: kDone with `result`,
  // kFailed with `failure` (what the read threw), or kBusy (the reader is still on a read).
  Outcome run(Job job, double budget, SampleMatrix& result, std::exception_ptr& failure) {
    std::unique_lock lock(state_->mutex);
    if (state_->busy) return Outcome::kBusy;
    state_->job = std::move(job);
    state_->busy = true;
    const uint64_t ticket = ++state_->posted;
    state_->wake.notify_all();
    if (!state_->done.wait_for(lock, std::chrono::duration<double>(budget),
                               [&] { return state_->finished >= ticket; }))
      return Outcome::kBusy;
    if (state_->failure) {
      failure = std::exchange(state_->failure, nullptr);
      return Outcome::kFailed;
    }
    result = std::move(state_->result);
    return Outcome::kDone;
  }

 private:
  struct State {
    std::mutex mutex;
    std::condition_variable wake, done;
    std::optional<RecordingFile> file;  // touched by the reader's thread only
    std::function<void()> before_read;
    Job job;
    bool busy = false, stop = false;
    uint64_t posted = 0, finished = 0;
    SampleMatrix result;
    std::exception_ptr failure;
  };

  static void run(State& state) {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(state.mutex);
        state.wake.wait(lock, [&] { return state.stop || state.job; });
        if (!state.job) return;
        job = std::move(state.job);
        state.job = nullptr;
      }
      SampleMatrix result;
      std::exception_ptr failure;
      try {
        if (state.before_read) state.before_read();
        result = job(state.file);
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard lock(state.mutex);
      state.result = std::move(result);
      state.failure = failure;
      state.busy = false;
      ++state.finished;
      state.done.notify_all();
      if (state.stop) return;
    }
  }

  std::shared_ptr<State> state_;
  std::thread thread_;
};

namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A read that failed because the file or its disk went away, not because its bytes are
// damaged: the file driver's failed read, or the file no longer there. Told by the message
// alone: a look at the path from here could hang on the disk that went away.
bool lost_file(const std::string& error) {
  return error.find("cannot read the file") != std::string::npos ||
         error.find("no such file") != std::string::npos;
}

}  // namespace

FileSampleSource::FileSampleSource(const std::string& path, const FileSourceOptions& options)
    : cache_limit_(std::max<int64_t>(options.cache_bytes, 0)),
      damaged_as_gaps_(options.damaged_chunks_as_gaps),
      cache_(std::make_unique<Cache>()),
      path_(path),
      read_budget_(options.read_budget_seconds > 0.0 ? options.read_budget_seconds : 0.5),
      retry_seconds_(std::max(0.0, options.retry_seconds)) {
  RecordingFile opened(path);
  const RecordingFile& file = opened;
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
  reader_ = std::make_unique<Reader>(std::move(opened), options.before_read);
}

bool FileSampleSource::read_file(int channel_first, int channels, int64_t first, int64_t count,
                                 SampleMatrix& out) const {
  const double now = steady_seconds();
  std::exception_ptr failure;
  if (!unavailable_.empty()) {
    if (now - last_look_ < retry_seconds_) return false;
    last_look_ = now;
    // Look for the file again, on the reader's thread (the look may hang as a read would).
    SampleMatrix found;
    const Reader::Outcome outcome = reader_->run(
        [path = path_, stream = info_.stream](std::optional<RecordingFile>& file) {
          file.reset();
          file.emplace(path);
          SampleMatrix samples(1, 1);
          samples(0, 0) = static_cast<float>(file->stream(stream).sample_count);
          return samples;
        },
        read_budget_, found, failure);
    if (outcome != Reader::Outcome::kDone) return false;
    if (static_cast<int64_t>(found(0, 0)) < sample_count_) {
      unavailable_ =
          path_ + " is back but shorter than it was: open it again to see what it holds now";
      return false;
    }
    unavailable_.clear();
  }
  const Reader::Outcome outcome = reader_->run(
      [stream = info_.stream, channel_first, channels, first,
       count](std::optional<RecordingFile>& file) {
        if (!file) throw Error("", "cannot read the file: it is not open");
        return file->read_channels(stream, channel_first, channels, first, count);
      },
      read_budget_, out, failure);
  if (outcome == Reader::Outcome::kDone) return true;
  last_look_ = now;
  if (outcome == Reader::Outcome::kBusy) {
    unavailable_ = path_ +
                   " does not answer (a network share or a USB stick gone?): showing what is "
                   "cached; it reopens when it answers";
    return false;
  }
  std::string error;
  try {
    std::rethrow_exception(failure);
  } catch (const Error& damage) {
    error = damage.message();
    if (!lost_file(error)) throw;  // damaged bytes: the caller decides (a gap, or an error)
  } catch (const std::exception& other) {
    error = other.what();
  }
  unavailable_ = path_ + " cannot be read now (" + error +
                 "): showing what is cached; it reopens when it is back";
  return false;
}

std::string FileSampleSource::unavailable() const {
  std::lock_guard lock(mutex_);
  if (!unavailable_.empty() && steady_seconds() - last_look_ >= retry_seconds_) {
    // Nothing may ask for raw samples while the file is away (the overview is in memory):
    // the look for it again happens here too.
    SampleMatrix probe;
    read_file(0, 0, 0, 0, probe);
  }
  return unavailable_;
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
        SampleMatrix block;
        if (!read_file(channel, 1, chunk_first, chunk_count, block)) {
          // The file is away: a gap for now, not kept, so it is read once the file is back.
          const int64_t offset = index - chunk_first;
          const int64_t n = std::min(total - done, chunk_count - offset);
          std::fill_n(out.data() + done, n, std::numeric_limits<float>::quiet_NaN());
          done += n;
          continue;
        }
        read.assign(block.data(), block.data() + block.size());
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
    std::memcpy(out.data() + done, samples->data() + offset,
                static_cast<size_t>(n) * sizeof(float));
    done += n;
  }
}

void FileSampleSource::minmax(int channel, std::span<const int64_t> edges,
                              std::span<MinMax> out) const {
  if (channel < 0 || channel >= channel_count())
    throw Error(path_, "no channel " + std::to_string(channel));
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
      if (!read_file(0, channels, chunk_first, chunk_count, block)) return values;  // away: gaps
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
      cache.insert(Cache::key(channel, chunk), std::vector<float>(column, column + chunk_count),
                   cache_limit_);
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
    throw Error(path_ + ":/streams/" + info_.stream,
                "samples [" + std::to_string(first) + ", " + std::to_string(first + count) +
                    ") outside [0, " + std::to_string(sample_count_) + ")");
  SampleMatrix out(count, static_cast<Eigen::Index>(channels.size()));
  std::lock_guard lock(mutex_);
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] < 0 || channels[k] >= channel_count())
      throw Error(path_, "no channel " + std::to_string(channels[k]));
    copy_samples(
        channels[k], first,
        std::span<float>(out.col(static_cast<Eigen::Index>(k)).data(), static_cast<size_t>(count)));
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

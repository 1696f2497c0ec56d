#include "tactile/live/live_recorder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

// What must stay free for a clean close: the next flushes (a chunk being filled is written
// again at each) and the file's closing metadata.
constexpr int64_t kClosingBytes = int64_t{256} << 10;
constexpr int kReserveFlushes = 3;

}  // namespace

LiveRecorder::LiveRecorder(const std::string& path, const LiveSampleSource& source,
                           const LiveRecorderOptions& options)
    : path_(path),
      lag_seconds_(std::max(0.0, options.lag_seconds)),
      warn_minutes_(options.warn_minutes),
      room_probe_(options.room),
      clock_(options.clock ? options.clock : [] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
      }) {
  if (!(options.pretrigger_seconds >= 0.0) || !std::isfinite(options.pretrigger_seconds))
    throw Error("pre-trigger", "must be a number of seconds, 0 or more");
  recording_id_ = std::filesystem::path(path).stem().string();
  const SourceInfo& info = source.info();
  const int64_t count = source.sample_count();
  first_ = std::max(
      source.first_kept(),
      count - static_cast<int64_t>(std::llround(options.pretrigger_seconds * info.rate_hz)));
  first_ = std::max<int64_t>(first_, 0);
  next_ = first_;
  start_time_ = count > 0 ? source.time_of(first_) : source.start_time();
  if (room_probe_) {
    const int64_t free = room_probe_(path);
    if (free >= 0 && free < 2 * kClosingBytes)
      throw Error(path, "only " + byte_text(free) + " left on its disk: too little to record");
  }
  RecordingWriterOptions writer_options;
  writer_options.flush_seconds = options.flush_seconds;
  Metadata metadata = options.metadata;
  metadata["source"] = metadata.count("source") ? metadata["source"] : "live";
  writer_ = std::make_unique<RecordingWriter>(
      path, recording_id_, info.layout_id, metadata, info.stream.empty() ? "skin" : info.stream,
      info.rate_hz, start_time_, info.channels, info.units, writer_options);
  writer_rate_ = info.rate_hz;
  thread_ = std::thread([this] { run(); });
}

LiveRecorder::~LiveRecorder() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  try {
    if (writer_) writer_->finish();
  } catch (const std::exception&) {
    // finish(source) is where errors are reported.
  }
}

void LiveRecorder::take(const LiveSampleSource& source) {
  if (finished_ || stopped()) return;
  const int64_t lag = static_cast<int64_t>(std::llround(lag_seconds_ * source.rate_hz()));
  const int64_t until = source.sample_count() - lag;
  if (until <= next_) return;
  const int64_t kept = source.first_kept();
  SampleMatrix rows(until - next_, source.channel_count());
  rows.setConstant(std::numeric_limits<float>::quiet_NaN());
  // Samples that left the buffer untaken (the UI stalled longer than the buffer) are gaps.
  const int64_t from = std::max(next_, kept);
  if (until > from) rows.bottomRows(until - from) = source.read_all_channels(from, until - from);
  next_ = until;
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(rows));
  }
  wake_.notify_one();
}

void LiveRecorder::finish(const LiveSampleSource& source) {
  if (finished_) return;
  lag_seconds_ = 0.0;
  take(source);
  finished_ = true;
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  std::string failure = error();
  if (failure.empty()) {
    try {
      writer_->finish();
    } catch (const std::exception& error) {
      failure = error.what();
    }
  }
  if (!failure.empty()) throw Error(path_, failure);
}

int64_t LiveRecorder::samples_on_disk() const {
  std::lock_guard lock(mutex_);
  return on_disk_;
}

std::string LiveRecorder::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

RecorderRoom LiveRecorder::room() const {
  std::lock_guard lock(mutex_);
  return room_;
}

bool LiveRecorder::stopped() const {
  std::lock_guard lock(mutex_);
  return !room_.stopped.empty();
}

void LiveRecorder::check_room() {
  const int64_t bytes = writer_->file_bytes();
  const double now = clock_();
  const int64_t free = room_probe_ ? room_probe_(path_) : -1;
  RecorderRoom room = this->room();
  room.free_bytes = free;
  if (measured_seconds_ >= 0.0 && now > measured_seconds_ && bytes > measured_bytes_) {
    // The file's growth per second of the wall clock (a source replayed at 4x fills the disk
    // four times as fast) and per flush (what the next one will take), smoothed; the first
    // interval carries the file's own structure, a fair start, smoothed away after.
    const double per_second =
        static_cast<double>(bytes - measured_bytes_) / (now - measured_seconds_);
    const double per_flush = static_cast<double>(bytes - measured_bytes_);
    room.bytes_per_second =
        room.bytes_per_second > 0.0 ? 0.7 * room.bytes_per_second + 0.3 * per_second : per_second;
    bytes_per_flush_ =
        bytes_per_flush_ > 0.0 ? 0.7 * bytes_per_flush_ + 0.3 * per_flush : per_flush;
  }
  measured_bytes_ = bytes;
  measured_seconds_ = now;
  if (free < 0 || !(room.bytes_per_second > 0.0)) {
    std::lock_guard lock(mutex_);
    room_ = room;
    return;
  }
  const double reserve = kReserveFlushes * bytes_per_flush_ + static_cast<double>(kClosingBytes);
  room.minutes_left =
      std::max(0.0, (static_cast<double>(free) - reserve) / room.bytes_per_second / 60.0);
  room.low = room.minutes_left < warn_minutes_;
  if (static_cast<double>(free) < reserve) {
    std::string failure;
    try {
      writer_->finish();
    } catch (const std::exception& error) {
      failure = error.what();
    }
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.1f",
                  static_cast<double>(writer_->samples_on_disk()) / writer_rate_);
    room.stopped = "stopped recording: " + byte_text(free) + " left on the disk of " + path_ +
                   ", too little for more at " +
                   byte_text(static_cast<int64_t>(room.bytes_per_second)) +
                   "/s; the file is closed whole with " + seconds + " s";
    std::lock_guard lock(mutex_);
    room_ = room;
    if (!failure.empty()) error_ = failure;
    queue_.clear();
    return;
  }
  std::lock_guard lock(mutex_);
  room_ = room;
}

void LiveRecorder::run() {
  for (;;) {
    SampleMatrix rows;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return closing_ || !queue_.empty(); });
      if (queue_.empty()) return;  // closing, all written
      rows = std::move(queue_.front());
      queue_.pop_front();
    }
    try {
      const int64_t before = writer_->samples_on_disk();
      writer_->append(rows);
      const int64_t after = writer_->samples_on_disk();
      {
        std::lock_guard lock(mutex_);
        on_disk_ = after;
      }
      if (after != before) check_room();
      if (stopped()) return;
    } catch (const std::exception& failure) {
      std::lock_guard lock(mutex_);
      error_ = failure.what();
      queue_.clear();
      return;
    }
  }
}

//---- Contact

ContactDetector::ContactDetector(int channels, double rate_hz,
                                 const ContactDetectorOptions& options)
    : channels_(channels), rate_(rate_hz), options_(options) {
  if (channels < 1 || !(rate_hz > 0.0))
    throw Error("contact detector", "needs channels and a rate");
  learning_.resize(static_cast<size_t>(channels));
}

ContactDetector::State ContactDetector::add(std::span<const float> values) {
  began_ = false;
  if (state_ == State::kLearning) {
    for (int channel = 0; channel < channels_; ++channel)
      if (std::isfinite(values[static_cast<size_t>(channel)]))
        learning_[static_cast<size_t>(channel)].push_back(values[static_cast<size_t>(channel)]);
    if (++learnt_ < std::max<int64_t>(2, std::llround(options_.learn_seconds * rate_)))
      return state_;
    rest_.resize(static_cast<size_t>(channels_));
    band_.resize(static_cast<size_t>(channels_));
    for (int channel = 0; channel < channels_; ++channel) {
      std::vector<float>& seen = learning_[static_cast<size_t>(channel)];
      if (seen.empty()) seen.push_back(0.0f);
      const float median = stats::median(seen);
      for (float& value : seen) value = std::fabs(value - median);
      // 1.4826 MAD estimates a normal deviation; a channel that never moved still needs a band.
      const float sigma =
          std::max(1.4826f * stats::median(std::move(seen)), 1e-6f + 1e-3f * std::fabs(median));
      rest_[static_cast<size_t>(channel)] = median;
      band_[static_cast<size_t>(channel)] = static_cast<float>(options_.noise_sigmas) * sigma;
    }
    learning_.clear();
    state_ = State::kQuiet;
    quiet_samples_ = std::numeric_limits<int32_t>::max();
    return state_;
  }
  int beyond = 0;
  for (int channel = 0; channel < channels_; ++channel) {
    const float value = values[static_cast<size_t>(channel)];
    if (std::isfinite(value) && std::fabs(value - rest_[static_cast<size_t>(channel)]) >
                                    band_[static_cast<size_t>(channel)])
      ++beyond;
  }
  if (beyond >= options_.min_channels) {
    began_ = state_ != State::kContact;
    state_ = State::kContact;
    quiet_samples_ = 0;
  } else {
    ++quiet_samples_;
    state_ = State::kQuiet;
  }
  return state_;
}

bool ContactDetector::quiet_for_long() const {
  return state_ == State::kQuiet &&
         quiet_samples_ >= static_cast<int64_t>(std::llround(options_.quiet_seconds * rate_));
}

}  // namespace tactile

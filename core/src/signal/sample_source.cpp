// SampleSource helpers and the in-memory source.
#include "tactile/signal/sample_source.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tactile/error.h"

namespace tactile {

//---- Time and index

double SampleSource::duration() const {
  const int64_t count = sample_count();
  if (count == 0) return 0.0;
  if (const std::vector<double>* times = timestamps()) {
    const int64_t last = std::min<int64_t>(count, static_cast<int64_t>(times->size())) - 1;
    return (*times)[static_cast<size_t>(last)] - times->front() +
           (rate_hz() > 0 ? 1.0 / rate_hz() : 0.0);
  }
  return rate_hz() > 0 ? static_cast<double>(count) / rate_hz() : 0.0;
}

double SampleSource::time_of(int64_t index) const {
  if (const std::vector<double>* times = timestamps()) {
    if (times->empty()) return start_time();
    const auto last = static_cast<int64_t>(times->size()) - 1;
    return (*times)[static_cast<size_t>(std::clamp<int64_t>(index, 0, last))];
  }
  return rate_hz() > 0 ? start_time() + static_cast<double>(index) / rate_hz() : start_time();
}

int64_t SampleSource::index_at(double t) const {
  const int64_t count = sample_count();
  if (count == 0 || !std::isfinite(t)) return 0;
  if (const std::vector<double>* times = timestamps()) {
    const auto end = times->begin() + std::min<int64_t>(count, static_cast<int64_t>(times->size()));
    const auto after = std::upper_bound(times->begin(), end, t);
    return std::clamp<int64_t>((after - times->begin()) - 1, 0, count - 1);
  }
  if (!(rate_hz() > 0)) return 0;
  const double position = std::floor((t - start_time()) * rate_hz() + 1e-9);
  return static_cast<int64_t>(std::clamp(position, 0.0, static_cast<double>(count - 1)));
}

int64_t SampleSource::first_index_at_or_after(double t) const {
  const int64_t count = sample_count();
  if (std::isnan(t)) return 0;
  if (const std::vector<double>* times = timestamps()) {
    const auto end = times->begin() + std::min<int64_t>(count, static_cast<int64_t>(times->size()));
    if (t < (times->empty() ? 0.0 : times->front())) return -1;
    return std::lower_bound(times->begin(), end, t) - times->begin();
  }
  if (!(rate_hz() > 0)) return 0;
  const double position = std::ceil((t - start_time()) * rate_hz() - 1e-9);
  return static_cast<int64_t>(std::clamp(position, -1.0, static_cast<double>(count) + 1.0));
}

int SampleSource::channel_index(const std::string& name) const {
  const auto& names = info().channels;
  const auto found = std::find(names.begin(), names.end(), name);
  return found == names.end() ? -1 : static_cast<int>(found - names.begin());
}

std::vector<MinMax> SampleSource::minmax_over_time(int channel, double t0, double t1,
                                                   int columns) const {
  std::vector<MinMax> out(static_cast<size_t>(std::max(columns, 0)));
  if (columns <= 0 || !(t1 > t0)) return out;
  const double column_time = (t1 - t0) / columns;
  const double samples_per_column = rate_hz() > 0 ? column_time * rate_hz() : 0.0;
  const int64_t block = std::max<int64_t>(1, coarse_block());
  // Edges go to the nearest block boundary, half a block at most: under one column while a
  // column spans half a block or more. Below that a column's edges read raw samples, so the
  // raw reads stay within what half a block per column covers, whatever the recording's
  // length (an hour at 105 Hz across 1600 columns was every chunk of every plotted channel).
  const bool snap = block > 1 && 2.0 * samples_per_column >= static_cast<double>(block);
  const int64_t count = sample_count();
  std::vector<int64_t> edges(static_cast<size_t>(columns) + 1), exact(edges.size());
  for (int column = 0; column <= columns; ++column) {
    const int64_t edge = first_index_at_or_after(t0 + column * column_time);
    exact[static_cast<size_t>(column)] = edge;
    // The end of the data stays where it is: the overview covers its partial block.
    edges[static_cast<size_t>(column)] = snap && edge > 0 && edge < count
                                             ? std::min(count, (edge + block / 2) / block * block)
                                             : edge;
  }
  minmax(channel, edges, out);
  // A column narrower than a block whose two edges snapped to one boundary shows the block
  // around its middle, rather than a gap.
  for (int column = 0; snap && column < columns; ++column) {
    const auto at = static_cast<size_t>(column);
    if (edges[at] != edges[at + 1] || exact[at] >= exact[at + 1] || exact[at + 1] <= 0 ||
        exact[at] >= count)
      continue;
    const int64_t middle = std::clamp<int64_t>((exact[at] + exact[at + 1]) / 2, 0, count - 1);
    const int64_t around[2] = {middle / block * block,
                               std::min(count, (middle / block + 1) * block)};
    minmax(channel, around, std::span<MinMax>(&out[at], 1));
  }
  return out;
}

MinMax SampleSource::channel_extent(int channel) const {
  const int64_t count = sample_count();
  MinMax extent;
  if (count == 0) return extent;
  // Edges on coarse blocks, the last at the end: answered from coarse data alone,
  // except for a final partial block which a file's overview also covers.
  const int64_t edges[2] = {0, count};
  minmax(channel, edges, std::span<MinMax>(&extent, 1));
  return extent;
}

//---- In memory

MemorySampleSource::MemorySampleSource(const Recording& recording, const Stream& stream)
    : MemorySampleSource(stream, recording.layout_id, recording.id) {
  info_.metadata = recording.metadata;
}

MemorySampleSource::MemorySampleSource(Stream stream, std::string layout_id,
                                       std::string recording_id)
    : stream_(std::move(stream)) {
  info_.recording_id = std::move(recording_id);
  info_.layout_id = std::move(layout_id);
  info_.stream = stream_.name;
  info_.rate_hz = stream_.rate_hz;
  info_.start_time = stream_.timestamps.empty() ? stream_.start_time : stream_.timestamps.front();
  info_.channels = stream_.channels;
  info_.units = stream_.units;
  if (static_cast<int64_t>(info_.channels.size()) != stream_.channel_count())
    throw Error("stream " + stream_.name, std::to_string(info_.channels.size()) +
                                              " channel names for " +
                                              std::to_string(stream_.channel_count()) + " columns");
  build_pyramids();
}

void MemorySampleSource::build_pyramids() {
  pyramids_.clear();
  pyramids_.reserve(static_cast<size_t>(stream_.channel_count()));
  for (int64_t column = 0; column < stream_.channel_count(); ++column)
    pyramids_.emplace_back(std::span<const float>(stream_.samples.col(column).data(),
                                                  static_cast<size_t>(stream_.sample_count())));
}

void MemorySampleSource::minmax(int channel, std::span<const int64_t> edges,
                                std::span<MinMax> out) const {
  if (channel < 0 || channel >= channel_count())
    throw Error("stream " + info_.stream, "no channel " + std::to_string(channel));
  pyramids_[static_cast<size_t>(channel)].query_edges(edges, out);
}

std::vector<float> MemorySampleSource::values_at(int64_t index) const {
  std::vector<float> values(static_cast<size_t>(channel_count()),
                            std::numeric_limits<float>::quiet_NaN());
  if (index < 0 || index >= sample_count()) return values;
  for (int channel = 0; channel < channel_count(); ++channel)
    values[static_cast<size_t>(channel)] = stream_.samples(index, channel);
  return values;
}

SampleMatrix MemorySampleSource::read(std::span<const int> channels, int64_t first,
                                      int64_t count) const {
  if (first < 0 || count < 0 || first + count > sample_count())
    throw Error("stream " + info_.stream, "samples [" + std::to_string(first) + ", " +
                                              std::to_string(first + count) + ") outside [0, " +
                                              std::to_string(sample_count()) + ")");
  SampleMatrix out(count, static_cast<Eigen::Index>(channels.size()));
  for (size_t k = 0; k < channels.size(); ++k) {
    if (channels[k] < 0 || channels[k] >= channel_count())
      throw Error("stream " + info_.stream, "no channel " + std::to_string(channels[k]));
    out.col(static_cast<Eigen::Index>(k)) = stream_.samples.col(channels[k]).segment(first, count);
  }
  return out;
}

int64_t MemorySampleSource::memory_bytes() const {
  int64_t bytes = static_cast<int64_t>(stream_.samples.size()) * 4 +
                  static_cast<int64_t>(stream_.timestamps.size()) * 8;
  for (const MinMaxPyramid& pyramid : pyramids_) bytes += pyramid.memory_bytes();
  return bytes;
}

namespace {

// A recording of the source's stream holding no samples yet, its sample 0 the source's
// sample `first`.
Recording empty_recording_of(const SampleSource& source, int64_t first) {
  const SourceInfo& info = source.info();
  Recording recording;
  recording.id = info.recording_id;
  recording.layout_id = info.layout_id;
  recording.metadata = info.metadata;
  Stream stream;
  stream.name = info.stream;
  stream.rate_hz = info.rate_hz;
  stream.start_time = first == 0 ? info.start_time : source.time_of(first);
  stream.channels = info.channels;
  stream.units = info.units;
  stream.samples.resize(0, static_cast<Eigen::Index>(info.channels.size()));
  recording.streams = {std::move(stream)};
  return recording;
}

std::vector<int> every_channel(const SampleSource& source) {
  std::vector<int> channels(static_cast<size_t>(source.channel_count()));
  for (size_t k = 0; k < channels.size(); ++k) channels[k] = static_cast<int>(k);
  return channels;
}

}  // namespace

Recording read_all(const SampleSource& source, const std::function<void(double)>& step) {
  Recording recording = empty_recording_of(source, 0);
  Stream& stream = recording.streams.front();
  const int64_t count = source.sample_count();
  const std::vector<int> channels = every_channel(source);
  stream.samples.resize(count, static_cast<Eigen::Index>(channels.size()));
  const int64_t block =
      std::max<int64_t>(1, (int64_t{1} << 20) / std::max<int64_t>(1, channels.size()));
  for (int64_t first = 0; first < count; first += block) {
    const int64_t rows = std::min(block, count - first);
    stream.samples.middleRows(first, rows) = source.read(channels, first, rows);
    if (step) step(static_cast<double>(first + rows) / static_cast<double>(count));
  }
  if (const std::vector<double>* times = source.timestamps())
    stream.timestamps.assign(times->begin(),
                             times->begin() + std::min<int64_t>(count, times->size()));
  return recording;
}

Recording read_window(const SampleSource& source, int64_t first, int64_t count) {
  Recording recording = empty_recording_of(source, first);
  Stream& stream = recording.streams.front();
  if (count > 0) stream.samples = source.read(every_channel(source), first, count);
  if (const std::vector<double>* times = source.timestamps())
    stream.timestamps.assign(times->begin() + first,
                             times->begin() + first + std::max<int64_t>(0, count));
  return recording;
}

}  // namespace tactile

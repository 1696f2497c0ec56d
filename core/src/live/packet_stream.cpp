#include "tactile/live/packet_stream.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "tactile/error.h"

namespace tactile {

//---- Receiving -------------------------------------------------------------------------

namespace {

LiveTimelineOptions collector_timeline(const SkinLayout& layout) {
  device_channels(layout);  // refuses a layout without a packet format now, not per datagram
  const PacketFormatInfo format = packet_format_info(layout.id);
  return {.rate_hz = format.sample_rate_hz, .samples_per_datagram = format.samples_per_datagram};
}

}  // namespace

PacketCollector::PacketCollector(SkinLayout layout, bool keep_samples)
    : layout_(std::move(layout)),
      keep_samples_(keep_samples),
      timeline_(collector_timeline(layout_)) {}

bool PacketCollector::add(std::span<const uint8_t> datagram, double arrival) {
  const PacketFormatInfo format = packet_format_info(layout_.id);
  if (arrival < 0.0) arrival = last_arrival_ + format.samples_per_datagram / format.sample_rate_hz;
  last_arrival_ = std::max(last_arrival_, arrival);
  ++datagrams_;
  bytes_ += static_cast<int64_t>(datagram.size());
  PacketBatch batch;
  try {
    batch = decode_packet(datagram, layout_);
  } catch (const Error& error) {
    ++broken_;
    last_error_ = error.what();
    return false;
  }
  const int64_t rows = batch.samples.rows();
  const LiveTimeline::Placement placement =
      timeline_.place(batch.sequence, batch.time, rows, arrival);
  if (!placement.deliver) return false;
  batch.time = placement.time;
  const double end = batch.time + static_cast<double>(rows) / format.sample_rate_hz;
  if (samples_ == 0) {
    first_time_ = batch.time;
    end_time_ = end;
  } else {
    first_time_ = std::min(first_time_, batch.time);
    end_time_ = std::max(end_time_, end);
  }
  samples_ += rows;
  if (batch.saturated) ++saturated_;
  if (keep_samples_) batches_.push_back(std::move(batch));
  return true;
}

Recording PacketCollector::recording(const std::string& id) const {
  if (!keep_samples_) throw Error("recording " + id, "the collector was told not to keep samples");
  if (batches_.empty()) throw Error("recording " + id, "no datagram arrived");
  std::vector<const PacketBatch*> ordered;
  for (const PacketBatch& batch : batches_) ordered.push_back(&batch);
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const PacketBatch* a, const PacketBatch* b) { return a->time < b->time; });

  const double rate = packet_format_info(layout_.id).sample_rate_hz;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate;
  const std::vector<int>& channels = ordered.front()->channels;
  for (int channel : channels) {
    stream.channels.push_back(layout_.channels[static_cast<size_t>(channel)].name);
    stream.units.push_back(layout_.channels[static_cast<size_t>(channel)].unit);
  }
  stream.samples.resize(samples_, static_cast<Eigen::Index>(channels.size()));
  std::vector<double> times;
  times.reserve(static_cast<size_t>(samples_));
  bool regular = true;
  int64_t row = 0;
  for (const PacketBatch* batch : ordered) {
    // A datagram is contiguous with the one before when it starts one sample period after it
    // ended (half a period of slack for the f64 time stamps).
    if (row > 0 && std::abs(batch->time - (times.back() + 1.0 / rate)) > 0.5 / rate)
      regular = false;
    stream.samples.middleRows(row, batch->samples.rows()) = batch->samples;
    for (int64_t index = 0; index < batch->samples.rows(); ++index)
      times.push_back(batch->time + static_cast<double>(index) / rate);
    row += batch->samples.rows();
  }
  stream.start_time = times.front();
  if (!regular) stream.timestamps = std::move(times);

  Recording recording;
  recording.id = id;
  recording.layout_id = layout_.id;
  recording.metadata["source"] = "udp";
  recording.metadata["datagrams_lost"] = std::to_string(timeline_.sequence().lost());
  recording.streams.push_back(std::move(stream));
  return recording;
}

}  // namespace tactile

#include "tactile/live/live_receiver.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "tactile/error.h"
#include "tactile/live/live_timeline.h"
#include "tactile/live/packets.h"

namespace tactile {

LiveReceiver::LiveReceiver(std::unique_ptr<DatagramInput> input, SkinLayout layout,
                           double ring_seconds)
    : input_(std::move(input)), layout_(std::move(layout)) {
  const PacketFormatInfo format = packet_format_info(layout_.id);
  const std::vector<int> channels = device_channels(layout_);
  info_.layout_id = layout_.id;
  info_.stream = "skin";
  info_.rate_hz = format.sample_rate_hz;
  info_.metadata = input_->metadata();
  for (int channel : channels) {
    info_.channels.push_back(layout_.channels[static_cast<size_t>(channel)].name);
    info_.units.push_back(layout_.channels[static_cast<size_t>(channel)].unit);
  }
  const auto slots = std::max<int64_t>(4096, std::llround(ring_seconds * format.sample_rate_hz));
  ring_ = std::make_unique<SampleRing>(slots, static_cast<int>(channels.size()));
  description_ = input_->describe();
  thread_ = std::thread([this] { run(); });
}

LiveReceiver::~LiveReceiver() { stop(); }

void LiveReceiver::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

LiveCounters LiveReceiver::counters() const {
  std::lock_guard lock(mutex_);
  LiveCounters counters = counters_;
  return counters;
}

std::string LiveReceiver::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

void LiveReceiver::run() {
  const std::chrono::steady_clock::time_point began = std::chrono::steady_clock::now();
  const auto seconds_now = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  };
  const PacketFormatInfo format = packet_format_info(layout_.id);
  LiveTimeline timeline(
      {.rate_hz = format.sample_rate_hz, .samples_per_datagram = format.samples_per_datagram});
  std::vector<uint8_t> datagram;
  std::vector<float> row;
  int64_t refused_count = 0;  // by the decoder; the input counts what its framing threw away
  int64_t replugs = 0;
  const auto count_input = [&] {  // caller holds mutex_
    counters_.broken = refused_count + input_->broken();
    counters_.unplugs = input_->unplugs();
    counters_.replugs = input_->replugs();
    counters_.gone = input_->gone();
    counters_.stalls = timeline.stalls();
    counters_.stalled = timeline.stalled();
  };
  while (!stop_) {
    try {
      const bool arrived = input_->next(datagram, 0.05);
      if (input_->replugs() != replugs) {
        replugs = input_->replugs();
        timeline.reconnected();
      }
      if (!arrived) {
        if (input_->ended()) break;
        timeline.idle(seconds_now());
        std::lock_guard lock(mutex_);
        count_input();
        continue;
      }
    } catch (const std::exception& error) {
      std::lock_guard lock(mutex_);
      failure_ = error.what();
      break;
    }
    const double arrival = seconds_now();
    PacketBatch batch;
    std::string refused;
    try {
      batch = decode_packet(datagram, layout_);
    } catch (const std::exception& error) {
      refused = error.what();
    }
    int64_t pushed = 0, overflow = 0;
    bool delivered = false;
    if (refused.empty()) {
      const LiveTimeline::Placement placement =
          timeline.place(batch.sequence, batch.time, batch.samples.rows(), arrival);
      delivered = placement.deliver;
      if (delivered) {
        row.resize(static_cast<size_t>(batch.samples.cols()));
        for (Eigen::Index sample = 0; sample < batch.samples.rows(); ++sample) {
          for (Eigen::Index column = 0; column < batch.samples.cols(); ++column)
            row[static_cast<size_t>(column)] = batch.samples(sample, column);
          const double time = placement.time + static_cast<double>(sample) / info_.rate_hz;
          if (ring_->push(time, row))
            ++pushed;
          else
            ++overflow;
        }
      }
    }
    std::lock_guard lock(mutex_);
    ++counters_.datagrams;
    counters_.samples += pushed;
    counters_.overflow += overflow;
    const SequenceTracker& tracker = timeline.sequence();
    counters_.lost = tracker.lost();
    counters_.duplicated = tracker.duplicated();
    counters_.reordered = tracker.reordered();
    counters_.restarts = tracker.restarts();
    counters_.clock_jumps = timeline.clock_jumps();
    counters_.late_dropped = timeline.late_dropped();
    if (!refused.empty()) {
      ++refused_count;
      counters_.last_error = refused;
    } else if (batch.saturated && delivered) {
      ++counters_.saturated;
    }
    count_input();
  }
  {
    std::lock_guard lock(mutex_);
    counters_.gone.clear();
  }
  ended_ = true;
}

}  // namespace tactile

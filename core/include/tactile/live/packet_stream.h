#pragma once
// Both ends of a live packet stream, without sockets: PacedSender hands a Stream's datagrams
// to a transmit function at the device's rate (times a factor) on a steady clock;
// PacketCollector decodes what arrives, tracks sequence numbers and rebuilds a Recording.

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/packets.h"

namespace tactile {

//---- Sending ---------------------------------------------------------------------------

struct SendTotals {
  int64_t datagrams = 0;
  int64_t bytes = 0;
  int64_t samples = 0;
  int64_t refused = 0;  // datagrams the transmit function reported as not delivered
};

class PacedSender {
 public:
  // Returns false when the datagram could not be delivered (counted, not an error).
  using Transmit = std::function<bool(std::span<const uint8_t>)>;

  // rate_factor > 0: 2 sends twice as fast as the device would. Throws tactile::Error at
  // "--rate-factor" otherwise.
  PacedSender(Transmit transmit, double rate_factor);

  // Sends samples [first, first + count) of the encoder's stream, one datagram at a time. The
  // datagram holding device time t goes out at start + (t - t0) / rate_factor on the steady
  // clock, where (start, t0) is the first datagram ever sent by this sender: due times are
  // absolute, so a late wake-up never accumulates into drift. Consecutive calls continue the
  // same schedule (streams of later trials carry later device times).
  void send(const PacketEncoder& encoder, const Stream& stream, int64_t first, int64_t count,
            uint32_t& sequence);

  const SendTotals& totals() const { return totals_; }
  // Wall time from the first datagram to the last one sent.
  double elapsed_seconds() const;

 private:
  Transmit transmit_;
  double rate_factor_;
  bool started_ = false;
  std::chrono::steady_clock::time_point start_clock_;
  std::chrono::steady_clock::time_point last_clock_;
  double start_device_time_ = 0.0;
  SendTotals totals_;
};

//---- Receiving -------------------------------------------------------------------------

class PacketCollector {
 public:
  // keep_samples = false counts and checks only (no memory grows with the stream's length).
  PacketCollector(SkinLayout layout, bool keep_samples);

  // Decodes one datagram. Returns false for a broken datagram (counted, its error kept as
  // last_error()) or a duplicate (counted by the tracker); true when its samples were taken.
  bool add(std::span<const uint8_t> datagram);

  const SequenceTracker& sequence() const { return tracker_; }
  int64_t datagrams() const { return datagrams_; }  // everything that arrived
  int64_t bytes() const { return bytes_; }
  int64_t broken() const { return broken_; }
  int64_t samples() const { return samples_; }
  int64_t saturated() const { return saturated_; }  // datagrams flagged as clamped
  const std::string& last_error() const { return last_error_; }
  // Device time of the earliest and one past the latest sample taken (s); 0 when none.
  double first_time() const { return first_time_; }
  double end_time() const { return end_time_; }

  // The samples taken, in device-time order, as one stream "skin" of the layout's device
  // channels. Regular (start_time, no time stamps) when every datagram follows the one
  // before; time stamped per sample when some are missing, so gaps stay visible. Throws
  // tactile::Error when built with keep_samples = false or when nothing arrived.
  Recording recording(const std::string& id) const;

 private:
  SkinLayout layout_;
  bool keep_samples_;
  SequenceTracker tracker_;
  std::vector<PacketBatch> batches_;
  int64_t datagrams_ = 0;
  int64_t bytes_ = 0;
  int64_t broken_ = 0;
  int64_t samples_ = 0;
  int64_t saturated_ = 0;
  std::string last_error_;
  double first_time_ = 0.0;
  double end_time_ = 0.0;
};

}  // namespace tactile

#pragma once
// The receiving end of a live packet stream, without sockets: PacketCollector decodes what
// arrives, places it on the stream's clock (LiveTimeline: sequence numbers, restarts, clock
// jumps, stalls) and rebuilds a Recording. (Datagrams are made and paced by
// the inputs of live_input.h: `sim://`, `replay://`.)

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_timeline.h"
#include "tactile/live/packets.h"

namespace tactile {

//---- Receiving -------------------------------------------------------------------------

class PacketCollector {
 public:
  // keep_samples = false counts and checks only (no memory grows with the stream's length).
  PacketCollector(SkinLayout layout, bool keep_samples);

  // Decodes one datagram that arrived at `arrival` seconds (any steady clock; negative: one
  // datagram period after the last, a sender exactly on time). Returns false for a broken
  // datagram (counted, its error kept as last_error()), a duplicate (counted by the tracker)
  // or a late one whose place is taken; true when its samples were taken.
  bool add(std::span<const uint8_t> datagram, double arrival = -1.0);
  // Nothing arrived by `now` (the clock of add's arrivals): counts a stall once per silence.
  void idle(double now) { timeline_.idle(now); }

  const SequenceTracker& sequence() const { return timeline_.sequence(); }
  const LiveTimeline& timeline() const { return timeline_; }
  int64_t datagrams() const { return datagrams_; }  // everything that arrived
  int64_t bytes() const { return bytes_; }
  int64_t broken() const { return broken_; }
  int64_t samples() const { return samples_; }
  int64_t saturated() const { return saturated_; }  // datagrams flagged as clamped
  const std::string& last_error() const { return last_error_; }
  // Stream time (the sender's device time unless its clock jumped or it restarted) of the
  // earliest and one past the latest sample taken (s); 0 when none.
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
  LiveTimeline timeline_;
  double last_arrival_ = 0.0;
  std::vector<PacketBatch> batches_;  // their time: the stream time LiveTimeline gave them
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

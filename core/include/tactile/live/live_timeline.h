#pragma once
// LiveTimeline: where each received datagram goes on the stream's clock (docs/LIVE.md,
// "Devices that go away"). A sender's own time stamps are trusted only while they agree with
// its sequence numbers and with the receiver's arrival clock:
//
// - within one run of the sender's count (a session) a datagram is placed at its device time
//   plus the session's offset, so lost datagrams leave gaps of their size;
// - a time stamp that disagrees with the sequence numbers (an NTP step, a clock that starts
//   again at 0) is a clock jump: counted, and the datagram is placed where its sequence
//   number puts it; a forward step that the silence before it explains is a real pause and
//   stays a gap;
// - a new session (the count starts over, or a replugged device sends numbers the silence
//   cannot explain) continues after the last placed sample, the silence measured by the
//   arrival clock left as a gap;
// - no data for longer than stall_seconds is a stall, counted once per silence.
//
// Time on the stream never goes backwards and no place is given twice: a late datagram is
// placed only into a hole the datagrams around it left; anything else is dropped
// (late_dropped). No clock is read here: arrival times
// are passed in, so every decision can be tested without waiting.

#include <cstdint>
#include <utility>
#include <vector>

#include "tactile/live/packets.h"

namespace tactile {

struct LiveTimelineOptions {
  double rate_hz = 0.0;          // the device's sample rate
  int samples_per_datagram = 1;  // as the device packs them
  // Silence longer than this is a stall; 0: ten datagram periods, at least 0.25 s.
  double stall_seconds = 0.0;
  // A time stamp this far from where the sequence numbers put it is a clock jump; 0: three
  // datagram periods, at least 0.25 s. Any step back is a jump, however small.
  double jump_seconds = 0.0;
  // A number more than this many seconds of datagrams behind the newest is a restart of the
  // sender's count, not a late datagram (at least 16 datagrams, at most the tracker's window).
  double reorder_seconds = 1.0;
};

class LiveTimeline {
 public:
  // Throws tactile::Error when the rate is not positive or samples_per_datagram < 1.
  explicit LiveTimeline(const LiveTimelineOptions& options);

  struct Placement {
    bool deliver = false;  // false: a duplicate, or a late datagram whose place is taken
    double time = 0.0;     // the stream time of its first sample
  };
  // A decoded datagram: its header's sequence number and device time, its sample count, and
  // when it arrived (seconds on any steady clock, never decreasing).
  Placement place(uint32_t sequence, double device_time, int64_t samples, double arrival);
  // Nothing arrived by `now` (same clock): counts a stall once the silence is long enough.
  void idle(double now);
  // The input lost its device and has it again: the next datagram may start a new session.
  void reconnected() { reconnected_ = true; }

  const SequenceTracker& sequence() const { return tracker_; }
  int64_t restarts() const { return tracker_.restarts(); }
  int64_t stalls() const { return stalls_; }
  int64_t clock_jumps() const { return clock_jumps_; }
  int64_t late_dropped() const { return late_dropped_; }
  bool stalled() const { return stalled_; }  // silent for longer than stall_seconds now
  double stall_seconds() const { return stall_seconds_; }
  double jump_seconds() const { return jump_seconds_; }
  // One past the newest placed sample on the stream's clock (0 before the first).
  double end_time() const { return end_; }

 private:
  double session_start(double arrival) const;

  double rate_;
  int per_datagram_;
  double stall_seconds_;
  double jump_seconds_;
  SequenceTracker tracker_;
  bool started_ = false;
  bool reconnected_ = false;
  bool stalled_ = false;
  double last_arrival_ = 0.0;
  double offset_ = 0.0;         // stream time - device time in this session
  double device_end_ = 0.0;     // device time one past the highest number's samples
  double last_duration_ = 0.0;  // seconds the last placed datagram covered
  double origin_ = 0.0;         // stream time of the first sample: index 0 of the grid
  double end_ = 0.0;            // stream time one past the newest placed sample
  int64_t end_index_ = 0;       // its grid index
  // Grid index ranges [first, end) skipped by in-order datagrams and not yet filled, the
  // newest kHoles: the only places a late datagram may take.
  static constexpr size_t kHoles = 256;
  std::vector<std::pair<int64_t, int64_t>> holes_;
  int64_t stalls_ = 0;
  int64_t clock_jumps_ = 0;
  int64_t late_dropped_ = 0;
};

}  // namespace tactile

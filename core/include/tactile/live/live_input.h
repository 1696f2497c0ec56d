#pragma once
// Where live datagrams come from (docs/LIVE.md): a UDP socket, a serial port carrying the
// same packets back to back, the simulator of a skin, or a recording replayed at 0.25x-4x.
// Each is a DatagramInput; LiveReceiver (live_receiver.h) decodes what any of them delivers.

#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/recording.h"

namespace tactile {

// A parsed live source address:
//   udp://HOST:PORT        HOST a dotted IPv4 address; udp://:PORT listens on loopback only
//   serial:///dev/ttyUSB0?baud=921600  (unplugged, it is reopened every 0.25 s until back)
//   sim://SKIN?seed=1&rate=1&trials=N the skin's simulator, `rate` times the device's speed,
//                                     trial after trial (N trials, then it ends; default endless)
//   replay:///path/file.h5?speed=1&seconds=60   a recording (its first 60 s), 0.25-4 times
//                                               its speed, once
struct LiveAddress {
  std::string scheme;    // "udp", "serial", "sim", "replay"
  std::string host;      // udp
  uint16_t port = 0;     // udp
  std::string path;      // serial device, replay file
  int baud = 921600;     // serial
  std::string skin;      // sim
  uint64_t seed = 1;     // sim
  double speed = 1.0;    // sim (rate factor) and replay
  double seconds = 0.0;  // replay: only this much of the recording (0: all)
  int trials = 0;        // sim: trials before the input ends (0: endless)
  std::string url;       // as given
};

// Throws tactile::Error at `option` (e.g. "--connect") naming what is wrong.
LiveAddress parse_live_address(const std::string& url, const std::string& option);

class DatagramInput {
 public:
  virtual ~DatagramInput() = default;
  // Waits up to `timeout_seconds` for the next datagram and puts its bytes in `out`; false on
  // timeout or when the input has ended (see ended()). Never blocks longer than the timeout,
  // also while its device is gone. Throws tactile::Error when the input fails for good (a
  // socket error); a serial port that goes away is not that: it is waited for (gone()).
  virtual bool next(std::vector<uint8_t>& out, double timeout_seconds) = 0;
  // A device that went away and came back (a serial port unplugged and plugged in again):
  // how often it went, how often it came back, and while it is away what is waited for
  // ("" while it is there). Sockets never go away.
  virtual int64_t unplugs() const { return 0; }
  virtual int64_t replugs() const { return 0; }
  virtual std::string gone() const { return ""; }
  // True once an input with an end (a replay) has delivered everything.
  virtual bool ended() const { return false; }
  // Damaged stretches the input itself threw away (serial framing), counted as broken.
  virtual int64_t broken() const { return 0; }
  // The skin the input sends, when it knows ("" for sockets and ports).
  virtual std::string skin() const { return ""; }
  // What the input knows of the recording it sends (a replayed file's metadata, the
  // simulated device's calibration); empty for sockets and ports.
  virtual Metadata metadata() const { return {}; }
  virtual std::string describe() const = 0;
};

// Opens the input for an address. Sockets and ports are opened here (errors name them).
std::unique_ptr<DatagramInput> open_live_input(const LiveAddress& address);

// Cuts a byte stream (a serial line) back into datagrams: finds the magic, reads the header's
// lengths, and keeps a datagram only when its payload matches the header's CRC-32; anything
// else is skipped byte by byte until the next magic, and each skipped stretch counts as one
// broken datagram. Never holds more than one largest datagram plus what was fed.
class PacketFramer {
 public:
  static constexpr size_t kMaxDatagram = 65536;
  void feed(std::span<const uint8_t> bytes);
  // The next whole datagram, if one is complete.
  bool next(std::vector<uint8_t>& out);
  // Forgets what is buffered (the line was cut: a partial datagram never completes), counted
  // as one broken datagram when there was something.
  void reset();
  int64_t broken() const { return broken_; }
  size_t buffered() const { return buffer_.size() - start_; }

 private:
  void skip(size_t bytes);
  std::vector<uint8_t> buffer_;
  size_t start_ = 0;
  bool skipping_ = false;  // inside a broken stretch
  int64_t broken_ = 0;
};

}  // namespace tactile

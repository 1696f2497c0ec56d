// Live inputs: UDP, serial (termios), the simulator and a replayed recording.
#include "tactile/live/live_input.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <optional>
#include <thread>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/packets.h"
#include "tactile/live/playback.h"
#include "tactile/live/udp.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile {

namespace {

using Clock = std::chrono::steady_clock;

// "a=1&b=2" -> {a: 1, b: 2}; every key must be one of `known`.
std::map<std::string, std::string> query_of(const std::string& query, const std::string& url,
                                            const std::vector<std::string>& known,
                                            const std::string& option) {
  std::map<std::string, std::string> values;
  size_t start = 0;
  while (start < query.size()) {
    size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string pair = query.substr(start, end - start);
    const size_t equals = pair.find('=');
    const std::string key = pair.substr(0, equals);
    if (equals == std::string::npos || std::find(known.begin(), known.end(), key) == known.end()) {
      std::string names;
      for (const std::string& name : known) names += (names.empty() ? "" : ", ") + name;
      throw Error(option, "\"" + pair + "\" in \"" + url + "\" is not KEY=VALUE with KEY one of " +
                              (names.empty() ? "(none)" : names));
    }
    values[key] = pair.substr(equals + 1);
    start = end + 1;
  }
  return values;
}

double number_in(const std::string& text, const std::string& what, const std::string& option) {
  double value = 0.0;
  const auto [end, failure] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || failure != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value))
    throw Error(option, what + " \"" + text + "\" is not a number");
  return value;
}

//---- UDP

class UdpInput final : public DatagramInput {
 public:
  explicit UdpInput(const UdpEndpoint& local)
      : socket_(UdpSocket::bind_to(local)),
        where_(UdpEndpoint{local.host, socket_.local_port()}.url()),
        buffer_(PacketFramer::kMaxDatagram) {}
  bool next(std::vector<uint8_t>& out, double timeout_seconds) override {
    const std::optional<size_t> size = socket_.receive(buffer_, timeout_seconds);
    if (!size) return false;
    // A datagram longer than the buffer is cut; the decoder refuses it by its length.
    out.assign(buffer_.begin(),
               buffer_.begin() + static_cast<std::ptrdiff_t>(std::min(*size, buffer_.size())));
    return true;
  }
  std::string describe() const override { return where_; }

 private:
  UdpSocket socket_;
  std::string where_;
  std::vector<uint8_t> buffer_;
};

//---- Serial

speed_t baud_constant(int baud, const std::string& where) {
  static const std::map<int, speed_t> rates = {
      {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},
      {115200, B115200},   {230400, B230400},   {460800, B460800},   {500000, B500000},
      {576000, B576000},   {921600, B921600},   {1000000, B1000000}, {1152000, B1152000},
      {1500000, B1500000}, {2000000, B2000000}, {3000000, B3000000}, {4000000, B4000000}};
  const auto found = rates.find(baud);
  if (found == rates.end())
    throw Error(where,
                "baud " + std::to_string(baud) + " is not a standard rate (9600 ... 4000000)");
  return found->second;
}

// A serial port that survives being unplugged: when the line fails (a hang-up, EIO, an end
// of file, the device node gone) the port is closed and counted as gone, and the same path
// is opened again every kRetrySeconds (with its baud rate set again) until it is back. A
// path that cannot be opened when the input is made is still an error.
class SerialInput final : public DatagramInput {
 public:
  static constexpr double kRetrySeconds = 0.25;

  SerialInput(const std::string& device, int baud)
      : device_(device), where_("serial://" + device), speed_(baud_constant(baud, where_)) {
    std::string why;
    descriptor_ = open_port(why);
    if (descriptor_ < 0) throw Error(where_, why);
  }
  ~SerialInput() override {
    if (descriptor_ >= 0) ::close(descriptor_);
  }

  bool next(std::vector<uint8_t>& out, double timeout_seconds) override {
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(timeout_seconds));
    uint8_t chunk[4096];
    for (;;) {
      if (descriptor_ >= 0 && framer_.next(out)) return true;
      const Clock::time_point now = Clock::now();
      if (now >= deadline) return false;
      if (descriptor_ < 0) {
        if (now >= retry_at_) reopen();
        if (descriptor_ < 0) {
          std::this_thread::sleep_until(std::min(deadline, retry_at_));
          continue;
        }
      }
      const double left = std::chrono::duration<double>(deadline - now).count();
      pollfd request{descriptor_, POLLIN, 0};
      const int ready = ::poll(&request, 1, static_cast<int>(std::ceil(left * 1000.0)));
      if (ready == 0) return false;
      if (ready < 0) {
        if (errno == EINTR) continue;
        went_away(system_error("cannot wait for bytes"));
        continue;
      }
      if ((request.revents & (POLLHUP | POLLERR | POLLNVAL)) && !(request.revents & POLLIN)) {
        went_away("the port hung up");
        continue;
      }
      const ssize_t size = ::read(descriptor_, chunk, sizeof chunk);
      if (size > 0) {
        framer_.feed(std::span<const uint8_t>(chunk, static_cast<size_t>(size)));
      } else if (size == 0) {
        went_away("the port was closed");
      } else if (errno != EINTR && errno != EAGAIN) {
        went_away(system_error("cannot read"));
      }
    }
  }
  int64_t broken() const override { return framer_.broken(); }
  int64_t unplugs() const override { return unplugs_; }
  int64_t replugs() const override { return replugs_; }
  std::string gone() const override { return gone_; }
  std::string describe() const override { return where_; }

 private:
  // Opens and configures the port; -1 with the reason in `why` when it cannot.
  int open_port(std::string& why) const {
    const int descriptor = ::open(device_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (descriptor < 0) {
      why = system_error("cannot open");
      return -1;
    }
    termios settings{};
    if (::tcgetattr(descriptor, &settings) < 0) {
      why = system_error("not a serial port");
      ::close(descriptor);
      return -1;
    }
    ::cfmakeraw(&settings);  // bytes as they come: no echo, no line editing, 8 bits, no parity
    settings.c_cflag |= CLOCAL | CREAD;
    ::cfsetispeed(&settings, speed_);
    ::cfsetospeed(&settings, speed_);
    if (::tcsetattr(descriptor, TCSANOW, &settings) < 0) {
      why = system_error("cannot set the port to raw mode");
      ::close(descriptor);
      return -1;
    }
    return descriptor;
  }
  void went_away(const std::string& why) {
    ::close(descriptor_);
    descriptor_ = -1;
    framer_.reset();  // a datagram cut by the unplug never completes
    ++unplugs_;
    gone_ = device_ + " (" + why + ")";
    retry_at_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(kRetrySeconds));
  }
  void reopen() {
    std::string why;
    descriptor_ = open_port(why);
    if (descriptor_ >= 0) {
      ++replugs_;
      gone_.clear();
      return;
    }
    gone_ = device_ + " (" + why + ")";
    retry_at_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(kRetrySeconds));
  }

  std::string device_;
  std::string where_;
  speed_t speed_;
  int descriptor_ = -1;
  PacketFramer framer_;
  int64_t unplugs_ = 0;
  int64_t replugs_ = 0;
  std::string gone_;
  Clock::time_point retry_at_;
};

//---- Paced: datagrams made here, handed out when their device time is due

class PacedInput : public DatagramInput {
 public:
  explicit PacedInput(double speed) : speed_(speed) {}

  bool next(std::vector<uint8_t>& out, double timeout_seconds) override {
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(timeout_seconds));
    while (queue_.empty()) {
      if (ended_) return false;
      refill();
    }
    const auto& [device_time, datagram] = queue_.front();
    if (!started_) {
      started_ = true;
      start_clock_ = Clock::now();
      start_device_time_ = device_time;
    }
    const auto due =
        start_clock_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                           (device_time - start_device_time_) / speed_));
    if (due > deadline) {
      std::this_thread::sleep_until(deadline);
      return false;
    }
    std::this_thread::sleep_until(due);
    out = std::move(queue_.front().second);
    queue_.pop_front();
    return true;
  }
  bool ended() const override { return ended_ && queue_.empty(); }

 protected:
  // Appends the next stretch of datagrams with their device times, or sets ended_.
  virtual void refill() = 0;
  void add_stream(const PacketEncoder& encoder, const Stream& stream, int64_t first,
                  int64_t count) {
    const int64_t per_datagram = encoder.format().samples_per_datagram;
    for (int64_t start = first; start < first + count; start += per_datagram) {
      const int64_t rows = std::min(per_datagram, first + count - start);
      for (std::vector<uint8_t>& datagram : encoder.encode(start, rows, sequence_))
        queue_.emplace_back(stream.time_of(start), std::move(datagram));
    }
  }

  std::deque<std::pair<double, std::vector<uint8_t>>> queue_;
  bool ended_ = false;

 private:
  double speed_;
  uint32_t sequence_ = 0;
  bool started_ = false;
  Clock::time_point start_clock_;
  double start_device_time_ = 0.0;
};

// The skin's simulator, trial after trial, device time running on; the next trial is
// simulated while this one is sent.
class SimulatorInput final : public PacedInput {
 public:
  SimulatorInput(const std::string& skin, uint64_t seed, double speed, int trials)
      : PacedInput(speed),
        skin_(skin),
        layout_(load_layout(skin)),
        generator_(skin_record(skin).simulate),
        limit_(trials) {
    packet_format_info(skin);  // refuses a skin without a packet format now
    if (!generator_) throw Error("sim://" + skin, "the skin has no simulator");
    options_.seed = seed;
    options_.subjects = 1;
    // The first trial now: its metadata (the device's calibration) is the stream's.
    first_ = generator_(layout_, options_, 0, 0);
    metadata_ = first_->recording.metadata;
    if (limit_ != 1) next_ = simulate(1);
  }
  std::string skin() const override { return skin_; }
  Metadata metadata() const override { return metadata_; }
  std::string describe() const override { return "sim://" + skin_; }

 protected:
  void refill() override {
    if (limit_ > 0 && trials_ >= limit_) {
      ended_ = true;
      return;
    }
    SimulatedTrial trial;
    if (first_) {
      trial = std::move(*first_);
      first_.reset();
    } else {
      trial = next_.get();
    }
    ++trials_;
    if (limit_ == 0 || trials_ < limit_) next_ = simulate(trials_);
    // The device sends the stream named "skin", or a recording's only stream.
    std::vector<Stream>& streams = trial.recording.streams;
    auto skin = std::find_if(streams.begin(), streams.end(),
                             [](const Stream& stream) { return stream.name == "skin"; });
    if (skin == streams.end() && streams.size() == 1) skin = streams.begin();
    if (skin == streams.end())
      throw Error("sim://" + skin_,
                  "trial " + std::to_string(trials_) + " has no stream named \"skin\"");
    if (skin->sample_count() == 0)
      throw Error("sim://" + skin_, "trial " + std::to_string(trials_) + " has no samples");
    Stream stream = std::move(*skin);
    stream.timestamps.clear();
    stream.start_time = device_time_;
    add_stream(PacketEncoder(layout_, stream), stream, 0, stream.sample_count());
    device_time_ += static_cast<double>(stream.sample_count()) / stream.rate_hz;
  }

 private:
  std::future<SimulatedTrial> simulate(int trial) {
    return std::async(std::launch::async,
                      [this, trial] { return generator_(layout_, options_, 0, trial); });
  }
  std::string skin_;
  SkinLayout layout_;
  TrialGenerator generator_;
  int limit_ = 0;  // trials before the input ends; 0: endless
  SimulationOptions options_;
  std::optional<SimulatedTrial> first_;
  Metadata metadata_;
  std::future<SimulatedTrial> next_;
  int trials_ = 0;
  double device_time_ = 0.0;
};

// A recording, read a second at a time and sent once at `speed` times its rate.
class ReplayInput final : public PacedInput {
 public:
  ReplayInput(const std::string& path, double speed, double seconds)
      : PacedInput(speed), file_(path) {
    layout_ = load_layout(file_.layout_id());
    packet_format_info(file_.layout_id());
    const auto& streams = file_.streams();
    const auto skin = std::find_if(streams.begin(), streams.end(),
                                   [](const StreamInfo& info) { return info.name == "skin"; });
    info_ = skin != streams.end() ? *skin : streams.front();
    if (info_.has_timestamps)
      throw Error(path + ":/streams/" + info_.name,
                  "is irregularly sampled; only a regular stream can be replayed as packets");
    if (seconds > 0.0)
      info_.sample_count =
          std::min<int64_t>(info_.sample_count, std::llround(seconds * info_.rate_hz));
  }
  std::string skin() const override { return file_.layout_id(); }
  Metadata metadata() const override { return file_.metadata(); }
  std::string describe() const override { return "replay://" + file_.path(); }

 protected:
  void refill() override {
    const int64_t count = std::min<int64_t>(std::max<int64_t>(1, std::llround(info_.rate_hz)),
                                            info_.sample_count - position_);
    if (count <= 0) {
      ended_ = true;
      return;
    }
    Stream stream;
    stream.name = info_.name;
    stream.rate_hz = info_.rate_hz;
    stream.start_time = info_.start_time + static_cast<double>(position_) / info_.rate_hz;
    stream.channels = info_.channels;
    stream.units = info_.units;
    stream.samples = file_.read(info_.name, position_, count);
    // A gap in the file (NaN: a datagram never received) is not sent again: each run of
    // whole samples goes out as it was.
    const PacketEncoder encoder(layout_, stream);
    for (int64_t row = 0; row < count;) {
      if (!stream.samples.row(row).allFinite()) {
        ++row;
        continue;
      }
      int64_t end = row;
      while (end < count && stream.samples.row(end).allFinite()) ++end;
      add_stream(encoder, stream, row, end - row);
      row = end;
    }
    position_ += count;
  }

 private:
  RecordingFile file_;
  SkinLayout layout_;
  StreamInfo info_;
  int64_t position_ = 0;
};

}  // namespace

LiveAddress parse_live_address(const std::string& url, const std::string& option) {
  LiveAddress address;
  address.url = url;
  const size_t separator = url.find("://");
  if (separator == std::string::npos)
    throw Error(option,
                "\"" + url +
                    "\" is not a live source: udp://HOST:PORT, serial:///dev/DEVICE?baud=N, "
                    "sim://SKIN or replay:///FILE.h5?speed=X");
  address.scheme = url.substr(0, separator);
  std::string rest = url.substr(separator + 3);
  std::string query;
  if (const size_t mark = rest.find('?'); mark != std::string::npos) {
    query = rest.substr(mark + 1);
    rest = rest.substr(0, mark);
  }
  if (address.scheme == "udp") {
    query_of(query, url, {}, option);
    // Loopback unless an interface is named: a workbench does not listen on the network
    // by accident.
    const std::string host = rest.starts_with(":") ? "127.0.0.1" + rest : rest;
    const UdpEndpoint endpoint = parse_udp_url("udp://" + host, option, UdpUse::kListen);
    address.host = endpoint.host;
    address.port = endpoint.port;
  } else if (address.scheme == "serial") {
    const auto values = query_of(query, url, {"baud"}, option);
    if (rest.empty() || rest.front() != '/')
      throw Error(option, "\"" + url + "\" lacks the device path (serial:///dev/ttyUSB0)");
    address.path = rest;
    if (values.count("baud")) {
      const double baud = number_in(values.at("baud"), "baud", option);
      if (baud != std::floor(baud) || baud < 1 || baud > 1e8)
        throw Error(option,
                    "baud \"" + values.at("baud") + "\" is not a whole number of bits per second");
      address.baud = static_cast<int>(baud);
      baud_constant(address.baud, option);
    }
  } else if (address.scheme == "sim") {
    const auto values = query_of(query, url, {"seed", "rate", "trials"}, option);
    address.skin = rest;
    const SkinRecord* record = find_skin(rest);
    if (!record || !record->simulate || !record->packet) {
      std::vector<std::string> names;
      for (const std::string& skin : simulated_skin_ids())
        if (find_skin(skin)->packet) names.push_back(skin);
      throw Error(option, "\"" + rest + "\" in \"" + url + "\" is not a simulated skin (" +
                              joined(names) + ")");
    }
    if (values.count("seed")) {
      const double seed = number_in(values.at("seed"), "seed", option);
      if (seed < 0 || seed != std::floor(seed))
        throw Error(option, "seed must be a whole number >= 0");
      address.seed = static_cast<uint64_t>(seed);
    }
    if (values.count("rate")) {
      address.speed = number_in(values.at("rate"), "rate", option);
      if (!(address.speed > 0.0) || address.speed > 1000.0)
        throw Error(option, "rate " + values.at("rate") + " is not in (0, 1000]");
    }
    if (values.count("trials")) {
      const double trials = number_in(values.at("trials"), "trials", option);
      if (trials < 1 || trials > 1e6 || trials != std::floor(trials))
        throw Error(option, "trials " + values.at("trials") +
                                " is not a whole number of trials, 1 or more");
      address.trials = static_cast<int>(trials);
    }
  } else if (address.scheme == "replay") {
    const auto values = query_of(query, url, {"speed", "seconds"}, option);
    if (rest.empty())
      throw Error(option, "\"" + url + "\" lacks the recording (replay:///path/file.h5)");
    address.path = rest;
    if (values.count("seconds")) {
      address.seconds = number_in(values.at("seconds"), "seconds", option);
      if (!(address.seconds > 0.0))
        throw Error(option, "seconds " + values.at("seconds") + " is not above 0");
    }
    if (values.count("speed")) {
      address.speed = number_in(values.at("speed"), "speed", option);
      if (address.speed < PlaybackClock::kMinSpeed || address.speed > PlaybackClock::kMaxSpeed)
        throw Error(option, "speed " + values.at("speed") + " is not in 0.25-4");
    }
  } else {
    throw Error(option, "\"" + address.scheme + "\" in \"" + url +
                            "\" is not a live source kind (udp, serial, sim, replay)");
  }
  return address;
}

std::unique_ptr<DatagramInput> open_live_input(const LiveAddress& address) {
  if (address.scheme == "udp")
    return std::make_unique<UdpInput>(UdpEndpoint{address.host, address.port});
  if (address.scheme == "serial") return std::make_unique<SerialInput>(address.path, address.baud);
  if (address.scheme == "sim")
    return std::make_unique<SimulatorInput>(address.skin, address.seed, address.speed,
                                            address.trials);
  if (address.scheme == "replay")
    return std::make_unique<ReplayInput>(address.path, address.speed, address.seconds);
  throw Error(address.url, "not a live source kind (udp, serial, sim, replay)");
}

//---- Framing a byte stream

void PacketFramer::feed(std::span<const uint8_t> bytes) {
  if (start_ > 0 && start_ >= buffer_.size() / 2) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void PacketFramer::reset() {
  if (buffer_.size() > start_ && !skipping_) ++broken_;
  buffer_.clear();
  start_ = 0;
  skipping_ = false;
}

void PacketFramer::skip(size_t bytes) {
  if (!skipping_) ++broken_;
  skipping_ = true;
  start_ += bytes;
}

bool PacketFramer::next(std::vector<uint8_t>& out) {
  for (;;) {
    const size_t available = buffer_.size() - start_;
    const uint8_t* data = buffer_.data() + start_;
    if (available < 4) return false;
    if (std::memcmp(data, kPacketMagic, 4) != 0) {
      // To the next possible magic (or keep the last 3 bytes: a magic may straddle).
      const uint8_t* found = static_cast<const uint8_t*>(memchr(data + 1, 'T', available - 1));
      skip(found ? static_cast<size_t>(found - data) : available - 3);
      continue;
    }
    if (available < static_cast<size_t>(kPacketHeaderSize)) return false;
    const size_t header = data[7];
    uint32_t payload = 0, crc = 0;
    std::memcpy(&payload, data + 24, 4);  // little-endian on the wire and on every host we build on
    std::memcpy(&crc, data + 28, 4);
    if (header < static_cast<size_t>(kPacketHeaderSize) || header + payload > kMaxDatagram) {
      skip(1);
      continue;
    }
    const size_t length = header + payload;
    if (available < length) return false;
    if (crc32(std::span<const uint8_t>(data + header, payload)) != crc) {
      skip(1);  // a false magic inside other bytes, or a damaged datagram
      continue;
    }
    out.assign(data, data + length);
    start_ += length;
    skipping_ = false;
    return true;
  }
}

}  // namespace tactile

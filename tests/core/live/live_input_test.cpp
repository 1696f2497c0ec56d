// Live inputs: addresses refused with their reason, a serial line through a pseudo-terminal
// pair (whole, cut anywhere, with noise between packets), the simulator and a replayed file
// through a LiveReceiver, and UDP loss counted.
#include "tactile/live/live_input.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_receiver.h"
#include "tactile/live/live_source.h"
#include "tactile/live/packets.h"
#include "tactile/live/udp.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

std::string refusal(const std::string& url) {
  try {
    parse_live_address(url, "--connect");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(LiveAddress, ReadsEveryKind) {
  const LiveAddress udp = parse_live_address("udp://:9000", "--connect");
  EXPECT_EQ(udp.host, "127.0.0.1");  // loopback unless an interface is named
  EXPECT_EQ(udp.port, 9000);
  EXPECT_EQ(parse_live_address("udp://0.0.0.0:9001", "--connect").host, "0.0.0.0");
  const LiveAddress serial = parse_live_address("serial:///dev/ttyUSB0?baud=115200", "--connect");
  EXPECT_EQ(serial.path, "/dev/ttyUSB0");
  EXPECT_EQ(serial.baud, 115200);
  const LiveAddress sim = parse_live_address("sim://nao?seed=3&rate=2", "--connect");
  EXPECT_EQ(sim.skin, "nao");
  EXPECT_EQ(sim.seed, 3u);
  EXPECT_DOUBLE_EQ(sim.speed, 2.0);
  const LiveAddress replay = parse_live_address("replay:///data/a.h5?speed=0.25", "--connect");
  EXPECT_EQ(replay.path, "/data/a.h5");
  EXPECT_DOUBLE_EQ(replay.speed, 0.25);
}

TEST(LiveAddress, RefusesWithTheReason) {
  EXPECT_NE(refusal("tcp://1.2.3.4:5").find("not a live source kind"), std::string::npos);
  EXPECT_NE(refusal("nao").find("not a live source"), std::string::npos);
  // Port 0 is a listener's "any free port" (the state JSON says which it got); above 65535 is
  // no port.
  EXPECT_NE(refusal("udp://:65536").find("not in 0-65535"), std::string::npos);
  EXPECT_EQ(parse_live_address("udp://:0", "--connect").port, 0);
  EXPECT_NE(refusal("serial:///dev/ttyS0?baud=12345").find("not a standard rate"),
            std::string::npos);
  EXPECT_NE(refusal("serial://ttyS0").find("device path"), std::string::npos);
  EXPECT_NE(refusal("sim://cat").find("not a simulated skin"), std::string::npos);
  EXPECT_NE(refusal("sim://nao?speed=2").find("KEY one of seed, rate"), std::string::npos);
  EXPECT_NE(refusal("replay:///a.h5?speed=9").find("not in 0.25-4"), std::string::npos);
  EXPECT_NE(refusal("replay:///a.h5?speed=x").find("not a number"), std::string::npos);
}

// A fur stream of `count` samples, as the simulator makes them.
Stream fur_stream() {
  const SkinLayout layout = load_layout("fur");
  SimulationOptions options;
  options.subjects = 1;
  SimulatedTrial trial = skin_record("fur").simulate(layout, options, 0, 0);
  return trial.recording.streams.front();
}

TEST(SimulatorInput, WithATrialCountSendsThatManyWholeTrialsThenEnds) {
  EXPECT_EQ(parse_live_address("sim://fur?trials=2", "--connect").trials, 2);
  EXPECT_EQ(parse_live_address("sim://fur", "--connect").trials, 0);  // endless
  EXPECT_NE(refusal("sim://fur?trials=0").find("trials 0 is not a whole number"),
            std::string::npos);
  EXPECT_NE(refusal("sim://fur?trials=1.5").find("trials 1.5"), std::string::npos);
  // What `tactile stream-sim` sends: every sample of trial 0, in device time from 0, then the end.
  const std::unique_ptr<DatagramInput> input =
      open_live_input(parse_live_address("sim://fur?rate=1000&trials=1", "--connect"));
  int64_t samples = 0;
  double first_time = -1.0;
  std::vector<uint8_t> datagram;
  while (!input->ended())
    if (input->next(datagram, 1.0)) {
      const PacketHeader header = decode_packet_header(datagram);
      if (first_time < 0.0) first_time = header.time;
      samples += header.sample_count;
    }
  EXPECT_EQ(samples, fur_stream().sample_count());
  EXPECT_EQ(first_time, 0.0);
}

std::vector<std::vector<uint8_t>> fur_datagrams(int64_t count) {
  const SkinLayout layout = load_layout("fur");
  const Stream stream = fur_stream();
  uint32_t sequence = 0;
  return PacketEncoder(layout, stream).encode(0, std::min(count, stream.sample_count()), sequence);
}

TEST(PacketFramer, CutsAByteStreamBackIntoDatagramsWhereverItIsSplit) {
  const auto datagrams = fur_datagrams(20);
  std::vector<uint8_t> bytes;
  for (const auto& datagram : datagrams)
    bytes.insert(bytes.end(), datagram.begin(), datagram.end());
  for (size_t piece : {size_t{1}, size_t{7}, size_t{352}, size_t{1000}}) {
    PacketFramer framer;
    std::vector<std::vector<uint8_t>> out;
    std::vector<uint8_t> datagram;
    for (size_t at = 0; at < bytes.size(); at += piece) {
      framer.feed(std::span<const uint8_t>(bytes.data() + at, std::min(piece, bytes.size() - at)));
      while (framer.next(datagram)) out.push_back(datagram);
    }
    EXPECT_EQ(out, datagrams) << "fed " << piece << " bytes at a time";
    EXPECT_EQ(framer.broken(), 0);
  }
}

TEST(PacketFramer, SkipsNoiseAndDamagedDatagramsAndCountsEachStretchOnce) {
  auto datagrams = fur_datagrams(6);
  datagrams[2][100] ^= 0x40;  // payload damage: the CRC no longer matches
  std::vector<uint8_t> bytes = {'T', 'W', 'x', 0, 1, 2};  // line noise, a false start
  for (const auto& datagram : datagrams)
    bytes.insert(bytes.end(), datagram.begin(), datagram.end());
  PacketFramer framer;
  framer.feed(bytes);
  std::vector<uint8_t> datagram;
  int whole = 0;
  while (framer.next(datagram)) {
    decode_packet(datagram, load_layout("fur"));  // every one handed out decodes
    ++whole;
  }
  EXPECT_EQ(whole, 5);
  EXPECT_EQ(framer.broken(), 2);  // the noise, the damaged datagram
  EXPECT_LT(framer.buffered(), 4u);
}

// A header that declares a 4 GiB payload is a false start: the framer neither waits for
// nor buffers those bytes, and the datagram after it arrives.
TEST(PacketFramer, AHeaderDeclaringAHugePayloadIsSkippedWithoutWaitingForIt) {
  auto datagrams = fur_datagrams(2);
  std::vector<uint8_t> bytes = datagrams[0];
  const uint32_t huge = 0xFFFFFFF0u;
  std::memcpy(bytes.data() + 24, &huge, 4);  // payload length field
  bytes.insert(bytes.end(), datagrams[1].begin(), datagrams[1].end());
  PacketFramer framer;
  framer.feed(bytes);
  std::vector<uint8_t> datagram;
  ASSERT_TRUE(framer.next(datagram));
  EXPECT_EQ(datagram, datagrams[1]);
  EXPECT_EQ(framer.broken(), 1);
  EXPECT_LT(framer.buffered(), 4u);
  // The decoder refuses the same header by its length, naming the byte.
  try {
    decode_packet(std::vector<uint8_t>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(
                                                                          datagrams[0].size())),
                  load_layout("fur"));
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("byte 24"), std::string::npos) << error.what();
  }
}

TEST(SerialInput, ReceivesPacketsThroughAPseudoTerminal) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  const std::string device = ptsname(master);
  const SkinLayout layout = load_layout("fur");
  LiveReceiver receiver(
      open_live_input(parse_live_address("serial://" + device + "?baud=115200", "--connect")),
      layout);
  auto datagrams = fur_datagrams(30);
  datagrams.erase(datagrams.begin() + 10);  // one lost on the line
  for (const auto& datagram : datagrams) {
    ASSERT_EQ(write(master, datagram.data(), datagram.size()),
              static_cast<ssize_t>(datagram.size()));
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (receiver.counters().datagrams < 29 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const LiveCounters counters = receiver.counters();
  EXPECT_EQ(counters.datagrams, 29);
  EXPECT_EQ(counters.lost, 1);
  EXPECT_EQ(counters.broken, 0);
  EXPECT_EQ(receiver.ring().size(), 29);
  receiver.stop();
  close(master);
}

TEST(SerialInput, RefusesAFileThatIsNotAPort) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("plain");
  { std::ofstream(path) << "x"; }
  try {
    open_live_input(parse_live_address("serial://" + path, "--connect"));
    FAIL() << "a plain file opened as a serial port";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("not a serial port"), std::string::npos)
        << error.what();
  }
}

//---- Devices that go away and come back

// A serial device behind a stable path (like /dev/serial/by-id/...): a pseudo-terminal whose
// master is the device's end, the path a symlink to its slave. Unplugging closes the master
// (the slave hangs up) and removes the link; plugging in makes a new pair and links again.
class PluggableDevice {
 public:
  explicit PluggableDevice(std::string path) : path_(std::move(path)) { plug(); }
  ~PluggableDevice() { unplug(); }
  void plug() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    ASSERT_GE(master_, 0);
    ASSERT_EQ(grantpt(master_), 0);
    ASSERT_EQ(unlockpt(master_), 0);
    ASSERT_EQ(symlink(ptsname(master_), path_.c_str()), 0);
  }
  void unplug() {
    if (master_ < 0) return;
    close(master_);
    master_ = -1;
    unlink(path_.c_str());
  }
  void send(const std::vector<uint8_t>& bytes) {
    ASSERT_EQ(write(master_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int master_ = -1;
};

// Waits (at most 10 s) until `done` holds; false when it never did.
template <typename Condition>
bool eventually(Condition done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

TEST(SerialInput, AnUnpluggedPortIsWaitedForAndNeverBlocksLongerThanItsTimeout) {
  testing::TemporaryDirectory directory;
  PluggableDevice device(directory.file("usb-tactile-if00"));
  const std::unique_ptr<DatagramInput> input = open_live_input(
      parse_live_address("serial://" + device.path() + "?baud=115200", "--connect"));
  const auto datagrams = fur_datagrams(3);
  device.send(datagrams[0]);
  std::vector<uint8_t> datagram;
  ASSERT_TRUE(eventually([&] { return input->next(datagram, 0.05); }));
  EXPECT_EQ(datagram, datagrams[0]);
  device.unplug();
  // Each call returns with nothing (no exception) while the device is away, saying so.
  for (int call = 0; call < 10; ++call) EXPECT_FALSE(input->next(datagram, 0.05));
  EXPECT_EQ(input->unplugs(), 1);
  EXPECT_EQ(input->replugs(), 0);
  EXPECT_NE(input->gone().find(device.path()), std::string::npos) << input->gone();
  device.plug();
  ASSERT_TRUE(eventually([&] {
    input->next(datagram, 0.05);
    return input->replugs() == 1;
  }));
  EXPECT_EQ(input->gone(), "");
  device.send(datagrams[1]);
  ASSERT_TRUE(eventually([&] { return input->next(datagram, 0.05); }));
  EXPECT_EQ(datagram, datagrams[1]);  // raw mode again: the bytes arrive as sent
  EXPECT_EQ(input->broken(), 0);
}

TEST(SerialInput, APathThatDoesNotExistAtTheStartIsStillAnError) {
  testing::TemporaryDirectory directory;
  try {
    open_live_input(parse_live_address("serial://" + directory.file("no-such-port"), "--connect"));
    FAIL() << "a missing port opened";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cannot open"), std::string::npos) << error.what();
  }
}

TEST(LiveReceiver, ARepluggedDeviceResumesAfterAGapWithEverySampleFromBeforeTheUnplug) {
  testing::TemporaryDirectory directory;
  PluggableDevice device(directory.file("usb-tactile-if00"));
  const SkinLayout layout = load_layout("fur");
  LiveReceiver receiver(
      open_live_input(parse_live_address("serial://" + device.path(), "--connect")), layout);
  const Stream stream = fur_stream();
  const auto datagrams = fur_datagrams(20);
  for (const auto& datagram : datagrams) device.send(datagram);
  ASSERT_TRUE(eventually([&] { return receiver.counters().datagrams == 20; }));
  device.unplug();
  ASSERT_TRUE(eventually([&] { return !receiver.counters().gone.empty(); }));
  EXPECT_NE(receiver.counters().gone.find(device.path()), std::string::npos);
  EXPECT_TRUE(receiver.failure().empty());  // the session goes on
  device.plug();
  ASSERT_TRUE(eventually([&] { return receiver.counters().replugs == 1; }));
  // The device started again: its count and its clock from 0.
  for (const auto& datagram : datagrams) device.send(datagram);
  ASSERT_TRUE(eventually([&] { return receiver.counters().datagrams == 40; }));
  receiver.stop();
  const LiveCounters counters = receiver.counters();
  EXPECT_EQ(counters.unplugs, 1);
  EXPECT_EQ(counters.replugs, 1);
  EXPECT_EQ(counters.restarts, 1);
  EXPECT_EQ(counters.lost + counters.duplicated + counters.reordered + counters.broken, 0);
  EXPECT_EQ(counters.gone, "");
  LiveSampleSource source(receiver.source_info(), 10000);
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  // 20 samples, the time the device was away as a gap, 20 samples again.
  const int64_t gap = source.gap_samples();
  EXPECT_GE(gap, 3);  // away for at least one reopening attempt, 0.25 s
  EXPECT_EQ(source.sample_count(), 40 + gap);
  for (int64_t row = 0; row < 20; ++row) {
    EXPECT_NEAR(source.values_at(row)[7], stream.samples(row, 7), 0.02) << row;
    EXPECT_NEAR(source.values_at(20 + gap + row)[7], stream.samples(row, 7), 0.02) << row;
  }
  for (int64_t row = 20; row < 20 + gap; ++row) EXPECT_TRUE(std::isnan(source.values_at(row)[0]));
}

TEST(LiveReceiver, AUdpSenderRestartedAfterAPauseIsARestartAndAStallNotLossOrDuplicates) {
  const SkinLayout layout = load_layout("fur");
  uint16_t port = 0;
  {
    UdpSocket probe = UdpSocket::bind_to({"127.0.0.1", 0});
    port = probe.local_port();
  }
  LiveReceiver receiver(
      open_live_input(parse_live_address("udp://:" + std::to_string(port), "--connect")), layout);
  const auto datagrams = fur_datagrams(30);
  {
    UdpSocket sender = UdpSocket::connect_to({"127.0.0.1", port});
    for (const auto& datagram : datagrams) sender.send(datagram);
    ASSERT_TRUE(eventually([&] { return receiver.counters().datagrams == 30; }));
  }
  // Silent for longer than the stall time (10 datagram periods, 0.67 s at 15 Hz) ...
  ASSERT_TRUE(eventually([&] { return receiver.counters().stalled; }));
  EXPECT_EQ(receiver.counters().stalls, 1);
  // ... then a new sender process: the same numbers and times again, from 0.
  UdpSocket sender = UdpSocket::connect_to({"127.0.0.1", port});
  for (int k = 0; k < 10; ++k) sender.send(datagrams[static_cast<size_t>(k)]);
  ASSERT_TRUE(eventually([&] { return receiver.counters().datagrams == 40; }));
  receiver.stop();
  const LiveCounters counters = receiver.counters();
  EXPECT_EQ(counters.restarts, 1);
  EXPECT_EQ(counters.stalls, 1);
  EXPECT_FALSE(counters.stalled);
  EXPECT_EQ(counters.lost + counters.duplicated + counters.reordered + counters.clock_jumps, 0);
  LiveSampleSource source(receiver.source_info(), 10000);
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  EXPECT_GE(source.gap_samples(), 10);  // the pause, by the arrival clock
  EXPECT_EQ(source.sample_count(), 40 + source.gap_samples());
}

TEST(LiveReceiver, ASenderWhoseClockJumpsForwardAndBackIsRecordedWithoutAJumpOrAGap) {
  const SkinLayout layout = load_layout("fur");
  uint16_t port = 0;
  {
    UdpSocket probe = UdpSocket::bind_to({"127.0.0.1", 0});
    port = probe.local_port();
  }
  LiveReceiver receiver(
      open_live_input(parse_live_address("udp://:" + std::to_string(port), "--connect")), layout);
  auto datagrams = fur_datagrams(30);
  // The header's time stamp (f64 at byte 12; the CRC covers the payload only): an NTP step
  // of an hour forward at datagram 10, and back to 0 at datagram 20.
  for (size_t k = 10; k < 30; ++k) {
    double time = 0.0;
    std::memcpy(&time, datagrams[k].data() + 12, 8);
    time = k < 20 ? time + 3600.0 : time - 20.0 / 15.0;
    std::memcpy(datagrams[k].data() + 12, &time, 8);
  }
  UdpSocket sender = UdpSocket::connect_to({"127.0.0.1", port});
  for (const auto& datagram : datagrams) sender.send(datagram);
  ASSERT_TRUE(eventually([&] { return receiver.counters().datagrams == 30; }));
  receiver.stop();
  const LiveCounters counters = receiver.counters();
  EXPECT_EQ(counters.clock_jumps, 2);
  EXPECT_EQ(counters.lost + counters.restarts + counters.late_dropped, 0);
  LiveSampleSource source(receiver.source_info(), 10000);
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  EXPECT_EQ(source.sample_count(), 30);
  EXPECT_EQ(source.gap_samples(), 0);
  const Stream stream = fur_stream();
  for (int64_t row = 0; row < 30; ++row)
    EXPECT_NEAR(source.values_at(row)[3], stream.samples(row, 3), 0.02);
}

TEST(LiveReceiver, TheSimulatorStreamsAtItsRateIntoTheBuffer) {
  // fur at 15 Hz, 8 times as fast: about 120 samples a second.
  LiveReceiver receiver(open_live_input(parse_live_address("sim://fur?rate=8", "--connect")),
                        load_layout("fur"));
  LiveSampleSource source(receiver.source_info(), 10000);
  // A second and a half of it; the simulator's first trial may take longer to make on a slow
  // or busy machine (a sanitizer build): then until 60 have come, 20 s at most.
  const auto began = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  while (receiver.counters().samples <= 60 &&
         std::chrono::steady_clock::now() - began < std::chrono::seconds(20))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  // Stopped before counting: a sample arriving between the drain and the count would make
  // them differ by one (it did under the sanitizers, which slow the reader down).
  receiver.stop();
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  const LiveCounters counters = receiver.counters();
  EXPECT_GT(counters.samples, 60);
  EXPECT_LT(counters.samples, 400);
  EXPECT_EQ(counters.lost + counters.broken + counters.overflow, 0);
  EXPECT_EQ(source.sample_count(), counters.samples);
  EXPECT_EQ(source.channel_count(), 160);
  EXPECT_EQ(source.gap_samples(), 0);
}

TEST(LiveReceiver, AReplayedFileArrivesWholeAndEnds) {
  testing::TemporaryDirectory directory;
  const SkinLayout layout = load_layout("fur");
  SimulationOptions options;
  options.subjects = 1;
  SimulatedTrial trial = skin_record("fur").simulate(layout, options, 0, 0);
  Stream& stream = trial.recording.streams.front();
  stream.samples.conservativeResize(60, Eigen::NoChange);  // 4 s at 15 Hz
  stream.samples.row(20).setConstant(NAN);                 // a datagram lost when it was recorded
  const std::string path = directory.file("trial.h5");
  write_recording(path, trial.recording);
  LiveReceiver receiver(
      open_live_input(parse_live_address("replay://" + path + "?speed=4", "--connect")), layout);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!receiver.ended() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_TRUE(receiver.ended());
  EXPECT_EQ(receiver.failure(), "");
  LiveSampleSource source(receiver.source_info(), 1000);
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  EXPECT_EQ(source.sample_count(), 60);
  EXPECT_EQ(source.gap_samples(), 1);
  EXPECT_DOUBLE_EQ(source.start_time(), stream.start_time);
  EXPECT_NEAR(source.values_at(30)[5], stream.samples(30, 5), 0.02);
}

TEST(LiveReceiver, CountsLossDuplicatesAndBrokenDatagramsOverUdp) {
  const SkinLayout layout = load_layout("fur");
  uint16_t port = 0;
  {
    UdpSocket probe = UdpSocket::bind_to({"127.0.0.1", 0});  // a free port
    port = probe.local_port();
  }
  LiveReceiver receiver(
      open_live_input(parse_live_address("udp://:" + std::to_string(port), "--connect")), layout);
  UdpSocket sender = UdpSocket::connect_to({"127.0.0.1", port});
  auto datagrams = fur_datagrams(12);
  std::vector<uint8_t> broken = datagrams[4];
  broken[40] ^= 1;
  for (int k : {0, 1, 2, 3, 5, 6, 6, 8, 7, 9, 10, 11})
    sender.send(datagrams[static_cast<size_t>(k)]);
  sender.send(broken);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (receiver.counters().datagrams < 13 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const LiveCounters counters = receiver.counters();
  EXPECT_EQ(counters.datagrams, 13);
  EXPECT_EQ(counters.lost, 1);  // 4 never came whole
  EXPECT_EQ(counters.duplicated, 1);
  EXPECT_EQ(counters.reordered, 1);
  EXPECT_EQ(counters.broken, 1);
  EXPECT_NE(counters.last_error.find("packet byte"), std::string::npos) << counters.last_error;
  LiveSampleSource source(receiver.source_info(), 1000);
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  EXPECT_EQ(source.sample_count(), 12);
  EXPECT_EQ(source.gap_samples(), 2);  // 4 missing; 7 left a gap that 7 filled when it came
  EXPECT_TRUE(std::isnan(source.values_at(4)[0]));
  EXPECT_FALSE(std::isnan(source.values_at(7)[0]));
}

}  // namespace
}  // namespace tactile

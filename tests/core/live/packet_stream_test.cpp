// Sequence tracking, rebuilding recordings from datagrams, and the paced UDP loop on loopback.
#include "tactile/live/packet_stream.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "packet_test_support.h"
#include "tactile/error.h"
#include "tactile/live/udp.h"

namespace tactile {
namespace {

//---- SequenceTracker -------------------------------------------------------------------

TEST(SequenceTracker, CountsALostADuplicatedAndAReorderedPacket) {
  SequenceTracker tracker;
  // 0 1 2 [3 lost] 4 5 5(duplicate) 7 6(late) 8
  for (uint32_t sequence : {0u, 1u, 2u, 4u, 5u}) EXPECT_TRUE(tracker.accept(sequence));
  EXPECT_FALSE(tracker.accept(5));
  EXPECT_TRUE(tracker.accept(7));
  EXPECT_EQ(tracker.lost(), 2);  // 3 and 6 missing so far
  EXPECT_TRUE(tracker.accept(6));
  EXPECT_TRUE(tracker.accept(8));
  EXPECT_EQ(tracker.received(), 8);
  EXPECT_EQ(tracker.lost(), 1);
  EXPECT_EQ(tracker.duplicated(), 1);
  EXPECT_EQ(tracker.reordered(), 1);
  EXPECT_EQ(tracker.restarts(), 0);
}

TEST(SequenceTracker, FollowsTheWrapOfTheThirtyTwoBitCounter) {
  SequenceTracker tracker;
  const uint32_t top = 0xFFFFFFFEu;
  EXPECT_TRUE(tracker.accept(top));
  EXPECT_TRUE(tracker.accept(top + 1));
  EXPECT_TRUE(tracker.accept(1));  // 0 lost across the wrap
  EXPECT_EQ(tracker.lost(), 1);
  EXPECT_FALSE(tracker.accept(top + 1));
  EXPECT_TRUE(tracker.accept(0));
  EXPECT_EQ(tracker.lost(), 0);
  EXPECT_EQ(tracker.duplicated(), 1);
  EXPECT_EQ(tracker.reordered(), 1);
}

TEST(SequenceTracker, ANumberFarBehindIsASenderRestartNotAFlood) {
  SequenceTracker tracker;
  for (uint32_t sequence = 50000; sequence < 50010; ++sequence) tracker.accept(sequence);
  EXPECT_TRUE(tracker.accept(0));
  EXPECT_TRUE(tracker.accept(1));
  EXPECT_EQ(tracker.restarts(), 1);
  EXPECT_EQ(tracker.lost(), 0);
  EXPECT_EQ(tracker.received(), 12);
  // Early numbers from before the first one seen are late, not lost, and not negative loss.
  SequenceTracker late;
  late.accept(10);
  EXPECT_TRUE(late.accept(9));
  EXPECT_EQ(late.lost(), 0);
  EXPECT_FALSE(late.accept(9));
}

//---- PacketCollector -------------------------------------------------------------------

TEST(PacketCollector, RebuildsTheStreamAndMarksAGapWithTimeStamps) {
  const SkinLayout layout = load_layout("flux");
  const Stream stream = test::grid_stream(layout, 50, 4);  // 5 datagrams of 10 samples
  uint32_t sequence = 0;
  const auto datagrams = PacketEncoder(layout, stream).encode(0, 50, sequence);
  ASSERT_EQ(datagrams.size(), 5u);

  PacketCollector whole(layout, true);
  for (int index : {0, 2, 1, 3, 4}) EXPECT_TRUE(whole.add(datagrams[index]));
  const Recording complete = whole.recording("flux-live");
  ASSERT_EQ(complete.streams.size(), 1u);
  const Stream& rebuilt = complete.streams[0];
  EXPECT_TRUE(rebuilt.timestamps.empty());
  EXPECT_DOUBLE_EQ(rebuilt.start_time, stream.start_time);
  EXPECT_EQ(rebuilt.channels.front(), "x1");
  EXPECT_EQ(rebuilt.channels.back(), "y4");
  EXPECT_EQ(rebuilt.samples.col(4), stream.samples.col(layout.channel_index("y1")));
  EXPECT_EQ(whole.sequence().reordered(), 1);

  PacketCollector gap(layout, true);
  for (int index : {0, 1, 3, 4}) gap.add(datagrams[index]);
  EXPECT_EQ(gap.sequence().lost(), 1);
  const Recording with_gap = gap.recording("flux-gap");
  const Stream& holed = with_gap.streams[0];
  ASSERT_EQ(holed.sample_count(), 40);
  ASSERT_EQ(holed.timestamps.size(), 40u);
  EXPECT_NEAR(holed.timestamps[20] - holed.timestamps[19], 0.011, 1e-9);  // 10 samples missing
}

TEST(PacketCollector, CountsBrokenDatagramsAndKeepsTheirError) {
  const SkinLayout layout = load_layout("robovie");
  PacketCollector collector(layout, false);
  const std::vector<uint8_t> garbage = {'T', 'W', 'P', 'K', 1};
  EXPECT_FALSE(collector.add(garbage));
  EXPECT_EQ(collector.broken(), 1);
  EXPECT_NE(collector.last_error().find("packet byte 5"), std::string::npos);
  EXPECT_THROW(collector.recording("x"), Error);
}

//---- UDP -------------------------------------------------------------------------------

TEST(UdpUrl, AcceptsHostAndPortAndNamesTheOptionOnEveryMistake) {
  const UdpEndpoint endpoint = parse_udp_url("udp://127.0.0.1:9000", "--to", UdpUse::kSend);
  EXPECT_EQ(endpoint.host, "127.0.0.1");
  EXPECT_EQ(endpoint.port, 9000);
  EXPECT_EQ(parse_udp_url("udp://localhost:1", "--to", UdpUse::kSend).host, "127.0.0.1");
  for (const char* url :
       {"tcp://127.0.0.1:9000", "udp://127.0.0.1", "udp://127.0.0.1:0", "udp://127.0.0.1:65536",
        "udp://127.0.0.1:90x", "udp://:9000", "udp://robot.example:9000", "udp://127.0.0.1:-5"}) {
    try {
      parse_udp_url(url, "--to", UdpUse::kSend);
      ADD_FAILURE() << url << " was accepted";
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), "--to") << url;
    }
  }
}

// A listener may ask for port 0 and learn the port the system gave it, so that no test (or
// user) has to guess a free port and race another program for it.
TEST(UdpUrl, AListenerTakesPortZeroAndReportsThePortItGot) {
  const UdpEndpoint any = parse_udp_url("udp://127.0.0.1:0", "--from", UdpUse::kListen);
  EXPECT_EQ(any.port, 0);
  UdpSocket listener = UdpSocket::bind_to(any);
  const uint16_t port = listener.local_port();
  EXPECT_GT(port, 0);
  UdpSocket sender = UdpSocket::connect_to({"127.0.0.1", port});
  const std::vector<uint8_t> datagram = {1, 2, 3};
  sender.send(datagram);
  std::vector<uint8_t> buffer(16);
  EXPECT_EQ(listener.receive(buffer, 5.0), std::optional<size_t>(3));
  for (const char* url : {"udp://127.0.0.1:65536", "udp://127.0.0.1:-1"})
    EXPECT_THROW(parse_udp_url(url, "--from", UdpUse::kListen), Error) << url;
}

}  // namespace
}  // namespace tactile

// Where received datagrams go on the stream's clock: a sender that pauses, restarts, loses
// datagrams or whose clock jumps. Arrival times are given, so nothing here waits.
#include "tactile/live/live_timeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "tactile/error.h"

namespace tactile {
namespace {

constexpr double kTimelineRate = 15.0;  // fur: one sample per datagram
constexpr double kTimelinePeriod = 1.0 / kTimelineRate;

LiveTimeline fur_timeline() {
  return LiveTimeline({.rate_hz = kTimelineRate, .samples_per_datagram = 1});
}

// The sample index of a stream time on the 15 Hz grid from 0.
int64_t index_of(double time) { return std::llround(time * kTimelineRate); }

TEST(LiveTimeline, ASteadySenderKeepsItsOwnTimeStamps) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 30; ++k) {
    const auto placement = timeline.place(k, 100.0 + k * kTimelinePeriod, 1, k * kTimelinePeriod);
    ASSERT_TRUE(placement.deliver);
    EXPECT_DOUBLE_EQ(placement.time, 100.0 + k * kTimelinePeriod);
  }
  EXPECT_EQ(timeline.clock_jumps(), 0);
  EXPECT_EQ(timeline.stalls(), 0);
  EXPECT_EQ(timeline.restarts(), 0);
  EXPECT_THROW(LiveTimeline({.rate_hz = 0.0}), Error);
}

TEST(LiveTimeline, LostDatagramsLeaveGapsOfTheirSize) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k : {0u, 1u, 2u, 5u, 6u}) {
    const auto placement = timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
    EXPECT_EQ(index_of(placement.time), k);
  }
  EXPECT_EQ(timeline.sequence().lost(), 2);
  // One of them comes late: it fills its own place; the same again is a duplicate.
  const auto late = timeline.place(3, 3 * kTimelinePeriod, 1, 7 * kTimelinePeriod);
  ASSERT_TRUE(late.deliver);
  EXPECT_EQ(index_of(late.time), 3);
  EXPECT_FALSE(timeline.place(3, 3 * kTimelinePeriod, 1, 7 * kTimelinePeriod).deliver);
  EXPECT_EQ(timeline.sequence().lost(), 1);
  EXPECT_EQ(timeline.clock_jumps(), 0);
}

TEST(LiveTimeline, ASenderRestartedAfterAPauseIsOneRestartNotLossOrReordering) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 100; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  // Silent for 2 s, then it counts from 0 again with its clock from 0.
  const double back = 99 * kTimelinePeriod + 2.0;
  for (uint32_t k = 0; k < 10; ++k) {
    const auto placement = timeline.place(k, k * kTimelinePeriod, 1, back + k * kTimelinePeriod);
    ASSERT_TRUE(placement.deliver) << k;
    // After the 100 samples, the silence beyond one datagram (2 s - 1/15 s = 29 samples) is a gap.
    EXPECT_EQ(index_of(placement.time), 100 + 29 + k);
  }
  const SequenceTracker& sequence = timeline.sequence();
  EXPECT_EQ(sequence.restarts(), 1);
  EXPECT_EQ(sequence.lost(), 0);
  EXPECT_EQ(sequence.reordered(), 0);
  EXPECT_EQ(sequence.duplicated(), 0);
  EXPECT_EQ(timeline.stalls(), 1);
  EXPECT_EQ(timeline.clock_jumps(), 0);  // a new session has a new clock: not a jump
}

TEST(LiveTimeline, ARestartAfterAPauseIsSeenEvenWhenTheOldCountWasShort) {
  // Five datagrams, then the sender starts again at 0: without the pause these numbers would
  // be duplicates of the first five.
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 5; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  for (uint32_t k = 0; k < 5; ++k)
    EXPECT_TRUE(timeline.place(k, k * kTimelinePeriod, 1, 2.0 + k * kTimelinePeriod).deliver);
  EXPECT_EQ(timeline.restarts(), 1);
  EXPECT_EQ(timeline.sequence().duplicated(), 0);
}

TEST(LiveTimeline, ARestartWithoutAPauseContinuesRightAfterTheNewestSample) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 200; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  const auto placement = timeline.place(0, 0.0, 1, 200 * kTimelinePeriod);
  EXPECT_TRUE(placement.deliver);
  EXPECT_EQ(index_of(placement.time), 200);
  EXPECT_EQ(timeline.restarts(), 1);
  EXPECT_EQ(timeline.stalls(), 0);
}

TEST(LiveTimeline, AClockJumpForwardIsCountedAndTheStreamGoesOnWithoutAGap) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 50; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  for (uint32_t k = 50; k < 80; ++k) {
    const auto placement =
        timeline.place(k, 3600.0 + k * kTimelinePeriod, 1, k * kTimelinePeriod);  // an NTP step
    EXPECT_EQ(index_of(placement.time), k);
  }
  EXPECT_EQ(timeline.clock_jumps(), 1);
  EXPECT_EQ(timeline.restarts(), 0);
}

TEST(LiveTimeline, AClockJumpBackNeverPutsASampleOverAnother) {
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 50; ++k)
    timeline.place(k, 10.0 + k * kTimelinePeriod, 1, k * kTimelinePeriod);
  // The clock steps back by 0.2 s (three samples) and later starts at 0; two datagrams lost.
  for (uint32_t k = 50; k < 60; ++k)
    EXPECT_EQ(
        index_of(timeline.place(k, 10.0 - 0.2 + k * kTimelinePeriod, 1, k * kTimelinePeriod).time),
        150 + k);
  EXPECT_EQ(index_of(timeline.place(62, 0.0, 1, 62 * kTimelinePeriod).time), 150 + 62);
  EXPECT_EQ(timeline.clock_jumps(), 2);
  EXPECT_EQ(timeline.sequence().lost(), 2);
}

TEST(LiveTimeline, APauseThatTheSendersClockAndTheArrivalsAgreeOnIsAGap) {
  // The sender stopped sending for 3 s and goes on with its count: its clock and the
  // receiver's both say 3 s passed, so the 3 s are a gap, not a clock jump.
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 30; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  const auto placement =
      timeline.place(30, 30 * kTimelinePeriod + 3.0, 1, 30 * kTimelinePeriod + 3.0);
  EXPECT_EQ(index_of(placement.time), 30 + 45);
  EXPECT_EQ(timeline.clock_jumps(), 0);
  EXPECT_EQ(timeline.restarts(), 0);
  EXPECT_EQ(timeline.stalls(), 1);
}

TEST(LiveTimeline, AReplugWhoseCountWentOnKeepsTheCountAndCountsTheMissedAsLost) {
  // A device that kept running while its cable was out: 15 datagrams a second for 2 s went
  // nowhere; they are lost, and the device's clock places the rest.
  LiveTimeline timeline = fur_timeline();
  for (uint32_t k = 0; k < 30; ++k) timeline.place(k, k * kTimelinePeriod, 1, k * kTimelinePeriod);
  timeline.reconnected();
  const auto placement = timeline.place(60, 60 * kTimelinePeriod, 1, 60 * kTimelinePeriod);
  EXPECT_EQ(index_of(placement.time), 60);
  EXPECT_EQ(timeline.sequence().lost(), 30);
  EXPECT_EQ(timeline.restarts(), 0);
  // A replugged device that starts over at once is a new session.
  timeline.reconnected();
  EXPECT_EQ(index_of(timeline.place(0, 0.0, 1, 61 * kTimelinePeriod).time), 61);
  EXPECT_EQ(timeline.restarts(), 1);
}

TEST(LiveTimeline, ASilenceIsOneStallHoweverOftenTheReceiverWaits) {
  LiveTimeline timeline = fur_timeline();
  timeline.idle(5.0);  // nothing has come yet: not a stall of a stream
  EXPECT_EQ(timeline.stalls(), 0);
  timeline.place(0, 0.0, 1, 0.0);
  timeline.idle(0.1);
  EXPECT_FALSE(timeline.stalled());
  for (double now = 1.0; now < 3.0; now += 0.05) timeline.idle(now);
  EXPECT_TRUE(timeline.stalled());
  EXPECT_EQ(timeline.stalls(), 1);
  timeline.place(1, kTimelinePeriod, 1, 3.0);
  EXPECT_FALSE(timeline.stalled());
  EXPECT_EQ(timeline.stalls(), 1);
  timeline.place(2, 2 * kTimelinePeriod, 1, 4.0);  // a silence seen only when the next one came
  EXPECT_EQ(timeline.stalls(), 2);
}

TEST(LiveTimeline, DatagramsOfTenSamplesArePlacedByTheirCount) {
  LiveTimeline timeline({.rate_hz = 1000.0, .samples_per_datagram = 10});
  for (uint32_t k = 0; k < 5; ++k) timeline.place(k, k * 0.01, 10, k * 0.01);
  // Clock back to 0, one datagram (ten samples) lost: placed at sample 60.
  EXPECT_NEAR(timeline.place(6, 0.0, 10, 0.06).time, 0.06, 1e-9);
  EXPECT_EQ(timeline.clock_jumps(), 1);
}

// Whatever the sender does, no two delivered samples share a place and the end of the
// stream never moves back.
TEST(LiveTimeline, NoPlaceIsGivenTwiceWhateverTheSenderDoes) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    std::mt19937 random(seed);
    LiveTimeline timeline = fur_timeline();
    std::map<int64_t, uint32_t> taken;  // sample index -> the sequence number placed there
    uint32_t sequence = 0;
    double device = 0.0, arrival = 0.0;
    int in_order = 0;
    for (int step = 0; step < 3000; ++step) {
      const int event = static_cast<int>(random() % 100);
      if (event < 2) {
        sequence = random() % 50;  // restart
        device = 0.0;
      } else if (event < 4) {
        device += (static_cast<double>(random() % 2000) - 1000.0) / 10.0;  // clock jump
      } else if (event < 6) {
        arrival += static_cast<double>(random() % 40) / 10.0;  // a pause
      } else if (event < 9) {
        sequence += 1 + random() % 3;  // loss
        device += kTimelinePeriod;
      }
      uint32_t sent = sequence;
      double sent_time = device;
      const bool late = event >= 9 && event < 12 && sequence >= 2;
      if (late) {
        sent = sequence - 2;  // reordered or a duplicate
        sent_time = device - 2 * kTimelinePeriod;
      }
      const double end_before = timeline.end_time();
      const auto placement = timeline.place(sent, sent_time, 1, arrival);
      ASSERT_GE(timeline.end_time(), end_before) << "seed " << seed << " step " << step;
      if (placement.deliver) {
        const int64_t index = std::llround(placement.time * kTimelineRate);
        ASSERT_TRUE(taken.emplace(index, sent).second)
            << "seed " << seed << " step " << step << ": index " << index << " placed twice";
        // Behind the newest only to fill a place left empty (checked just above).
        if (placement.time >= end_before - 0.5 * kTimelinePeriod) ++in_order;
      }
      if (!late) {
        ++sequence;
        device += kTimelinePeriod;
      }
      arrival += kTimelinePeriod;
    }
    EXPECT_GT(in_order, 2500) << "seed " << seed;
  }
}

}  // namespace
}  // namespace tactile

#include "tactile/live/playback.h"

#include <gtest/gtest.h>

namespace tactile {
namespace {

TEST(PlaybackClock, AdvancesByWallTimeTimesSpeedOnlyWhilePlaying) {
  PlaybackClock clock;
  clock.set_range(0.0, 10.0);
  clock.advance(1.0);
  EXPECT_DOUBLE_EQ(clock.time(), 0.0);
  clock.play();
  clock.set_speed(2.0);
  clock.advance(1.5);
  EXPECT_DOUBLE_EQ(clock.time(), 3.0);
  clock.set_speed(0.25);
  clock.advance(2.0);
  EXPECT_DOUBLE_EQ(clock.time(), 3.5);
}

TEST(PlaybackClock, StopsAtTheEndAndRestartsFromTheBeginning) {
  PlaybackClock clock;
  clock.set_range(1.0, 2.0);
  clock.play();
  clock.advance(5.0);
  EXPECT_DOUBLE_EQ(clock.time(), 2.0);
  EXPECT_FALSE(clock.playing());
  clock.play();
  EXPECT_DOUBLE_EQ(clock.time(), 1.0);
  EXPECT_TRUE(clock.playing());
}

TEST(PlaybackClock, LoopsWhenAsked) {
  PlaybackClock clock;
  clock.set_range(0.0, 4.0);
  clock.set_looping(true);
  clock.play();
  clock.advance(5.0);
  EXPECT_DOUBLE_EQ(clock.time(), 1.0);
  EXPECT_TRUE(clock.playing());
}

TEST(PlaybackClock, SpeedAndSeekAreClamped) {
  PlaybackClock clock;
  clock.set_range(0.0, 10.0);
  clock.set_speed(100.0);
  EXPECT_DOUBLE_EQ(clock.speed(), PlaybackClock::kMaxSpeed);
  clock.set_speed(0.01);
  EXPECT_DOUBLE_EQ(clock.speed(), PlaybackClock::kMinSpeed);
  clock.seek(-3.0);
  EXPECT_DOUBLE_EQ(clock.time(), 0.0);
  clock.seek(42.0);
  EXPECT_DOUBLE_EQ(clock.time(), 10.0);
}

}  // namespace
}  // namespace tactile

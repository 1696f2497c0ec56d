// The live buffer: samples placed by time, gaps where packets were lost, reordered samples
// filling their place, old samples gone past the buffer's length, min/max answers exactly
// as a brute-force scan over what is kept.
#include "tactile/live/live_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

#include "tactile/error.h"
#include "tactile/live/live_recorder.h"
#include "tactile/live/sample_ring.h"

namespace tactile {
namespace {

SourceInfo two_channels(double rate = 100.0) {
  SourceInfo info;
  info.layout_id = "test";
  info.rate_hz = rate;
  info.channels = {"a", "b"};
  info.units = {"V", "V"};
  return info;
}

std::vector<float> pair(float a, float b) { return {a, b}; }

TEST(LiveSampleSource, PlacesSamplesByTimeAndStartsAtTheFirst) {
  LiveSampleSource source(two_channels(), 1000);
  EXPECT_EQ(source.sample_count(), 0);
  source.add(5.0, pair(1, 10));
  source.add(5.01, pair(2, 20));
  EXPECT_EQ(source.sample_count(), 2);
  EXPECT_DOUBLE_EQ(source.start_time(), 5.0);
  EXPECT_EQ(source.values_at(1), pair(2, 20));
  EXPECT_EQ(source.index_at(5.015), 1);
}

TEST(LiveSampleSource, LostSamplesAreGapsNeverValues) {
  LiveSampleSource source(two_channels(), 1000);
  source.add(0.0, pair(1, 1));
  const auto placed = source.add(0.05, pair(3, 3));  // 4 samples missing
  EXPECT_EQ(placed.index, 5);
  EXPECT_EQ(placed.gap, 4);
  EXPECT_EQ(source.gap_samples(), 4);
  EXPECT_TRUE(std::isnan(source.values_at(2)[0]));
  EXPECT_EQ(source.gaps(), (std::vector<std::pair<int64_t, int64_t>>{{1, 5}}));
  source.add(0.03, pair(2, 2));  // one of them comes late: the stretch splits around it
  EXPECT_EQ(source.gaps(), (std::vector<std::pair<int64_t, int64_t>>{{1, 3}, {4, 5}}));
  source.add(0.02, pair(2, 2));
  // A column over the gap alone is empty: a plot draws a break there.
  const int64_t edges[] = {1, 2};
  MinMax out[1];
  source.minmax(0, edges, out);
  EXPECT_TRUE(out[0].empty());
}

TEST(LiveSampleSource, ALateSampleFillsItsGap) {
  LiveSampleSource source(two_channels(), 1000);
  source.add(0.00, pair(1, 1));
  source.add(0.02, pair(3, 3));
  source.add(0.01, pair(2, 2));  // reordered
  EXPECT_EQ(source.sample_count(), 3);
  EXPECT_EQ(source.values_at(1), pair(2, 2));
  EXPECT_TRUE(source.gaps().empty());
  const int64_t edges[] = {0, 3};
  MinMax out[1];
  source.minmax(1, edges, out);
  EXPECT_EQ(out[0], (MinMax{1, 3}));
}

TEST(LiveSampleSource, KeepsOnlyTheBufferAndRefusesToReadBeforeIt) {
  LiveSampleSource source(two_channels(), 100);
  for (int k = 0; k < 250; ++k) source.add(k / 100.0, pair(static_cast<float>(k), 0));
  EXPECT_EQ(source.sample_count(), 250);
  EXPECT_EQ(source.first_kept(), 150);
  EXPECT_TRUE(std::isnan(source.values_at(149)[0]));
  EXPECT_EQ(source.values_at(150)[0], 150.0f);
  EXPECT_THROW(source.read(std::vector<int>{0}, 149, 2), Error);
  EXPECT_EQ(source.read(std::vector<int>{0}, 240, 10)(9, 0), 249.0f);
  // A sample older than the buffer is dropped, not written over newer ones.
  EXPECT_EQ(source.add(1.0, pair(-1, -1)).index, -1);
  EXPECT_EQ(source.dropped_samples(), 1);
  const int64_t edges[] = {0, 250};
  MinMax out[1];
  source.minmax(0, edges, out);
  EXPECT_EQ(out[0], (MinMax{150, 249}));
}

TEST(LiveSampleSource, MinMaxMatchesAScanAtEveryZoomAfterManyLaps) {
  // A buffer of 5000 samples fed 40,000 with random gaps: every query from the block
  // levels equals the brute-force answer over the samples kept.
  std::mt19937 random(7);
  LiveSampleSource source(two_channels(1000.0), 5000);
  std::normal_distribution<float> value(0.0f, 1.0f);
  std::vector<float> truth;  // by index, NaN for gaps
  int64_t index = 0;
  while (index < 40000) {
    if (random() % 50 == 0) {
      const int64_t skip = 1 + random() % 300;
      truth.insert(truth.end(), static_cast<size_t>(skip), NAN);
      index += skip;
    }
    const float v = value(random);
    source.add(static_cast<double>(index) / 1000.0, pair(v, -v));
    truth.push_back(v);
    ++index;
  }
  ASSERT_EQ(source.sample_count(), static_cast<int64_t>(truth.size()));
  const int64_t count = source.sample_count();
  const int64_t kept = source.first_kept();
  for (int trial = 0; trial < 300; ++trial) {
    int64_t a = static_cast<int64_t>(random() % (count + 200)) - 100;
    int64_t b = static_cast<int64_t>(random() % (count + 200)) - 100;
    if (a > b) std::swap(a, b);
    const int64_t edges[] = {a, b};
    MinMax out[1];
    source.minmax(0, edges, out);
    MinMax expected;
    for (int64_t k = std::max(a, kept); k < std::min(b, count); ++k)
      expected.add(truth[static_cast<size_t>(k)]);
    ASSERT_EQ(out[0], expected) << "samples [" << a << ", " << b << ")";
  }
}

TEST(LiveSampleSource, ACostThatDoesNotGrowWithTheStream) {
  // The frame's query reads blocks, not samples: 1000 columns over the whole buffer touch
  // at most a few dozen entries per column whatever its length.
  LiveSampleSource source(two_channels(2500.0), 2500 * 60);
  for (int64_t k = 0; k < 2500 * 60; ++k) source.add(static_cast<double>(k) / 2500.0, pair(1, 2));
  const std::vector<MinMax> columns =
      source.minmax_over_time(0, source.start_time(), source.end_time(), 1000);
  for (const MinMax& column : columns) EXPECT_EQ(column, (MinMax{1, 1}));
  EXPECT_LT(source.memory_bytes(), int64_t{2500} * 60 * 2 * 4 * 11 / 10);
}

TEST(LiveSampleSource, ClearStartsAgain) {
  LiveSampleSource source(two_channels(), 100);
  source.add(3.0, pair(1, 1));
  source.clear();
  EXPECT_EQ(source.sample_count(), 0);
  source.add(7.0, pair(2, 2));
  EXPECT_DOUBLE_EQ(source.start_time(), 7.0);
  EXPECT_EQ(source.values_at(0), pair(2, 2));
}

TEST(LiveSampleSource, ASenderWhoseClockStartedOverGoesOn) {
  LiveSampleSource source(two_channels(), 100);
  for (int k = 0; k < 500; ++k) source.add(100.0 + k / 100.0, pair(1, 1));
  source.add(0.0, pair(5, 5));  // far before anything held: the device restarted
  EXPECT_EQ(source.sample_count(), 501);
  EXPECT_EQ(source.values_at(500), pair(5, 5));
}

TEST(LiveSampleSource, RefusesNonsense) {
  SourceInfo info = two_channels(0.0);
  EXPECT_THROW(LiveSampleSource(info, 10), Error);
  EXPECT_THROW(LiveSampleSource(two_channels(), 0), Error);
  LiveSampleSource source(two_channels(), 10);
  EXPECT_THROW(source.add(0.0, std::vector<float>{1}), Error);
  EXPECT_EQ(source.add(NAN, pair(1, 1)).index, -1);
}

TEST(SampleRing, HandsSamplesOverInOrderAcrossThreads) {
  SampleRing ring(64, 3);
  constexpr int kSamples = 200000;
  int64_t refused = 0;
  std::thread producer([&] {
    for (int k = 0; k < kSamples; ++k) {
      const float v = static_cast<float>(k);
      while (!ring.push(k, std::vector<float>{v, v + 1, v + 2})) ++refused;
    }
  });
  int next = 0;
  bool in_order = true;
  while (next < kSamples) {
    ring.drain([&](double time, std::span<const float> values) {
      in_order = in_order && time == next && values[0] == next && values[2] == next + 2;
      ++next;
    });
  }
  producer.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(ring.size(), 0);
}

TEST(SampleRing, AFullRingRefusesInsteadOfBlocking) {
  SampleRing ring(2, 1);
  EXPECT_TRUE(ring.push(0, std::vector<float>{0}));
  EXPECT_TRUE(ring.push(1, std::vector<float>{1}));
  EXPECT_FALSE(ring.push(2, std::vector<float>{2}));
  EXPECT_EQ(ring.drain([](double, std::span<const float>) {}, 1), 1);
  EXPECT_TRUE(ring.push(2, std::vector<float>{2}));
  EXPECT_THROW(SampleRing(0, 1), Error);
}

TEST(ContactDetector, LearnsTheNoiseBandThenSeesAContactBeginAndAQuietTimeEnd) {
  ContactDetectorOptions options;
  options.learn_seconds = 1.0;
  options.quiet_seconds = 0.5;
  ContactDetector detector(2, 100.0, options);
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  const auto feed = [&](float level, int samples) {
    bool began = false;
    for (int k = 0; k < samples; ++k) {
      detector.add(std::vector<float>{5.0f + noise(random), level + noise(random)});
      began = began || detector.contact_began();
    }
    return began;
  };
  EXPECT_FALSE(feed(1.0f, 100));  // learning: a second of rest
  EXPECT_EQ(detector.state(), ContactDetector::State::kQuiet);
  EXPECT_FALSE(feed(1.0f, 100));  // noise stays inside the band
  EXPECT_TRUE(feed(1.5f, 20));    // a press on channel 1
  EXPECT_EQ(detector.state(), ContactDetector::State::kContact);
  feed(1.0f, 30);  // released, 0.3 s quiet: not yet
  EXPECT_FALSE(detector.quiet_for_long());
  feed(1.0f, 30);  // 0.6 s quiet
  EXPECT_TRUE(detector.quiet_for_long());
  EXPECT_THROW(ContactDetector(0, 100.0), Error);
}

}  // namespace
}  // namespace tactile

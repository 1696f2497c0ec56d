// The offset proposal on synthetic activity series of known offset, and the skin's activity
// from a source in memory.
#include "tactile/video/video_sync.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <string>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/signal/sample_source.h"

namespace tactile {
namespace {

constexpr double kRate = 10.0;

struct Touch {
  double t0 = 0, t1 = 0, force = 1;
};

// Touches at random times (a pause of 1..6 s, a contact of 0.3..3 s) over `seconds`.
std::vector<Touch> random_touches(double seconds, uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> pause(1.0, 6.0), contact(0.3, 3.0), force(0.5, 1.5);
  std::vector<Touch> touches;
  for (double t = pause(engine); t < seconds;) {
    const double length = contact(engine);
    touches.push_back({t, t + length, force(engine)});
    t += length + pause(engine);
  }
  return touches;
}

// How much changes at time t: a bump of 0.2 s at each touch's start and end.
double change_at(const std::vector<Touch>& touches, double t) {
  double sum = 0;
  for (const Touch& touch : touches)
    for (double edge : {touch.t0, touch.t1})
      sum += touch.force * std::exp(-0.5 * std::pow((t - edge) / 0.2, 2));
  return sum;
}

// The skin's activity over [0, seconds) of recording time: a noise floor and the touches.
ActivitySeries skin_series(const std::vector<Touch>& touches, double seconds, uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> noise(0.0, 5.0);
  ActivitySeries series{0.0, kRate, {}};
  for (int k = 0; k < static_cast<int>(seconds * kRate); ++k)
    series.values.push_back(50.0 + noise(engine) + 400.0 * change_at(touches, k / kRate));
  return series;
}

// A video of `seconds` whose time 0 is shown at recording time `offset`: its motion follows
// the touches, plus noise and a person moving now and then unrelated to the touches.
ActivitySeries motion_series(const std::vector<Touch>& touches, double offset, double seconds,
                             uint64_t seed, double unrelated = 0.5) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  const std::vector<Touch> person = random_touches(seconds, seed + 100);
  ActivitySeries series{0.0, kRate, {}};
  for (int k = 0; k < static_cast<int>(seconds * kRate); ++k) {
    const double video_time = k / kRate;
    series.values.push_back(1.0 + std::abs(noise(engine)) +
                            5.0 * change_at(touches, offset + video_time) +
                            5.0 * unrelated * change_at(person, video_time));
  }
  return series;
}

TEST(VideoSync, FindsTheOffsetOfAVideoWhoseMotionFollowsTheTouches) {
  const std::vector<Touch> touches = random_touches(300.0, 1);
  const ActivitySeries skin = skin_series(touches, 300.0, 2);
  for (double offset = -30.0; offset <= 30.0; offset += 7.37) {
    const ActivitySeries motion = motion_series(touches, offset, 200.0, 3);
    const SyncProposal proposal = propose_offset(skin, motion, 0.0, 40.0);
    EXPECT_NEAR(proposal.offset, offset, 1.0 / kRate) << "offset " << offset;
    EXPECT_TRUE(proposal.sure) << "offset " << offset << ": " << proposal.why;
    EXPECT_GT(proposal.correlation, 0.5);
    EXPECT_GT(proposal.confidence, kSureConfidence);
  }
}

TEST(VideoSync, FindsTheOffsetAroundAnotherCentreAndAtAnotherVideoRate) {
  const std::vector<Touch> touches = random_touches(400.0, 4);
  const ActivitySeries skin = skin_series(touches, 400.0, 5);
  ActivitySeries motion = motion_series(touches, 120.4, 150.0, 6);
  // The same motion at 30 Hz: each value three times.
  ActivitySeries fast{0.0, 3 * kRate, {}};
  for (double value : motion.values) fast.values.insert(fast.values.end(), 3, value);
  const SyncProposal proposal = propose_offset(skin, fast, 100.0, 30.0);
  EXPECT_NEAR(proposal.offset, 120.4, 1.0 / kRate);
  EXPECT_TRUE(proposal.sure) << proposal.why;
}

TEST(VideoSync, AStillVideoIsNotSureAndSaysItShowsNoMotion) {
  const std::vector<Touch> touches = random_touches(300.0, 7);
  const ActivitySeries skin = skin_series(touches, 300.0, 8);
  const ActivitySeries still{0.0, kRate, std::vector<double>(2000, 0.01)};
  const SyncProposal proposal = propose_offset(skin, still, 0.0, 30.0);
  EXPECT_FALSE(proposal.sure);
  EXPECT_NE(proposal.why.find("no motion"), std::string::npos) << proposal.why;
}

TEST(VideoSync, AQuietSkinIsNotSureAndSaysItShowsNoTouches) {
  const ActivitySeries quiet = skin_series({}, 300.0, 9);
  const ActivitySeries motion = motion_series(random_touches(300.0, 10), 0.0, 200.0, 11);
  const SyncProposal proposal = propose_offset(quiet, motion, 0.0, 30.0);
  EXPECT_FALSE(proposal.sure);
  EXPECT_NE(proposal.why.find("no touches"), std::string::npos) << proposal.why;
}

TEST(VideoSync, PeriodicTouchesAreAmbiguousAndNameTwoOffsets) {
  // A touch every 5 s, all alike: every multiple of 5 s fits as well.
  std::vector<Touch> touches;
  for (double t = 2.0; t < 300.0; t += 5.0) touches.push_back({t, t + 1.0, 1.0});
  const ActivitySeries skin = skin_series(touches, 300.0, 12);
  const ActivitySeries motion = motion_series(touches, 10.0, 200.0, 13, 0.0);
  const SyncProposal proposal = propose_offset(skin, motion, 0.0, 30.0);
  EXPECT_FALSE(proposal.sure);
  EXPECT_LT(proposal.confidence, kSureConfidence);
  EXPECT_NE(proposal.why.find("two offsets fit about equally"), std::string::npos) << proposal.why;
}

TEST(VideoSync, MotionUnrelatedToTheTouchesIsNotSure) {
  const ActivitySeries skin = skin_series(random_touches(300.0, 14), 300.0, 15);
  const ActivitySeries motion = motion_series(random_touches(300.0, 16), 0.0, 200.0, 17);
  const SyncProposal proposal = propose_offset(skin, motion, 0.0, 30.0);
  EXPECT_FALSE(proposal.sure) << proposal.offset << " " << proposal.correlation << " "
                              << proposal.confidence;
}

TEST(VideoSync, AShortOverlapIsNotSure) {
  const std::vector<Touch> touches = random_touches(300.0, 18);
  const ActivitySeries skin = skin_series(touches, 300.0, 19);
  // An 8 s clip: every overlap is under 10 s.
  const ActivitySeries motion = motion_series(touches, 100.0, 8.0, 20);
  const SyncProposal proposal = propose_offset(skin, motion, 100.0, 20.0);
  EXPECT_FALSE(proposal.sure);
  EXPECT_NE(proposal.why.find("under 10"), std::string::npos) << proposal.why;
}

//---- Skin activity

Stream eight_channel_stream() {
  // Channel 0 loud (noise sigma 100), channels 1..7 quiet (sigma 1..2); channels 1..3 touched
  // by 60 sigma for 2 s at 20 s; 100 Hz for 60 s starting at 5 s.
  std::mt19937_64 engine(21);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.start_time = 5.0;
  stream.samples = SampleMatrix::Zero(6000, 8);
  for (int c = 0; c < 8; ++c) {
    stream.channels.push_back(std::to_string(c));
    stream.units.push_back("");
  }
  for (int k = 0; k < 6000; ++k) {
    stream.samples(k, 0) = 1000.0f + 100.0f * noise(engine);
    for (int c = 1; c < 8; ++c) {
      const float sigma = 1.0f + static_cast<float>(c) / 7.0f;
      const bool touched = c <= 3 && k >= 1500 && k < 1700;
      stream.samples(k, c) = 500.0f + sigma * (noise(engine) + (touched ? 60.0f : 0.0f));
    }
  }
  return stream;
}

TEST(SkinActivity, QuietChannelsTouchesStandOutOfALoudChannelsNoise) {
  // Unscaled, channel 0's noise alone would change by about 10 x 113 / 3 per step, far above the
  // touch's 3 x 60 x 1.4.
  const MemorySampleSource source(eight_channel_stream());
  const ActivitySeries activity = skin_activity(source, kRate);
  EXPECT_DOUBLE_EQ(activity.start, 5.0);
  EXPECT_DOUBLE_EQ(activity.rate, kRate);
  ASSERT_EQ(activity.values.size(), 600u);
  std::vector<double> sorted = activity.values;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  // The moving mean over 3 samples (a quarter of a 10-sample step, rounded) changes by
  // |x[i] - x[i-3]| / 3 with noise: 1.13 sigma / 3 on average, 10 a step, 8 channels: about 30.
  EXPECT_NEAR(median, 30.0, 6.0);
  // The touch starts at sample 1500 (20 s) and ends at 1700 (22 s): steps 150 and 170.
  EXPECT_GT(activity.values[150], 2.5 * median);
  EXPECT_GT(activity.values[170], 2.5 * median);
  EXPECT_LT(activity.values[160], 1.5 * median);
}

TEST(SkinActivity, StopsWithAnErrorWhenItsJobIsCancelled) {
  const MemorySampleSource source(eight_channel_stream());
  const std::atomic<bool> cancelled{true};
  const CancelScope scope(&cancelled);
  try {
    skin_activity(source, kRate);
    FAIL() << "not cancelled";
  } catch (const Error& error) {
    EXPECT_EQ(error.message(), "cancelled");
  }
}

}  // namespace
}  // namespace tactile

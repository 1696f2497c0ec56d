// adaptive with no parameters on the kinds of signal a lab brings (issue 40): binary sensors,
// noiseless pulses, saturating 8-bit grids, a squeeze that eases and returns; and the fit to
// a few labelled touches (segment/fit.h).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "tactile/error.h"
#include "tactile/segment/adaptive.h"
#include "tactile/segment/fit.h"
#include "tactile/segment/segmenter.h"
#include "touch_scenes.h"

namespace tactile {
namespace {

// A recording of `layout_id` at `rate` Hz, `samples` frames, value(t, channel).
Recording touch_recording(const std::string& layout_id, double rate, int samples,
                          const std::function<float(int, int)>& value) {
  const SkinLayout layout = load_layout(layout_id);
  Recording recording;
  recording.id = "touches";
  recording.layout_id = layout_id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate;
  for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  const int channels = static_cast<int>(stream.channels.size());
  stream.samples.resize(samples, channels);
  for (int t = 0; t < samples; ++t)
    for (int c = 0; c < channels; ++c) stream.samples(t, c) = value(t, c);
  recording.streams = {stream};
  return recording;
}

std::vector<Label> adaptive(const Recording& recording, const std::string& parameters = "") {
  return segment_recording("adaptive", recording, load_layout(recording.layout_id),
                           Parameters::parse(parameters, "test"));
}

TEST(TouchSegmenter, BinarySensorsWithNoNoiseAreSegmentedTouchForTouch) {
  // strip:8 at 50 Hz, 0/1: touch k on sensors k mod 8 (and its neighbour for odd k) from
  // 2 s + 3 s k for 0.4-1.6 s.
  const int touches = 12;
  const auto on = [](int t, int c, int k) {
    const int start = 100 + 150 * k, length = 20 + 10 * (k % 5);
    return t >= start && t < start + length && (c == k % 8 || (k % 2 == 1 && c == (k + 1) % 8));
  };
  const Recording recording =
      touch_recording("strip:8", 50.0, 100 + 150 * touches, [&](int t, int c) {
        for (int k = 0; k < touches; ++k)
          if (on(t, c, k)) return 1.0f;
        return 0.0f;
      });
  const std::vector<Label> labels = adaptive(recording);
  ASSERT_EQ(labels.size(), static_cast<size_t>(touches));
  for (int k = 0; k < touches; ++k) {
    EXPECT_NEAR(labels[static_cast<size_t>(k)].t0, (100 + 150 * k) / 50.0, 1e-9) << k;
    EXPECT_NEAR(labels[static_cast<size_t>(k)].t1, (100 + 150 * k + 20 + 10 * (k % 5)) / 50.0, 1e-9)
        << k;
  }
}

TEST(TouchSegmenter, AReleaseOfAFewFramesInsideABinaryTouchJoinsIt) {
  // 8 touches of 1 s on one sensor, each with a 3-frame release in its middle (a finger lifted
  // and put back): one touch each; join_seconds=0 keeps the contacts apart.
  const Recording recording = touch_recording("strip:8", 50.0, 1000, [](int t, int c) {
    if (c != 2 || t < 50) return 0.0f;
    const int phase = (t - 50) % 120;
    return phase < 50 && !(phase >= 24 && phase < 27) ? 1.0f : 0.0f;
  });
  EXPECT_EQ(adaptive(recording).size(), 8u);
  EXPECT_EQ(adaptive(recording, "join_seconds=0").size(), 16u);
}

TEST(TouchSegmenter, CleanPulsesOnAFourByFourGridAreFound) {
  // Channel i = max(0, sin(t / 7)) x (i mod 5), t the sample index, 50 Hz, 10 s, no noise:
  // each positive half-period is a touch (44 samples a period): found touch for touch, each
  // where the strongest channels pass a fifth of their press.
  const Recording recording = touch_recording("grid:4x4", 50.0, 500, [](int t, int c) {
    return static_cast<float>(std::max(0.0, std::sin(t / 7.0)) * (c % 5));
  });
  const std::vector<Label> labels = adaptive(recording);
  ASSERT_EQ(labels.size(), 12u);
  const double period = 2.0 * M_PI * 7.0;
  for (size_t k = 0; k < labels.size(); ++k) {
    EXPECT_NEAR(labels[k].t0 * 50.0, period * static_cast<double>(k), 8.0) << k;
    if (k + 1 < labels.size()) {
      EXPECT_NEAR(labels[k].t1 * 50.0, period * static_cast<double>(k) + period / 2.0, 8.0) << k;
    }
  }
}

TEST(TouchSegmenter, ASqueezeThatEasesAndReturnsIsOneTouch) {
  // grid:4x4 at 50 Hz, unit noise: 10 squeezes of 3 s on a 2 x 2 patch, 6 s apart; the
  // pressure eases every 0.56 s, for 0.06 s to a tenth of its press (below the band).
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  const Recording recording = touch_recording("grid:4x4", 50.0, 4700, [&](int t, int c) {
    const int row = c / 4, column = c % 4;
    float value = 100.0f + 10.0f * static_cast<float>(c) + noise(random);
    const int local = t - 100;
    if (local >= 0 && local % 450 < 150 && local / 450 < 10 && row >= 1 && row <= 2 &&
        column >= 1 && column <= 2) {
      const double cycle = std::fmod(local % 450 / 50.0, 0.56);
      const double pressure = cycle < 0.06 ? 0.1 : 1.0;
      value += static_cast<float>(200.0 * pressure);
    }
    return value;
  });
  const std::vector<Label> labels = adaptive(recording);
  ASSERT_EQ(labels.size(), 10u);
  for (size_t k = 0; k < labels.size(); ++k) EXPECT_NEAR(labels[k].t0, 2.0 + 9.0 * k + 0.06, 0.05);
}

TEST(TouchSegmenter, ASaturatingEightBitGridWithUnevenIdleLevelsKeepsEachTouch) {
  // grid:4x4 at 15 Hz, integer values 0-255: idle levels 0-40, noise of a count; 10 presses
  // of 1 s on a 2 x 2 patch, saturating, 2 s apart; crosstalk of 30 counts on the others.
  std::mt19937 random(4);
  std::uniform_int_distribution<int> noise(-1, 1);
  const int samples = 15 * 32;
  const Recording recording = touch_recording("grid:4x4", 15.0, samples, [&](int t, int c) {
    const int row = c / 4, column = c % 4;
    double value = (c * 7) % 41 + noise(random);
    const int local = t - 30;
    if (local >= 0 && local % 45 < 15 && local / 45 < 10) {
      const bool patch =
          row >= 1 && row <= 2 && column >= (local / 45) % 3 && column <= (local / 45) % 3 + 1;
      value += patch ? 400.0 : 30.0;
    }
    return static_cast<float>(std::clamp(std::round(value), 0.0, 255.0));
  });
  const std::vector<Label> labels = adaptive(recording);
  ASSERT_EQ(labels.size(), 10u);
  for (size_t k = 0; k < labels.size(); ++k) {
    EXPECT_NEAR(labels[k].t0, (30 + 45 * k) / 15.0, 1.5 / 15.0);
    EXPECT_NEAR(labels[k].t1, (45 + 45 * k) / 15.0, 1.5 / 15.0);
  }
}

TEST(TouchSegmenter, TheScanAndDecideHalvesGiveWhatOneRunGives) {
  const Recording recording = touch_recording("strip:8", 50.0, 1000, [](int t, int c) {
    return (c == 1 || c == 2) && t % 100 < 40 + (t / 100) % 3 ? 1.0f : 0.0f;
  });
  const AdaptiveSegmenter segmenter(recording, load_layout("strip:8"), Parameters{});
  for (const char* fast : {"", "share=0.4,taxels=3", "join_seconds=0.8"}) {
    const std::vector<Label> once = adaptive(recording, fast);
    const std::vector<Label> halves = segmenter.segments(Parameters::parse(fast, "test"));
    ASSERT_EQ(once.size(), halves.size()) << fast;
    for (size_t k = 0; k < once.size(); ++k) {
      EXPECT_DOUBLE_EQ(once[k].t0, halves[k].t0);
      EXPECT_DOUBLE_EQ(once[k].t1, halves[k].t1);
    }
  }
  EXPECT_THROW(segmenter.segments(Parameters::parse("margin=3", "test")), Error);
  EXPECT_THROW(
      AdaptiveSegmenter(recording, load_layout("strip:8"), Parameters::parse("share=0.3", "test")),
      Error);
}

Recording double_taps(int pairs) { return test::double_tap_recording("touches", pairs); }
std::vector<Label> double_tap_labels(int pairs) {
  return test::double_tap_touches("touches", pairs);
}

TEST(SegmenterFit, LearnsThatAPersonLabelsDoubleTapsAsOneTouch) {
  const Recording recording = double_taps(9);
  const SkinLayout layout = load_layout("strip:8");
  EXPECT_EQ(adaptive(recording).size(), 18u);  // each tap its own touch by default
  const SegmenterFit fit = fit_segmenter({{&recording, &layout, double_tap_labels(9)}});
  EXPECT_EQ(fit.folds, "by time blocks (3 folds)");
  EXPECT_EQ(fit.touches, 9);
  EXPECT_DOUBLE_EQ(fit.held_out.events.f1(), 1.0);
  EXPECT_DOUBLE_EQ(fit.fitted.events.f1(), 1.0);
  const std::vector<Label> fitted = adaptive(recording, fit.params);
  EXPECT_EQ(fitted.size(), 9u) << fit.params;
  EXPECT_NE(fit_report(fit).find(fit.params), std::string::npos);
}

TEST(SegmenterFit, ScoresOnlyTheLabelledStretch) {
  // Five of nine pairs labelled: the four after them are not false alarms.
  const Recording recording = double_taps(9);
  const SkinLayout layout = load_layout("strip:8");
  std::vector<Label> five = double_tap_labels(5);
  const SegmenterFit fit = fit_segmenter({{&recording, &layout, five}});
  EXPECT_EQ(fit.fitted.segments, 5);
  EXPECT_DOUBLE_EQ(fit.fitted.events.f1(), 1.0);
}

TEST(SegmenterFit, RefusesFewerThanThreeTouchesAndLabelsOutsideTheRecording) {
  const Recording recording = double_taps(3);
  const SkinLayout layout = load_layout("strip:8");
  std::vector<Label> two = double_tap_labels(2);
  try {
    fit_segmenter({{&recording, &layout, two}});
    FAIL() << "two touches were accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("at least three labelled touches, has 2"),
              std::string::npos)
        << error.what();
  }
  std::vector<Label> outside = double_tap_labels(3);
  outside.back().t1 = 100.0;
  try {
    fit_segmenter({{&recording, &layout, outside}});
    FAIL() << "a label outside the recording was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("outside the recording"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace tactile

// Flux sensor excitation segmenter and features (spec §5.5-5.7). Expected numbers from
// TEST_VECTORS.md X2.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/dsp/flux.h"
#include "tactile/error.h"
#include "tactile/features/flux.h"
#include "tactile/segment/excitation.h"

namespace tactile {
namespace {

// TV X2 at fs = 100 Hz: a ramp to 0.5, then a slow relaxation towards 0.1.
Eigen::VectorXd x2_signal() {
  Eigen::VectorXd e(700);
  for (int n = 0; n < 700; ++n) {
    if (n < 50)
      e[n] = 0.0;
    else if (n < 59)
      e[n] = 0.05 * (n - 49);
    else
      e[n] = 0.1 + 0.4 * std::exp(-(n - 59) / 150.0);
  }
  return e;
}

TEST(FluxExcitation, OnsetIsTheFirstSampleStrictlyAboveTheThreshold) {
  const Eigen::MatrixXd e = x2_signal();
  EXPECT_NEAR(e(62, 0), 0.492079, 1e-6);
  EXPECT_EQ(excitation_onsets(e, 1, 100.0, dsp::FluxOptions{}), (std::vector<int64_t>{51}));
}

TEST(FluxFeatures, MatchTheSpecVectorOnItsToyChannel) {
  const Eigen::VectorXd e = x2_signal();
  const int64_t window = dsp::samples_of(5.0, 100.0, 1);
  ASSERT_EQ(window, 500);
  const auto features =
      flux_channel_features({e.data() + 51, static_cast<size_t>(window)}, 100.0, 50);
  const double expected[6] = {0.5, 5, -0.26578, 1.09335, 0.117923, 0.08};
  for (int feature = 0; feature < 6; ++feature)
    EXPECT_NEAR(features[feature], expected[feature],
                1e-5 * std::max(1.0, std::abs(expected[feature])))
        << feature;
}

TEST(FluxFeatures, ConstantAndSingleSampleWindowsHaveZeroDerivativesAndTime) {
  const double constant[4] = {0.2, 0.2, 0.2, 0.2};
  const auto flat = flux_channel_features(constant, 1000.0, 500);
  EXPECT_DOUBLE_EQ(flat[0], 0.2);
  EXPECT_EQ(flat[1], 0.0);
  EXPECT_EQ(flat[2], 0.0);
  EXPECT_DOUBLE_EQ(flat[3], 0.8 / 1000.0);
  EXPECT_DOUBLE_EQ(flat[4], 0.2);  // window shorter than 0.5 s: mean of all of it
  EXPECT_EQ(flat[5], 0.0);
  const double single[1] = {0.3};
  const auto one = flux_channel_features(single, 1000.0, 500);
  EXPECT_EQ(one[1], 0.0);
  EXPECT_EQ(one[2], 0.0);
  EXPECT_DOUBLE_EQ(one[4], 0.3);
}

//---- Segmenter and extractor on recordings

// Raw counts at 1 kHz, x1..x4 and y1..y4 at 500; presses raise the named top channel.
struct Press {
  int channel;
  int64_t first;
  int64_t count;
  float rise;  // counts added
};

Recording raw_recording(int64_t samples, const std::vector<Press>& presses) {
  Recording recording;
  recording.id = "flux-run";
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 1000.0;
  skin.channels = {"x1", "x2", "x3", "x4", "y1", "y2", "y3", "y4"};
  skin.units.assign(8, "counts");
  skin.samples = SampleMatrix::Constant(samples, 8, 500.0f);
  for (const Press& press : presses)
    skin.samples.col(press.channel).segment(press.first, press.count).array() += press.rise;
  recording.streams.push_back(skin);
  return recording;
}

TEST(ExcitationSegmenter, OneFiveSecondSegmentPerPressCutAtTheEnd) {
  const SkinLayout layout = load_layout("flux");
  // Presses of +20 % on x1 at 1 s and on x3 at 12 s, and one at 20 s that the recording cuts.
  const Recording recording = raw_recording(
      22000, {{0, 1000, 800, 100.0f}, {2, 12000, 800, 100.0f}, {1, 20000, 500, 100.0f}});
  const std::vector<Label> labels = segment_excitation(recording, layout, {});
  ASSERT_EQ(labels.size(), 3u);
  // The moving average reaches +6 % on the third raised sample (the +5 % on the second is
  // not above 5 %): onset 1002 -> 1.002 s.
  EXPECT_NEAR(labels[0].t0, 1.002, 1e-9);
  EXPECT_NEAR(labels[0].t1, 6.002, 1e-9);
  EXPECT_NEAR(labels[1].t0, 12.002, 1e-9);
  EXPECT_NEAR(labels[2].t0, 20.002, 1e-9);
  EXPECT_NEAR(labels[2].t1, 22.0, 1e-9);
  EXPECT_EQ(labels[0].class_name, "");
  EXPECT_EQ(labels[0].source, LabelSource::kSegmenter);
}

TEST(ExcitationSegmenter, NoNewOnsetInsideTheWindow) {
  // Two presses 2 s apart: the second falls inside the first one's 5 s window.
  const Recording recording =
      raw_recording(10000, {{0, 1000, 300, 100.0f}, {3, 3000, 300, 100.0f}});
  EXPECT_EQ(segment_excitation(recording, load_layout("flux"), {}).size(), 1u);
}

TEST(ExcitationSegmenter, BottomLayerAloneIsNoExcitation) {
  const Recording recording = raw_recording(5000, {{5, 1000, 300, 200.0f}});
  EXPECT_TRUE(segment_excitation(recording, load_layout("flux"), {}).empty());
}

TEST(FluxExtractor, ThirtyColumnsChannelMajor) {
  const auto columns = make_flux_extractor({})->columns(load_layout("flux"));
  ASSERT_EQ(columns.size(), 30u);
  EXPECT_EQ(columns[0].name, "x1.max_value");
  EXPECT_EQ(columns[6 + 1].name, "x2.max_derivative");
  EXPECT_EQ(columns[24 + 5].name, "x_sum.time_of_max");
}

TEST(FluxExtractor, DescribesThePressOfALabelledSegment) {
  const SkinLayout layout = load_layout("flux");
  const auto extractor = make_flux_extractor({});
  // x2 held at +20 % for 2 s from 1 s.
  const Recording processed =
      extractor->preprocess(raw_recording(8000, {{1, 1000, 2000, 100.0f}}), layout);
  Label segment;
  segment.t0 = 0.5;
  segment.t1 = 3.5;
  const FeatureResult result = extractor->extract({processed, layout, segment});
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  ASSERT_EQ(result.values.size(), 30u);
  const double* x1 = &result.values[0];
  const double* x2 = &result.values[6];
  const double* sum = &result.values[24];
  EXPECT_NEAR(x2[0], 0.2, 1e-6);             // max value
  EXPECT_NEAR(x2[1], 0.02 * 1000.0, 1e-3);   // one tenth of the step per sample, times fs
  EXPECT_NEAR(x2[2], -0.02 * 1000.0, 1e-3);  // the release, inside the 5 s window
  // Rise 0.06..0.18 (0.84), 1991 samples at 0.2 (398.2), release 0.18..0.02 (0.9), over fs.
  EXPECT_NEAR(x2[3], 399.94 / 1000.0, 1e-6);
  EXPECT_NEAR(x2[4], 0.0, 1e-6);    // settled back to baseline
  EXPECT_NEAR(x2[5], 0.007, 1e-9);  // full level at 1009, 7 samples after the onset
  for (int feature = 0; feature < 6; ++feature) {
    EXPECT_EQ(x1[feature], 0.0) << feature;
    EXPECT_NEAR(sum[feature], x2[feature], 1e-6) << feature;
  }
}

TEST(FluxExtractor, SegmentWithoutExcitationIsSkipped) {
  const SkinLayout layout = load_layout("flux");
  const auto extractor = make_flux_extractor({});
  const Recording processed = extractor->preprocess(raw_recording(3000, {}), layout);
  Label segment;
  segment.t0 = 0.0;
  segment.t1 = 3.0;
  const FeatureResult result = extractor->extract({processed, layout, segment});
  EXPECT_TRUE(result.values.empty());
  EXPECT_NE(result.skip_reason.find("no excitation"), std::string::npos) << result.skip_reason;
}

TEST(FluxExtractor, NaNInTheWindowIsSkippedNamingChannelAndTime) {
  const SkinLayout layout = load_layout("flux");
  const auto extractor = make_flux_extractor({});
  Recording raw = raw_recording(8000, {{1, 1000, 2000, 100.0f}});
  raw.streams[0].samples(2500, 3) = std::numeric_limits<float>::quiet_NaN();
  const Recording processed = extractor->preprocess(raw, layout);
  Label segment;
  segment.t0 = 0.5;
  segment.t1 = 3.5;
  const FeatureResult result = extractor->extract({processed, layout, segment});
  EXPECT_TRUE(result.values.empty());
  EXPECT_NE(result.skip_reason.find("x4"), std::string::npos) << result.skip_reason;
  EXPECT_NE(result.skip_reason.find("t=2.5"), std::string::npos) << result.skip_reason;
}

TEST(FluxExtractor, NeedsItsPreprocessing) {
  const SkinLayout layout = load_layout("flux");
  const Recording raw = raw_recording(100, {});
  Label segment;
  segment.t1 = 0.1;
  EXPECT_THROW(make_flux_extractor({})->extract({raw, layout, segment}), Error);
}

TEST(FluxExtractor, UnknownParameterIsRejected) {
  EXPECT_THROW(make_flux_extractor(Parameters::parse("window=5", "--params")), Error);
}

}  // namespace
}  // namespace tactile

// The raw-sample and rocket pipelines (issue 26) on hand-built strip recordings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "tactile/error.h"
#include "tactile/features/raw.h"
#include "tactile/features/rocket.h"

namespace tactile {
namespace {

// A strip recording at 100 Hz, every channel resting at `rest`.
Recording raw_test_recording(const SkinLayout& layout, int64_t samples, float rest) {
  Recording recording;
  recording.id = "raw-hand-built";
  recording.layout_id = layout.id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples =
      SampleMatrix::Constant(samples, static_cast<int64_t>(layout.channels.size()), rest);
  recording.streams.push_back(std::move(stream));
  return recording;
}

Label raw_test_segment(double t0, double t1) {
  Label label;
  label.t0 = t0;
  label.t1 = t1;
  return label;
}

FeatureResult raw_test_run(const FeatureExtractor& extractor, const Recording& recording,
                           const SkinLayout& layout, const Label& label) {
  const Recording prepared = extractor.preprocess(recording, layout);
  return extractor.extract(SegmentInput{prepared, layout, label});
}

// Channel 0 rises 0, 1, ..., 19 above rest 5 over samples 40..59 (t = 0.40..0.59 s).
Recording raw_test_ramp(const SkinLayout& layout) {
  Recording recording = raw_test_recording(layout, 100, 5.0f);
  for (int64_t k = 0; k < 20; ++k)
    recording.streams[0].samples(40 + k, 0) = 5.0f + static_cast<float>(k);
  return recording;
}

//---- raw

TEST(RawFeatures, ResamplingARampIsExactAtEveryPoint) {
  const std::vector<double> ramp = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<double> coarse = resample_linear(ramp, 4);
  ASSERT_EQ(coarse.size(), 4u);
  for (size_t k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(coarse[k], 3.0 * static_cast<double>(k));
  const std::vector<double> fine = resample_linear(ramp, 19);
  ASSERT_EQ(fine.size(), 19u);
  for (size_t k = 0; k < 19; ++k) EXPECT_NEAR(fine[k], 0.5 * static_cast<double>(k), 1e-12);
  EXPECT_EQ(resample_linear(std::vector<double>{7.0}, 3), (std::vector<double>{7.0, 7.0, 7.0}));
}

TEST(RawFeatures, ColumnsAreEveryChannelsPointsInOrderAndEveryValueIsFinite) {
  const SkinLayout layout = make_strip_layout(3);
  Parameters parameters = Parameters::parse("samples=8", "--params");
  const auto extractor = make_raw_extractor(parameters);
  const std::vector<FeatureColumn> columns = extractor->columns(layout);
  ASSERT_EQ(columns.size(), 24u);
  EXPECT_EQ(columns[0].name, layout.channels[0].name + ".s0");
  EXPECT_EQ(columns[9].name, layout.channels[1].name + ".s1");
  const FeatureResult result =
      raw_test_run(*extractor, raw_test_ramp(layout), layout, raw_test_segment(0.3, 0.7));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  ASSERT_EQ(result.values.size(), 24u);
  for (double value : result.values) EXPECT_TRUE(std::isfinite(value));
}

TEST(RawFeatures, RestIsSubtractedAndEachScaleIsItsDocumentedQuantile) {
  const SkinLayout layout = make_strip_layout(2);
  const Recording recording = raw_test_ramp(layout);
  const Label segment = raw_test_segment(0.40, 0.60);
  const auto point = [&](const std::string& parameters, size_t channel, size_t k) {
    const auto extractor =
        make_raw_extractor(Parameters::parse("samples=20," + parameters, "--params"));
    const FeatureResult result = raw_test_run(*extractor, recording, layout, segment);
    EXPECT_TRUE(result.skip_reason.empty()) << result.skip_reason;
    return result.values.at(channel * 20 + k);
  };
  EXPECT_DOUBLE_EQ(point("scale=none", 0, 7), 7.0);
  EXPECT_DOUBLE_EQ(point("scale=none,baseline=none", 0, 7), 12.0);
  // global: the 99th percentile (floor index 197 of 200) of |x - rest| over both channels:
  // 181 zeros, then 1..19, so 17.
  EXPECT_NEAR(point("scale=global", 0, 7), 7.0 / 17.0, 1e-6);
  // channel: index 98 of channel 0's 100 values (81 zeros, then 1..19) is 18; a flat
  // channel keeps its units.
  EXPECT_NEAR(point("scale=channel", 0, 7), 7.0 / 18.0, 1e-6);
  EXPECT_DOUBLE_EQ(point("scale=channel", 1, 7), 0.0);
}

// Channels of two modalities do not share a global factor; a layout channel missing from the
// stream (as flux's virtual sums are) reads as 0, and a stream with none of them is an error.
TEST(RawFeatures, GlobalScaleIsPerModalityAndMissingChannelsReadAsZero) {
  SkinLayout layout = make_strip_layout(2);
  layout.channels[1].modality = "temperature";
  layout.modalities.push_back("temperature");
  Recording recording = raw_test_ramp(layout);
  for (int64_t k = 0; k < 100; ++k)
    recording.streams[0].samples(k, 1) = 100.0f + static_cast<float>(k % 2);
  const auto extractor = make_raw_extractor(Parameters::parse("samples=20", "--params"));
  const FeatureResult result =
      raw_test_run(*extractor, recording, layout, raw_test_segment(0.40, 0.60));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  EXPECT_NEAR(result.values.at(7), 7.0 / 18.0, 1e-6);  // channel 0's own 99th percentile
  // The stream holds the layout's first channel only.
  Stream& stream = recording.streams[0];
  stream.samples = SampleMatrix(stream.samples.leftCols(1));
  stream.channels.resize(1);
  stream.units.resize(1);
  const FeatureResult missing =
      raw_test_run(*extractor, recording, layout, raw_test_segment(0.40, 0.60));
  ASSERT_TRUE(missing.skip_reason.empty()) << missing.skip_reason;
  EXPECT_NEAR(missing.values.at(7), 7.0 / 18.0, 1e-6);
  for (size_t k = 20; k < 40; ++k) EXPECT_EQ(missing.values.at(k), 0.0);
  stream.channels[0] = "neither";
  EXPECT_THROW(raw_test_run(*extractor, recording, layout, raw_test_segment(0.40, 0.60)), Error);
}

TEST(RawFeatures, BadParametersAreNamed) {
  const auto message = [](const std::string& text) {
    try {
      make_raw_extractor(Parameters::parse(text, "--params"));
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("samples=1").find("samples=1"), std::string::npos);
  EXPECT_NE(message("baseline=mean").find("baseline=mean"), std::string::npos);
  EXPECT_NE(message("scale=feature").find("classifier"), std::string::npos);
  EXPECT_NE(message("scale=row").find("scale=row"), std::string::npos);
  EXPECT_NE(message("sample=8").find("sample"), std::string::npos);
  const auto extractor = make_raw_extractor(Parameters::parse("modality=force", "--params"));
  EXPECT_THROW(extractor->columns(make_strip_layout(2)), Error);
}

//---- rocket

TEST(RocketFeatures, TheKernelsAreThe84TriplesOfPositionsInOrder) {
  const std::vector<std::array<int, 3>> kernels = minirocket_kernels();
  ASSERT_EQ(kernels.size(), 84u);
  EXPECT_EQ(kernels.front(), (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(kernels[1], (std::array<int, 3>{0, 1, 3}));
  EXPECT_EQ(kernels.back(), (std::array<int, 3>{6, 7, 8}));
  std::set<std::array<int, 3>> distinct(kernels.begin(), kernels.end());
  EXPECT_EQ(distinct.size(), 84u);
  for (const auto& kernel : kernels) {
    EXPECT_LT(kernel[0], kernel[1]);
    EXPECT_LT(kernel[1], kernel[2]);
    EXPECT_LE(kernel[2], 8);
  }
}

TEST(RocketFeatures, DilationsGrowExponentiallyUpToAnEighthOfTheLength) {
  const RocketPlan plan = plan_rocket(64, 3, 10000, 1, 16);
  EXPECT_EQ(plan.feature_count(), 9996);
  EXPECT_EQ(plan.dilations.front(), 1);
  EXPECT_LE(plan.dilations.back(), 63 / 8);
  EXPECT_GE(plan.dilations.back(), 4);
  int64_t per_kernel = 0;
  for (int count : plan.features_per_dilation) per_kernel += count;
  EXPECT_EQ(per_kernel, 119);
  for (const std::vector<int>& set : plan.channel_sets) {
    ASSERT_FALSE(set.empty());
    EXPECT_LE(set.size(), 3u);
    EXPECT_TRUE(std::is_sorted(set.begin(), set.end()));
    EXPECT_EQ(std::set<int>(set.begin(), set.end()).size(), set.size());
  }
  EXPECT_EQ(plan_rocket(9, 1, 84, 1, 16).dilations, std::vector<int>{1});
  EXPECT_THROW(plan_rocket(8, 1, 84, 1, 16), Error);
  EXPECT_THROW(plan_rocket(64, 1, 83, 1, 16), Error);
}

// An impulse at the centre of 9 samples: kernel k's output at t is its weight 8 - t.
TEST(RocketFeatures, PpvOfAnImpulseIsCountedByHand) {
  const RocketPlan plan = plan_rocket(9, 1, 84, 1, 1);
  ASSERT_EQ(plan.feature_count(), 84);
  Eigen::MatrixXf impulse = Eigen::MatrixXf::Zero(9, 1);
  impulse(4, 0) = 1.0f;
  const std::vector<float> biases(84, -0.5f);
  std::vector<double> features(84);
  rocket_transform(plan, impulse, biases, features);
  // Kernel 0 (2s at 0, 1, 2), zero-padded: outputs -1 x6, 2 x3 -> 3 of 9 above -0.5.
  EXPECT_DOUBLE_EQ(features[0], 3.0 / 9.0);
  // Kernel 1 (0, 1, 3), central part only (t = 4): weight 4 is -1.
  EXPECT_DOUBLE_EQ(features[1], 0.0);
  // Kernel 2 (0, 1, 4), zero-padded: weights 0, 1, 4 are 2 -> t = 8, 7, 4.
  EXPECT_DOUBLE_EQ(features[2], 3.0 / 9.0);
  // Kernel 3 (0, 1, 5), central: weight 4 is -1; kernel 13 (0, 3, 4), central: weight 4 is 2.
  EXPECT_DOUBLE_EQ(features[3], 0.0);
  EXPECT_DOUBLE_EQ(features[13], 1.0);
}

// The alpha/gamma sums give what the kernels' direct convolution gives, at every dilation.
TEST(RocketFeatures, TheTransformAgreesWithDirectConvolution) {
  const int64_t length = 40;
  const RocketPlan plan = plan_rocket(length, 1, 84 * 12, 7, 1);
  std::mt19937 generator(3);
  std::normal_distribution<float> noise;
  Eigen::MatrixXf series(length, 1);
  for (int64_t t = 0; t < length; ++t) series(t, 0) = noise(generator);
  std::vector<float> biases(static_cast<size_t>(plan.feature_count()));
  for (size_t k = 0; k < biases.size(); ++k) biases[k] = 0.3f * static_cast<float>(k % 7) - 0.9f;
  std::vector<double> features(biases.size());
  rocket_transform(plan, series, biases, features);
  const std::vector<double> values(series.data(), series.data() + length);
  size_t feature = 0;
  for (size_t d = 0; d < plan.dilations.size(); ++d)
    for (int kernel = 0; kernel < 84; ++kernel) {
      const std::vector<double> output = minirocket_convolution(values, kernel, plan.dilations[d]);
      const bool padded = (static_cast<int>(d % 2) + kernel) % 2 == 0;
      const size_t padding = padded ? 0 : static_cast<size_t>(4 * plan.dilations[d]);
      for (int index = 0; index < plan.features_per_dilation[d]; ++index, ++feature) {
        int positive = 0;
        for (size_t t = padding; t < output.size() - padding; ++t)
          positive += output[t] > biases[feature] ? 1 : 0;
        EXPECT_NEAR(features[feature], positive / static_cast<double>(output.size() - 2 * padding),
                    1e-12)
            << "kernel " << kernel << " dilation " << plan.dilations[d];
      }
    }
  EXPECT_EQ(feature, features.size());
}

TEST(RocketFeatures, SameSeedSameRowOtherSeedOtherRowAndOneValuePerColumn) {
  const SkinLayout layout = make_strip_layout(4);
  Recording recording = raw_test_ramp(layout);
  for (int64_t k = 0; k < 100; ++k)
    recording.streams[0].samples(k, 2) =
        5.0f + static_cast<float>(std::sin(0.3 * static_cast<double>(k)));
  const Label segment = raw_test_segment(0.30, 0.70);
  const auto row = [&](const std::string& parameters) {
    const auto extractor = make_rocket_extractor(Parameters::parse(parameters, "--params"));
    const FeatureResult result = raw_test_run(*extractor, recording, layout, segment);
    EXPECT_TRUE(result.skip_reason.empty()) << result.skip_reason;
    EXPECT_EQ(result.values.size(), extractor->columns(layout).size());
    return result.values;
  };
  const std::vector<double> first = row("features=1000,seed=4");
  EXPECT_EQ(first.size(), 84u * 11);
  for (double value : first) {
    EXPECT_GE(value, 0.0);
    EXPECT_LE(value, 1.0);
  }
  EXPECT_EQ(row("features=1000,seed=4"), first);
  EXPECT_NE(row("features=1000,seed=5"), first);
  EXPECT_EQ(row("").size(), 9996u);
  // Without the preprocessing there are no biases: the segment is skipped, saying why.
  const auto extractor = make_rocket_extractor({});
  EXPECT_FALSE(extractor->extract(SegmentInput{recording, layout, segment}).skip_reason.empty());
  EXPECT_THROW(make_rocket_extractor(Parameters::parse("features=50", "--params")), Error);
  EXPECT_THROW(make_rocket_extractor(Parameters::parse("samples=8", "--params")), Error);
}

// A series from a formula (no library generator), the same on every platform.
Eigen::MatrixXf rocket_stored_series(int64_t length, int64_t channels, double phase) {
  Eigen::MatrixXf series(length, channels);
  for (int64_t t = 0; t < length; ++t)
    for (int64_t c = 0; c < channels; ++c)
      series(t, c) = static_cast<float>(std::sin(0.37 * static_cast<double>(t * (c + 1)) + phase) +
                                        0.1 * static_cast<double>((t * 7 + c * 3) % 11) - 0.5);
  return series;
}

// FNV-1a over the features' bits: any change of any feature changes it.
uint64_t rocket_stored_hash(const std::vector<double>& features) {
  uint64_t hash = 14695981039346656037ull;
  for (double value : features) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) {
      hash ^= (bits >> (8 * byte)) & 0xffu;
      hash *= 1099511628211ull;
    }
  }
  return hash;
}

// Stored outputs of the transform (computed before its speed-up of issue 26): a faster
// transform must give the same features to the last bit, on one channel and on several, at
// lengths that are and are not multiples of a vector width.
TEST(RocketFeatures, TransformGivesTheStoredFeaturesBitForBit) {
  struct Case {
    int64_t length, channels, features;
    uint64_t hash;
    double sum;
  };
  const Case cases[] = {
      {64, 1, 10000, 4499109686123017204ull, 4988.1324404761936},
      {64, 3, 10000, 13879939409898969231ull, 5014.6904761904734},
      {37, 5, 2000, 14657207450017863641ull, 973.22880561501177},
      {9, 1, 84, 2753016954947004400ull, 40.444444444444436},
      {100, 12, 10000, 3670866819462143039ull, 5039.1723505769714},
  };
  for (const Case& c : cases) {
    const RocketPlan plan = plan_rocket(c.length, c.channels, c.features, 3, 2);
    const std::vector<float> biases =
        rocket_biases(plan, {rocket_stored_series(c.length, c.channels, 0.5),
                             rocket_stored_series(c.length, c.channels, 1.7)});
    std::vector<double> features(static_cast<size_t>(plan.feature_count()));
    rocket_transform(plan, rocket_stored_series(c.length, c.channels, 0.0), biases, features);
    double sum = 0.0;
    for (double value : features) sum += value;
    EXPECT_EQ(rocket_stored_hash(features), c.hash) << c.length << " x " << c.channels;
    EXPECT_EQ(sum, c.sum) << c.length << " x " << c.channels;
  }
}

//---- the summary series (series=summary, rocket's series=auto on large maps)

// A 9 x 9 grid (81 taxels, above generic's 64) with one sliding touch: channel `a` at 2, 1
// then 0, channel `b` (its right neighbour) at 0, 1 then 2, in samples 1..3 of 5.
Eigen::MatrixXd raw_test_slide(int a, int b) {
  Eigen::MatrixXd points = Eigen::MatrixXd::Zero(5, 81);
  points(1, a) = 2.0;
  points(2, a) = 1.0;
  points(2, b) = 1.0;
  points(3, b) = 2.0;
  return points;
}

TEST(RawSummary, SeriesAreNamedByModalityGroupKindAndRank) {
  const SkinLayout layout = make_grid_layout(9, 9);
  std::vector<int> channels(81);
  for (int k = 0; k < 81; ++k) channels[static_cast<size_t>(k)] = k;
  const RawSummaryPlan plan = plan_raw_summary(layout, channels);
  const std::vector<std::string> expected = {
      "value.total", "value.peak",  "value.active", "value.centroid_x", "value.centroid_y",
      "value.row.1", "value.row.2", "value.row.3",  "value.row0",       "value.row1",
      "value.row2",  "value.row3",  "value.row4",   "value.row5",       "value.row6",
      "value.row7",  "value.row8",  "value.top.1",  "value.top.2",      "value.top.3",
      "value.top.4", "value.top.5", "value.top.6",  "value.top.7",      "value.top.8"};
  EXPECT_EQ(plan.names, expected);
  EXPECT_EQ(plan.descriptions.size(), expected.size());
}

// Every series but the rows' own sums (which say where) is the same wherever the touch lands.
TEST(RawSummary, ValuesAreCountedByHandAndTheSameWhereverTheTouchLands) {
  const SkinLayout layout = make_grid_layout(9, 9);
  std::vector<int> channels(81);
  for (int k = 0; k < 81; ++k) channels[static_cast<size_t>(k)] = k;
  const RawSummaryPlan plan = plan_raw_summary(layout, channels);
  // Row 2, columns 3 -> 4; and row 6, columns 1 -> 2.
  const Eigen::MatrixXd here = raw_summary(plan, raw_test_slide(2 * 9 + 3, 2 * 9 + 4));
  const Eigen::MatrixXd there = raw_summary(plan, raw_test_slide(6 * 9 + 1, 6 * 9 + 2));
  ASSERT_EQ(here.rows(), 5);
  ASSERT_EQ(here.cols(), 25);
  EXPECT_TRUE(here.leftCols(8).isApprox(there.leftCols(8))) << here << "\n\n" << there;
  EXPECT_TRUE(here.rightCols(8).isApprox(there.rightCols(8))) << here << "\n\n" << there;
  for (int row = 0; row < 9; ++row) {
    const Eigen::VectorXd expected =
        row == 2 ? Eigen::VectorXd(here.col(0)) : Eigen::VectorXd::Zero(5);
    EXPECT_EQ(Eigen::VectorXd(here.col(8 + row)), expected) << "row " << row;
    EXPECT_EQ(Eigen::VectorXd(there.col(8 + row)),
              row == 6 ? Eigen::VectorXd(there.col(0)) : Eigen::VectorXd::Zero(5))
        << "row " << row;
  }
  const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(5);
  EXPECT_EQ(Eigen::VectorXd(here.col(0)), (Eigen::VectorXd(5) << 0, 2, 2, 2, 0).finished());
  EXPECT_EQ(Eigen::VectorXd(here.col(1)), (Eigen::VectorXd(5) << 0, 2, 1, 2, 0).finished());
  // Active above 0.2 of the largest excursion (0.4): one, two, one of 81 channels.
  EXPECT_NEAR(here(2, 2), 2.0 / 81.0, 1e-12);
  EXPECT_NEAR(here(1, 2), 1.0 / 81.0, 1e-12);
  // The centre moves 10 mm (one pitch) along x: -5, 0, +5 around its mean; 0 without contact.
  EXPECT_NEAR(here(1, 3), -5.0, 1e-9);
  EXPECT_NEAR(here(2, 3), 0.0, 1e-9);
  EXPECT_NEAR(here(3, 3), 5.0, 1e-9);
  EXPECT_EQ(here(0, 3), 0.0);
  EXPECT_EQ(Eigen::VectorXd(here.col(4)), zeros);
  // The touched row first, with the whole total; the other rows hold nothing.
  EXPECT_EQ(Eigen::VectorXd(here.col(5)), Eigen::VectorXd(here.col(0)));
  EXPECT_EQ(Eigen::VectorXd(here.col(6)), zeros);
  // Both channels carry energy 5; the tie keeps layout order: a, then b.
  EXPECT_EQ(Eigen::VectorXd(here.col(17)), (Eigen::VectorXd(5) << 0, 2, 1, 0, 0).finished());
  EXPECT_EQ(Eigen::VectorXd(here.col(18)), (Eigen::VectorXd(5) << 0, 0, 1, 2, 0).finished());
  EXPECT_EQ(Eigen::VectorXd(here.col(19)), zeros);
}

TEST(RawSummary, AutoReadsTheSummaryAboveSixtyFourTaxelsAndRawKeepsChannels) {
  const SkinLayout large = make_grid_layout(9, 9);
  const SkinLayout small = make_grid_layout(8, 8);
  const auto rocket = make_rocket_extractor(Parameters::parse("features=840", "--params"));
  EXPECT_EQ(rocket->columns(large).size(), 840u);
  EXPECT_NE(rocket->columns(large).front().description.find("value."), std::string::npos);
  EXPECT_EQ(rocket->columns(small).front().description.find("value."), std::string::npos);
  const auto forced =
      make_rocket_extractor(Parameters::parse("features=840,series=channels", "--params"));
  EXPECT_EQ(forced->columns(large).front().description.find("value."), std::string::npos);
  // raw keeps every channel unless asked (the raw-sample baseline of issue 26).
  EXPECT_EQ(make_raw_extractor(Parameters::parse("samples=4", "--params"))->columns(large).size(),
            81u * 4);
  const auto summary =
      make_raw_extractor(Parameters::parse("samples=4,series=summary", "--params"));
  EXPECT_EQ(summary->columns(large).size(), 25u * 4);
  EXPECT_EQ(summary->columns(large).front().name, "value.total.s0");
  EXPECT_EQ(summary->columns(small).size(), 24u * 4);
  try {
    make_raw_extractor(Parameters::parse("series=sheets", "--params"));
    ADD_FAILURE() << "series=sheets accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("series=sheets"), std::string::npos);
  }
}

// End to end: two touches of one recording in different rows give the same row of features
// when the layout has too many rows (30) for their sums to be series of their own.
TEST(RawSummary, RawAndRocketRowsDoNotDependOnWhereTheTouchLanded) {
  const SkinLayout layout = make_grid_layout(30, 3);
  Recording recording = raw_test_recording(layout, 100, 3.0f);
  for (int64_t k = 0; k < 10; ++k) {
    const auto rising = static_cast<float>(k) / 9.0f;
    recording.streams[0].samples(20 + k, 5 * 3 + 0) = 3.0f + 4.0f * (1.0f - rising);
    recording.streams[0].samples(20 + k, 5 * 3 + 1) = 3.0f + 4.0f * rising;
    recording.streams[0].samples(60 + k, 20 * 3 + 1) = 3.0f + 4.0f * (1.0f - rising);
    recording.streams[0].samples(60 + k, 20 * 3 + 2) = 3.0f + 4.0f * rising;
  }
  for (const std::string pipeline : {"raw", "rocket"}) {
    SCOPED_TRACE(pipeline);
    const auto extractor =
        pipeline == "raw"
            ? make_raw_extractor(Parameters::parse("samples=16,series=summary", "--params"))
            : make_rocket_extractor(Parameters::parse("features=840", "--params"));
    const FeatureResult first =
        raw_test_run(*extractor, recording, layout, raw_test_segment(0.15, 0.35));
    const FeatureResult second =
        raw_test_run(*extractor, recording, layout, raw_test_segment(0.55, 0.75));
    ASSERT_TRUE(first.skip_reason.empty()) << first.skip_reason;
    ASSERT_EQ(first.values.size(), extractor->columns(layout).size());
    ASSERT_EQ(second.values.size(), first.values.size());
    for (size_t k = 0; k < first.values.size(); ++k)
      EXPECT_NEAR(first.values[k], second.values[k], 1e-9) << "column " << k;
    EXPECT_NE(*std::max_element(first.values.begin(), first.values.end()), 0.0);
  }
}

}  // namespace
}  // namespace tactile

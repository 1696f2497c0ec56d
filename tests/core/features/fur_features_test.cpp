// Smart-fur segmentation (spec §3.4) and the fur feature set (spec §3.5).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/dsp/fur_preprocess.h"
#include "tactile/error.h"
#include "tactile/features/fur.h"
#include "tactile/segment/threshold.h"

namespace tactile {
namespace {

//---- Spec vector F2: threshold + hysteresis ----------------------------------------------

TEST(ThresholdSegments, QuietForcedAndOpenEndsMatchSpecVectorF2) {
  std::vector<uint8_t> active(130, 0);
  const auto set = [&active](int first, int last) {
    for (int t = first; t <= last; ++t) active[t] = 1;
  };
  set(5, 8);
  set(15, 17);
  set(40, 40);
  set(60, 124);
  const std::vector<SampleSegment> segments = threshold_segments(active, 15, 60);
  ASSERT_EQ(segments.size(), 4u);
  const std::vector<std::tuple<int64_t, int64_t, SegmentEnd>> expected = {
      {5, 17, SegmentEnd::kQuiet},
      {40, 40, SegmentEnd::kQuiet},
      {60, 119, SegmentEnd::kForced},
      {120, 124, SegmentEnd::kOpen}};
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(segments[k].first, std::get<0>(expected[k])) << k;
    EXPECT_EQ(segments[k].last, std::get<1>(expected[k])) << k;
    EXPECT_EQ(segments[k].end, std::get<2>(expected[k])) << k;
  }
}

TEST(ThresholdSegments, NothingActiveGivesNoSegment) {
  EXPECT_TRUE(threshold_segments(std::vector<uint8_t>(40, 0), 15, 60).empty());
  EXPECT_TRUE(threshold_segments({}, 15, 60).empty());
}

//---- Spec vector F3: the 15 features -------------------------------------------------------

Eigen::MatrixXd toy_values() {
  Eigen::MatrixXd values(5, 4);
  values << 0.5, 0.05, 0, 0,  //
      0.8, 0.3, 0.2, 0,       //
      0.6, 0.6, 0.05, 0.2,    //
      0.2, 0.9, 0, 0.4,       //
      0, 0.3, 0, 0.08;
  return values;
}
const std::vector<double> kToySizes = {4, 4, 9, 16};
const std::vector<Point2> kToyPositions = {{0, 0}, {2, 0}, {0, 3}, {3, 3.5}};

TEST(FurFeatures, SeriesMatchSpecVectorF3) {
  const FurSeries series = fur_series(toy_values(), kToySizes, kToyPositions, 0.1);
  const std::vector<double> area = {4, 17, 24, 24, 4};
  const std::vector<double> sum = {0.55, 1.3, 1.45, 1.5, 0.38};
  const std::vector<double> peak = {0.5, 0.8, 0.6, 0.9, 0.3};
  const std::vector<Point2> centre = {
      {0, 0}, {0.387097, 0.870968}, {1.8, 1.4}, {2.44444, 2.07407}, {2, 0}};
  ASSERT_EQ(series.centre.size(), centre.size());
  for (size_t t = 0; t < 5; ++t) {
    EXPECT_NEAR(series.area[t], area[t], 1e-9) << t;
    EXPECT_NEAR(series.sum[t], sum[t], 1e-9) << t;
    EXPECT_NEAR(series.peak[t], peak[t], 1e-9) << t;
    EXPECT_NEAR(series.centre[t].x, centre[t].x, 1e-5) << t;
    EXPECT_NEAR(series.centre[t].y, centre[t].y, 1e-5) << t;
  }
}

TEST(FurFeatures, FifteenFeaturesMatchSpecVectorF3) {
  const std::array<double, 15> expected = {5,       14.6,     24,       81.44,    1.5,
                                           1.036,   0.224584, 0.9,      0.62,     0.0456,
                                           1.32631, 0.869008, 0.913937, 0.648898, 2};
  const std::array<double, 15> features =
      fur_segment_features(toy_values(), kToySizes, kToyPositions, 0.1);
  for (size_t k = 0; k < 15; ++k)
    EXPECT_NEAR(features[k], expected[k], 1e-5 * std::max(1.0, std::abs(expected[k])))
        << "feature " << k + 1;
  EXPECT_NEAR(features[12] + features[13], 1.56284, 1e-5);  // the 14-feature "variance centre"
}

TEST(FurFeatures, SegmentBelowThresholdHasZeroCentreFeatures) {
  const Eigen::MatrixXd quiet = Eigen::MatrixXd::Constant(3, 4, 0.05);
  const std::array<double, 15> features =
      fur_segment_features(quiet, kToySizes, kToyPositions, 0.1);
  EXPECT_EQ(features[0], 3.0);
  EXPECT_EQ(features[1], 0.0);           // no active area
  EXPECT_NEAR(features[5], 0.2, 1e-12);  // the sum still counts every cell
  for (size_t k = 10; k < 15; ++k) EXPECT_EQ(features[k], 0.0) << k;
}

TEST(FurFeatures, OneSampleSegmentHasZeroVariancesAndNoTranslation) {
  const std::array<double, 15> features =
      fur_segment_features(toy_values().topRows(1), kToySizes, kToyPositions, 0.1);
  EXPECT_EQ(features[0], 1.0);
  for (size_t k : {3, 6, 9, 12, 13, 14}) EXPECT_EQ(features[k], 0.0) << k;
}

TEST(FurFeatures, RejectsSizesThatDoNotMatchTheCells) {
  EXPECT_THROW(fur_series(toy_values(), {1, 2}, kToyPositions, 0.1), Error);
}

//---- Segmenter and extractor on a fur recording ------------------------------------------

// 150 samples of the fur layout at 15 Hz resting at 700 counts, and a press that lowers
// cell f000 (top of the head) by 200 counts over samples 30..35.
Recording press_recording(const SkinLayout& layout) {
  Recording recording;
  recording.id = "press";
  recording.layout_id = layout.id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 15.0;
  for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  stream.samples =
      SampleMatrix::Constant(150, static_cast<Eigen::Index>(layout.channels.size()), 700.0f);
  stream.samples.block(30, layout.channel_index("f000"), 6, 1).array() -= 200.0f;
  recording.streams.push_back(std::move(stream));
  return recording;
}

TEST(ThresholdSegmenter, PressOnTheTopCellIsOneQuietSegmentOnTheTop) {
  const SkinLayout layout = load_layout("fur");
  const std::vector<Label> labels = segment_threshold(
      press_recording(layout), layout, Parameters::parse("calibration_peak=200", "--params"));
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_NEAR(labels[0].t0, 30.0 / 15.0, 1e-12);
  EXPECT_NEAR(labels[0].t1, 36.0 / 15.0, 1e-12);  // the release undershoots and is clipped
  EXPECT_EQ(labels[0].region, "top");
  EXPECT_EQ(labels[0].note, "end=quiet");
  EXPECT_EQ(labels[0].annotator, "segmenter:threshold");
}

TEST(ThresholdSegmenter, CalibrationFromMetadataScalesTheThreshold) {
  const SkinLayout layout = load_layout("fur");
  Recording recording = press_recording(layout);
  // Peaks ten times the press: v stays under 0.1 and nothing is segmented.
  std::string peaks;
  for (size_t k = 0; k < layout.channels.size(); ++k) peaks += (k ? ",2000" : "2000");
  recording.metadata["calibration_peak"] = peaks;
  EXPECT_TRUE(segment_threshold(recording, layout, {}).empty());
  recording.metadata["calibration_peak"] = "200,200";
  EXPECT_THROW(segment_threshold(recording, layout, {}), Error);
}

TEST(ThresholdSegmenter, RecordingWithoutCalibrationIsAnErrorNamingIt) {
  const SkinLayout layout = load_layout("fur");
  try {
    segment_threshold(press_recording(layout), layout, {});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("calibration"), std::string::npos);
    EXPECT_EQ(error.where(), "press");
  }
}

struct FurExtraction {
  std::vector<FeatureColumn> columns;
  FeatureResult result;
};

FurExtraction extract_fur(const SkinLayout& layout, const Recording& raw, const Label& label,
                          const std::string& parameters = "calibration_peak=200") {
  const auto extractor = make_fur_extractor(Parameters::parse(parameters, "--params"));
  const Recording preprocessed = extractor->preprocess(raw, layout);
  return {extractor->columns(layout), extractor->extract({preprocessed, layout, label})};
}

TEST(FurExtractor, PressOnOneCellGivesItsAreaPositionAndDecayingPressure) {
  const SkinLayout layout = load_layout("fur");
  const Recording raw = press_recording(layout);
  const std::vector<Label> labels =
      segment_threshold(raw, layout, Parameters::parse("calibration_peak=200", "--params"));
  ASSERT_EQ(labels.size(), 1u);
  const FurExtraction extracted = extract_fur(layout, raw, labels[0]);
  ASSERT_TRUE(extracted.result.skip_reason.empty()) << extracted.result.skip_reason;
  ASSERT_EQ(extracted.columns.size(), 15u);
  const std::vector<double>& values = extracted.result.values;
  ASSERT_EQ(values.size(), 15u);
  const Taxel& cell = layout.taxels[0];
  EXPECT_EQ(values[0], 6.0);
  EXPECT_NEAR(values[1], cell.area / 100.0, 1e-9);  // cm²
  EXPECT_NEAR(values[7], 0.9227, 1e-4);             // α: the step's first output
  EXPECT_NEAR(values[8], 0.9227 * (1 - std::pow(0.9227, 6)) / (1 - 0.9227) / 6, 1e-4);
  EXPECT_NEAR(values[10], cell.position.x / 10.0, 1e-9);  // cm
  EXPECT_NEAR(values[11], cell.position.y / 10.0, 1e-9);
  EXPECT_EQ(values[14], 0.0);  // one cell: no travel
}

TEST(FurExtractor, FourteenFeatureVariantJoinsTheCentreVariances) {
  const SkinLayout layout = load_layout("fur");
  Label label;
  label.t0 = 2.0;
  label.t1 = 2.4;
  const FurExtraction extracted =
      extract_fur(layout, press_recording(layout), label, "calibration_peak=200,fur_features=14");
  ASSERT_EQ(extracted.columns.size(), 14u);
  EXPECT_EQ(extracted.columns[12].name, "centre_variance");
  EXPECT_EQ(extracted.columns[13].name, "translation");
  EXPECT_EQ(extracted.result.values.size(), 14u);
}

TEST(FurExtractor, MissingSampleAndEmptySpanAreSkippedWithReasons) {
  const SkinLayout layout = load_layout("fur");
  Recording raw = press_recording(layout);
  raw.streams[0].samples(32, layout.channel_index("f017")) =
      std::numeric_limits<float>::quiet_NaN();
  Label label;
  label.t0 = 2.0;
  label.t1 = 2.4;
  const FurExtraction missing = extract_fur(layout, raw, label);
  EXPECT_TRUE(missing.result.values.empty());
  EXPECT_NE(missing.result.skip_reason.find("f017"), std::string::npos)
      << missing.result.skip_reason;
  label.t1 = label.t0;
  EXPECT_FALSE(extract_fur(layout, raw, label).result.skip_reason.empty());
}

TEST(FurExtractor, QuietSegmentHasFiniteFeaturesAndZeroCentre) {
  const SkinLayout layout = load_layout("fur");
  Label label;
  label.t0 = 6.0;
  label.t1 = 8.0;
  const FurExtraction extracted = extract_fur(layout, press_recording(layout), label);
  ASSERT_EQ(extracted.result.values.size(), 15u);
  EXPECT_EQ(extracted.result.values[0], 30.0);
  for (double value : extracted.result.values) EXPECT_TRUE(std::isfinite(value));
  EXPECT_EQ(extracted.result.values[10], 0.0);
}

TEST(FurExtractor, RejectsBadOptionsByName) {
  EXPECT_THROW(make_fur_extractor(Parameters::parse("fur_features=13", "--params")), Error);
  EXPECT_THROW(make_fur_extractor(Parameters::parse("threshold=2", "--params")), Error);
  EXPECT_THROW(make_fur_extractor(Parameters::parse("treshold=0.2", "--params")), Error);
}

}  // namespace
}  // namespace tactile

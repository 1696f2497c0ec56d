// TSA single-touch events (spec §2.4) and the tsa_event feature set (spec §2.5-2.11).
#include "tactile/features/tsa_event.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/dsp/tsa_preprocess.h"
#include "tactile/error.h"
#include "tactile/segment/frame_edge.h"

namespace tactile {
namespace {

//---- Spec vector T2: events from frame flags ---------------------------------------------

TEST(FrameEdge, OccupancyChangesMatchSpecVectorT2) {
  const std::vector<uint8_t> active = {0, 1, 1, 1, 0, 0, 1, 0, 1, 1};
  EXPECT_EQ(occupancy_changes(active), (std::vector<int>{1, 0, 0, -1, 0, 1, -1, 1, 0}));
}

TEST(FrameEdge, EventsMatchSpecVectorT2AndDropTheOpenRun) {
  const std::vector<uint8_t> active = {0, 1, 1, 1, 0, 0, 1, 0, 1, 1};
  const std::vector<FrameEvent> events = frame_events(active, 0, false);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].first, 1);
  EXPECT_EQ(events[0].last, 3);
  EXPECT_EQ(events[1].first, 6);
  EXPECT_EQ(events[1].last, 6);
}

TEST(FrameEdge, OpenRunIsKeptFlaggedWhenAskedAndARunFromFrameZeroStartsThere) {
  const std::vector<uint8_t> active = {1, 1, 0, 1, 1};
  const std::vector<FrameEvent> events = frame_events(active, 0, true);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].first, 0);
  EXPECT_FALSE(events[0].open);
  EXPECT_EQ(events[1].first, 3);
  EXPECT_EQ(events[1].last, 4);
  EXPECT_TRUE(events[1].open);
}

TEST(FrameEdge, GapToleranceMergesRunsSeparatedByShortGapsOnly) {
  const std::vector<uint8_t> active = {1, 0, 1, 0, 0, 1, 0};
  const std::vector<FrameEvent> merged = frame_events(active, 1, false);
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].first, 0);
  EXPECT_EQ(merged[0].last, 2);
  EXPECT_EQ(merged[1].first, 5);
  EXPECT_EQ(frame_events(active, 2, false).size(), 1u);
}

//---- Spec vector T3: the 3-frame toy ------------------------------------------------------

// Frames of T3 as active contacts (x = column, y = row).
std::vector<TsaFrame> toy_frames() {
  return {{{{0, 1}, 5}, {{0, 2}, 3}},
          {{{1, 1}, 6}, {{2, 1}, 2}, {{1, 2}, 4}},
          {{{3, 1}, 7}, {{3, 2}, 5}}};
}
constexpr Point2 kSheetCentre{1.5, 1.5};

TEST(TsaEventFeatures, CentroidsMatchSpecVectorT3) {
  const std::vector<TsaFrame> frames = toy_frames();
  const Point2 second = tsa_centroid(frames[1]);
  EXPECT_NEAR(tsa_centroid(frames[0]).x, 0.0, 1e-12);
  EXPECT_NEAR(tsa_centroid(frames[0]).y, 1.5, 1e-12);
  EXPECT_NEAR(second.x, 1.33333, 1e-5);
  EXPECT_NEAR(second.y, 1.33333, 1e-5);
  EXPECT_NEAR(tsa_centroid(frames[2]).x, 3.0, 1e-12);
}

TEST(TsaEventFeatures, AreaOfEachReadingMatchesSpecVectorT3) {
  EXPECT_NEAR(tsa_area(toy_frames(), TsaAreaMode::kDistanceSum), 3.96212, 1e-5);
  EXPECT_NEAR(tsa_area(toy_frames(), TsaAreaMode::kEq8Literal), 2.56891, 1e-5);
  EXPECT_DOUBLE_EQ(tsa_area(toy_frames(), TsaAreaMode::kCount), 7.0);
}

TEST(TsaEventFeatures, FrameDescriptorsMatchSpecVectorT3) {
  const std::vector<TsaFrame> frames = toy_frames();
  const std::array<std::array<double, 4>, 3> expected = {
      {{4, 5, 1.41421, 1.58114}, {4, 6, 2, 0.707107}, {6, 7, 1.41421, 1.58114}}};
  for (size_t n = 0; n < 3; ++n) {
    const std::array<double, 4> descriptors = tsa_frame_descriptors(frames[n], kSheetCentre);
    for (size_t k = 0; k < 4; ++k)
      EXPECT_NEAR(descriptors[k], expected[n][k], 1e-5) << n << " D" << k + 1;
  }
}

TEST(TsaEventFeatures, DescriptorStatisticsMatchSpecVectorT3) {
  const std::array<double, 8> expected = {4.66667, 6, 1.60948,  1.28979,
                                          1.1547,  1, 0.338204, 0.504623};
  const std::array<double, 8> statistics = tsa_descriptor_statistics(toy_frames(), kSheetCentre);
  for (size_t k = 0; k < 8; ++k) EXPECT_NEAR(statistics[k], expected[k], 1e-5) << "value " << k;
}

TEST(TsaEventFeatures, SingleContactFrameHasZeroSpreadAndZeroStd) {
  const std::vector<TsaFrame> frames = {{{{2, 2}, 9}}};
  EXPECT_DOUBLE_EQ(tsa_area(frames, TsaAreaMode::kDistanceSum), 0.0);
  const std::array<double, 8> statistics = tsa_descriptor_statistics(frames, kSheetCentre);
  EXPECT_DOUBLE_EQ(statistics[2], 0.0);  // D3 of one value
  EXPECT_DOUBLE_EQ(statistics[4], 0.0);  // eq. 6 with N = 1
  EXPECT_DOUBLE_EQ(statistics[0], 9.0);
}

TEST(TsaEventFeatures, ToyPathShapeAndDirectionMatchSpecVectorT3) {
  std::vector<Point2> path;
  for (const TsaFrame& frame : toy_frames()) path.push_back(tsa_centroid(frame));
  const TsaPathShape shape = tsa_path_shape(path);
  EXPECT_NEAR(shape.signed_area, 0.25, 1e-5);
  EXPECT_NEAR(shape.length, 3.01869, 1e-5);
  EXPECT_NEAR(shape.net_displacement, 3.0, 1e-12);
  EXPECT_NEAR(shape.angle_degrees, 0.0, 1e-12);
  EXPECT_EQ(tsa_direction_code(path), 3);
}

TEST(TsaEventFeatures, SquarePathTurnsClockwiseAndItsReverseCounterClockwise) {
  const std::vector<Point2> square = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  const TsaPathShape shape = tsa_path_shape(square);
  EXPECT_NEAR(shape.signed_area, 1.0, 1e-12);
  EXPECT_NEAR(shape.length, 3.0, 1e-12);
  EXPECT_NEAR(shape.net_displacement, 1.0, 1e-12);
  EXPECT_EQ(tsa_direction_code(square), 1);
  const std::vector<Point2> reversed(square.rbegin(), square.rend());
  EXPECT_NEAR(tsa_path_shape(reversed).signed_area, -1.0, 1e-12);
  EXPECT_EQ(tsa_direction_code(reversed), 2);
}

TEST(TsaEventFeatures, DiagonalUpwardsToTheRightIsLowerLeftToUpperRight) {
  const std::vector<Point2> path = {{0, 3}, {1.5, 1.5}, {3, 0}};
  EXPECT_NEAR(tsa_path_shape(path).angle_degrees, 45.0, 1e-9);
  EXPECT_EQ(tsa_direction_code(path), 9);
}

TEST(TsaEventFeatures, EveryStraightDirectionGetsItsCode) {
  const auto code = [](double dx, double dy) {
    return tsa_direction_code({{1.5, 1.5}, {1.5 + dx, 1.5 + dy}});
  };
  EXPECT_EQ(code(-2, 0), 4);
  EXPECT_EQ(code(0, 2), 5);  // y grows downwards
  EXPECT_EQ(code(0, -2), 6);
  EXPECT_EQ(code(2, 2), 7);
  EXPECT_EQ(code(-2, -2), 8);
  EXPECT_EQ(code(-2, 2), 10);
  EXPECT_EQ(code(0.2, 0.1), 0);  // under d_min: stationary
}

TEST(TsaEventFeatures, SingleFrameEventHasNoDirection) {
  EXPECT_EQ(tsa_direction_code({{2, 2}}), 0);
  EXPECT_EQ(tsa_direction_code({}), 0);
}

//---- Segmenter and extractor on a TSA recording --------------------------------------------

constexpr double kTouchCounts = 50.0;

// 120 frames of the tsa layout at 8 Hz: resting counts with a little deterministic noise,
// and a finger sliding left to right along rows 1-2 of sheet m03.s2 over frames 40..47.
Recording sliding_touch_recording(const SkinLayout& layout) {
  Recording recording;
  recording.id = "slide";
  recording.layout_id = layout.id;
  recording.metadata["front_end"] = "raw counts, rising with touch";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 8.0;
  for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  const auto columns = static_cast<Eigen::Index>(layout.channels.size());
  stream.samples.resize(120, columns);
  for (Eigen::Index frame = 0; frame < 120; ++frame)
    for (Eigen::Index column = 0; column < columns; ++column)
      stream.samples(frame, column) =
          static_cast<float>(400 + column % 97 + 0.3 * ((frame * 7 + column * 13) % 5 - 2));
  for (int frame = 40; frame <= 47; ++frame) {
    const int pad_column = (frame - 40) / 2;  // two frames per pad column
    for (int row : {1, 2}) {
      const std::string name = "m03.s2.p" + std::string(row * 4 + pad_column < 10 ? "0" : "") +
                               std::to_string(row * 4 + pad_column);
      stream.samples(frame, layout.channel_index(name)) += static_cast<float>(kTouchCounts);
    }
  }
  recording.streams.push_back(std::move(stream));
  return recording;
}

std::string location_of(const SkinLayout& layout, const std::string& sheet) {
  return layout.groups_of(layout.find_group(sheet)->taxels.front(), "location").front()->id;
}

TEST(FrameEdgeSegmenter, SlidingFingerIsOneEventOnItsSheetsLocation) {
  const SkinLayout layout = load_layout("tsa");
  const std::vector<Label> labels = segment_frame_edge(sliding_touch_recording(layout), layout, {});
  ASSERT_EQ(labels.size(), 1u);
  const Label& label = labels.front();
  EXPECT_DOUBLE_EQ(label.t0, 40.0 / 8.0);  // eq. 3 lifts the first frame by 50/4 counts
  EXPECT_GT(label.t1, 48.0 / 8.0);         // the smoothed tail outlasts the touch
  EXPECT_LT(label.t1, 60.0 / 8.0);
  EXPECT_EQ(label.region, location_of(layout, "m03.s2"));
  EXPECT_EQ(label.source, LabelSource::kSegmenter);
  EXPECT_EQ(label.annotator, "segmenter:frame-edge");
  EXPECT_NE(label.note.find("sheet=m03.s2"), std::string::npos);
  EXPECT_EQ(label.class_name, "");
}

TEST(FrameEdgeSegmenter, FallingTouchSignFindsNothingInRisingCounts) {
  const SkinLayout layout = load_layout("tsa");
  EXPECT_TRUE(segment_frame_edge(sliding_touch_recording(layout), layout,
                                 Parameters::parse("touch=falling", "--params"))
                  .empty());
}

TEST(FrameEdgeSegmenter, RejectsAnUnknownParameterByName) {
  const SkinLayout layout = load_layout("tsa");
  try {
    segment_frame_edge(sliding_touch_recording(layout), layout,
                       Parameters::parse("gapp=1", "--params"));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("gapp"), std::string::npos);
  }
}

struct TsaExtraction {
  std::vector<FeatureColumn> columns;
  FeatureResult result;
};

TsaExtraction extract_tsa(const SkinLayout& layout, const Recording& raw, const Label& label,
                          const std::string& parameters = "") {
  const auto extractor = make_tsa_event_extractor(Parameters::parse(parameters, "--params"));
  const Recording preprocessed = extractor->preprocess(raw, layout);
  return {extractor->columns(layout), extractor->extract({preprocessed, layout, label})};
}

TEST(TsaEventExtractor, SlidingFingerGoesLeftToRightOnSheetSix) {
  const SkinLayout layout = load_layout("tsa");
  const Recording raw = sliding_touch_recording(layout);
  const std::vector<Label> labels = segment_frame_edge(raw, layout, {});
  ASSERT_EQ(labels.size(), 1u);
  const TsaExtraction extracted = extract_tsa(layout, raw, labels.front());
  ASSERT_TRUE(extracted.result.skip_reason.empty()) << extracted.result.skip_reason;
  ASSERT_EQ(extracted.columns.size(), 4u);
  EXPECT_EQ(extracted.columns[0].name, "time");
  const std::vector<double>& values = extracted.result.values;
  ASSERT_EQ(values.size(), 4u);
  EXPECT_DOUBLE_EQ(values[0], labels.front().t1 - labels.front().t0);  // every frame active
  EXPECT_EQ(values[1], 3.0);                                           // left -> right
  EXPECT_GT(values[2], 0.0);  // two rows touched: spread about the centroid
  EXPECT_EQ(values[3], 6.0);  // m03.s2 = 2 * (3 - 1) + 2
}

TEST(TsaEventExtractor, ToyFramesOnSheetFiveGiveTheFeatureVectorOfSpecVectorT3) {
  // The three T3 frames as counts above a flat 100-count rest on sheet m03.s1 (code 5), with
  // eq. 3 switched off (N = 1) and a 1-count trigger, so the contacts are exactly T3's values.
  const SkinLayout layout = load_layout("tsa");
  Recording raw = sliding_touch_recording(layout);
  Stream& stream = raw.streams[0];
  stream.samples.setConstant(100.0f);
  const std::vector<std::vector<std::pair<int, float>>> frames = {
      {{4, 5}, {8, 3}}, {{5, 6}, {6, 2}, {9, 4}}, {{7, 7}, {11, 5}}};  // (pad, value)
  for (size_t n = 0; n < frames.size(); ++n)
    for (const auto& [pad, value] : frames[n]) {
      const std::string name = "m03.s1.p" + std::string(pad < 10 ? "0" : "") + std::to_string(pad);
      stream.samples(static_cast<Eigen::Index>(40 + n), layout.channel_index(name)) += value;
    }
  Label label;
  label.t0 = 40.0 / 8.0;
  label.t1 = 43.0 / 8.0;
  const TsaExtraction extracted =
      extract_tsa(layout, raw, label, "iir_n=1,min_threshold=1,tsa_features=EXTENDED");
  ASSERT_TRUE(extracted.result.skip_reason.empty()) << extracted.result.skip_reason;
  const std::vector<double> expected = {0.375,   3,       3.96212, 5, 4.66667,  6,
                                        1.60948, 1.28979, 1.1547,  1, 0.338204, 0.504623};
  ASSERT_EQ(extracted.result.values.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(extracted.result.values[k], expected[k], 1e-5) << extracted.columns[k].name;
}

TEST(TsaEventExtractor, ExtendedAndOneHotColumnsMatchTheirValues) {
  const SkinLayout layout = load_layout("tsa");
  const Recording raw = sliding_touch_recording(layout);
  const std::vector<Label> labels = segment_frame_edge(raw, layout, {});
  ASSERT_EQ(labels.size(), 1u);
  const TsaExtraction extracted = extract_tsa(
      layout, raw, labels.front(), "tsa_features=EXTENDED,direction=onehot,location=onehot");
  ASSERT_TRUE(extracted.result.skip_reason.empty()) << extracted.result.skip_reason;
  ASSERT_EQ(extracted.columns.size(), 1u + 11u + 1u + 42u + 8u);
  ASSERT_EQ(extracted.result.values.size(), extracted.columns.size());
  EXPECT_EQ(extracted.columns[1 + 3].name, "direction.left_to_right");
  EXPECT_EQ(extracted.result.values[1 + 3], 1.0);
  EXPECT_EQ(extracted.columns[13 + 5].name, "location.m03.s2");
  EXPECT_EQ(extracted.result.values[13 + 5], 1.0);
  EXPECT_EQ(extracted.columns[55].name, "d1_mean");
  // D2 >= D1 per frame, and a pad touched for two frames rises to at most 50 (1 - 0.75²).
  EXPECT_GE(extracted.result.values[56], extracted.result.values[55]);
  EXPECT_LE(extracted.result.values[56], kTouchCounts * (1.0 - 0.75 * 0.75) + 0.6);
  EXPECT_GT(extracted.result.values[56], 3.0);  // above the trigger floor
  for (double value : extracted.result.values) EXPECT_TRUE(std::isfinite(value));
}

TEST(TsaEventExtractor, GroundTruthLabelOnTheLocationFindsTheTouchedSheet) {
  const SkinLayout layout = load_layout("tsa");
  Label label;
  label.t0 = 5.0;
  label.t1 = 6.0;
  label.region = location_of(layout, "m03.s2");
  const TsaExtraction extracted = extract_tsa(layout, sliding_touch_recording(layout), label);
  ASSERT_TRUE(extracted.result.skip_reason.empty()) << extracted.result.skip_reason;
  EXPECT_DOUBLE_EQ(extracted.result.values[0], 1.0);  // frames 40..47, cut by the label
  EXPECT_EQ(extracted.result.values[3], 6.0);
}

TEST(TsaEventExtractor, SegmentWithoutContactIsSkippedWithAReason) {
  const SkinLayout layout = load_layout("tsa");
  Label label;
  label.t0 = 1.0;
  label.t1 = 3.0;
  const TsaExtraction extracted = extract_tsa(layout, sliding_touch_recording(layout), label);
  EXPECT_TRUE(extracted.result.values.empty());
  EXPECT_NE(extracted.result.skip_reason.find("no pad triggered"), std::string::npos);
}

TEST(TsaEventExtractor, MissingSampleInTheSegmentIsSkippedNamingTheChannel) {
  const SkinLayout layout = load_layout("tsa");
  Recording raw = sliding_touch_recording(layout);
  raw.streams[0].samples(42, layout.channel_index("m03.s2.p05")) =
      std::numeric_limits<float>::quiet_NaN();
  Label label;
  label.t0 = 5.0;
  label.t1 = 6.0;
  const TsaExtraction extracted = extract_tsa(layout, raw, label);
  EXPECT_NE(extracted.result.skip_reason.find("m03.s2.p05"), std::string::npos)
      << extracted.result.skip_reason;
}

TEST(TsaEventExtractor, UnknownRegionAndEmptySpanAreSkipped) {
  const SkinLayout layout = load_layout("tsa");
  Label label;
  label.t0 = 5.0;
  label.t1 = 6.0;
  label.region = "tail";
  EXPECT_NE(
      extract_tsa(layout, sliding_touch_recording(layout), label).result.skip_reason.find("tail"),
      std::string::npos);
  label.region = "all";
  label.t0 = label.t1 = 5.0;
  EXPECT_FALSE(
      extract_tsa(layout, sliding_touch_recording(layout), label).result.skip_reason.empty());
}

TEST(TsaEventExtractor, RejectsBadOptionsByName) {
  EXPECT_THROW(make_tsa_event_extractor(Parameters::parse("area_mode=PIXELS", "--params")), Error);
  EXPECT_THROW(make_tsa_event_extractor(Parameters::parse("iir_n=3", "--params")), Error);
  EXPECT_THROW(make_tsa_event_extractor(Parameters::parse("location=letters", "--params")), Error);
}

TEST(TsaPreprocess, SheetsOfTheTsaLayoutSitOnAFourByFourPitchGrid) {
  const SkinLayout layout = load_layout("tsa");
  Stream stream;
  for (const Channel& channel : layout.channels) stream.channels.push_back(channel.name);
  stream.samples = SampleMatrix::Zero(1, static_cast<Eigen::Index>(layout.channels.size()));
  const std::vector<dsp::TsaSheet> sheets = dsp::tsa_sheets(layout, stream);
  ASSERT_EQ(sheets.size(), 42u);
  const dsp::TsaSheet& sheet = sheets[5];
  EXPECT_EQ(sheet.id, "m03.s2");
  EXPECT_EQ(sheet.code, 6);
  EXPECT_NEAR(sheet.centre.x, 1.5, 1e-9);
  EXPECT_NEAR(sheet.centre.y, 1.5, 1e-9);
  // Pad 6 is row 1, column 2.
  EXPECT_NEAR(sheet.positions[6].x, 2.0, 1e-9);
  EXPECT_NEAR(sheet.positions[6].y, 1.0, 1e-9);
}

}  // namespace
}  // namespace tactile

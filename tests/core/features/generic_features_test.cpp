// The generic descriptor set on hand-built grid and strip recordings.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/error.h"
#include "tactile/features/generic.h"

namespace tactile {
namespace {

Recording blank_recording(const SkinLayout& layout, int64_t samples, double rate_hz) {
  Recording recording;
  recording.id = "hand-built";
  recording.layout_id = layout.id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate_hz;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples = SampleMatrix::Zero(samples, static_cast<int64_t>(layout.channels.size()));
  recording.streams.push_back(std::move(stream));
  return recording;
}

// A 3 x 3 blob, 1 at its centre and 0.5 around it, centred on (row, column) at `sample`.
void press_blob(Recording& recording, int64_t columns, int64_t sample, int64_t row, int64_t column,
                float scale = 1.0f) {
  for (int64_t dr = -1; dr <= 1; ++dr)
    for (int64_t dc = -1; dc <= 1; ++dc)
      recording.streams[0].samples(sample, (row + dr) * columns + column + dc) =
          scale * ((dr == 0 && dc == 0) ? 1.0f : 0.5f);
}

Label whole(const Recording& recording, const std::string& region = "all") {
  Label label;
  label.recording = recording.id;
  label.t0 = 0.0;
  label.t1 = recording.duration() + 1.0;
  label.region = region;
  return label;
}

// As a corpus run does: preprocess the recording once, then extract the segment.
FeatureResult run(const FeatureExtractor& extractor, const Recording& recording,
                  const SkinLayout& layout, const Label& label) {
  const Recording prepared = extractor.preprocess(recording, layout);
  return extractor.extract(SegmentInput{prepared, layout, label});
}

// The value of a named column.
double value_of(const FeatureExtractor& extractor, const SkinLayout& layout,
                const FeatureResult& result, const std::string& name) {
  const std::vector<FeatureColumn> columns = extractor.columns(layout);
  for (size_t index = 0; index < columns.size(); ++index)
    if (columns[index].name == name) return result.values.at(index);
  ADD_FAILURE() << "no column " << name;
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(GenericFeatures, BlobMovingAcrossAGridHasPathLengthOfTheDistanceMoved) {
  const SkinLayout layout = make_grid_layout(5, 8);
  // Centre moves along row 2 from column 1 to column 6, ten samples per column: 50 mm.
  Recording recording = blank_recording(layout, 60, 100.0);
  for (int64_t sample = 0; sample < 60; ++sample)
    press_blob(recording, 8, sample, 2, 1 + sample / 10);
  const auto extractor = make_generic_extractor({});
  const FeatureResult result = run(*extractor, recording, layout, whole(recording));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  ASSERT_EQ(result.values.size(), extractor->columns(layout).size());
  EXPECT_NEAR(value_of(*extractor, layout, result, "centroid.path_length"), 50.0, 1e-9);
  EXPECT_NEAR(value_of(*extractor, layout, result, "centroid.displacement"), 50.0, 1e-9);
  // Nine 10 x 10 mm taxels pass 0.2 of the range at every sample.
  EXPECT_NEAR(value_of(*extractor, layout, result, "contact.max_area"), 900.0, 1e-9);
  EXPECT_NEAR(value_of(*extractor, layout, result, "contact.mean_area"), 900.0, 1e-9);
}

TEST(GenericFeatures, StationaryPressHasNoDisplacementAndAnAreaThatGrowsWithTheThreshold) {
  const SkinLayout layout = make_grid_layout(4, 4);
  Recording recording = blank_recording(layout, 40, 50.0);
  // Rises and falls in place; samples 0..4 and 35..39 are untouched.
  for (int64_t sample = 5; sample < 35; ++sample)
    press_blob(recording, 4, sample, 1, 2, static_cast<float>(std::sin((sample - 5) * M_PI / 30)));
  const auto extractor = make_generic_extractor({});
  const FeatureResult result = run(*extractor, recording, layout, whole(recording));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  EXPECT_NEAR(value_of(*extractor, layout, result, "centroid.displacement"), 0.0, 1e-9);
  EXPECT_NEAR(value_of(*extractor, layout, result, "centroid.path_length"), 0.0, 1e-4);
  EXPECT_NEAR(value_of(*extractor, layout, result, "contact.max_area"), 900.0, 1e-9);
  const double mean_area = value_of(*extractor, layout, result, "contact.mean_area");
  EXPECT_GT(mean_area, 100.0);
  EXPECT_LT(mean_area, 900.0 * 30 / 40);

  Parameters strict;
  strict.set("threshold", "0.6");
  const auto strict_extractor = make_generic_extractor(strict);
  const FeatureResult centre_only = run(*strict_extractor, recording, layout, whole(recording));
  // Only the centre passes 0.6 of the range.
  EXPECT_NEAR(value_of(*strict_extractor, layout, centre_only, "contact.max_area"), 100.0, 1e-9);
}

TEST(GenericFeatures, PerChannelValuesMatchTheirDefinitions) {
  const SkinLayout layout = make_strip_layout(2);
  Recording recording = blank_recording(layout, 8, 10.0);
  const float values[] = {0, 1, 3, 2, 5, 5, 1, 0};  // first maximum at sample 4
  for (int64_t sample = 0; sample < 8; ++sample)
    recording.streams[0].samples(sample, 1) = values[sample];
  const auto extractor = make_generic_extractor({});
  Label label = whole(recording);
  label.t0 = 0.15;  // samples 2..7 (times 0.2 .. 0.7)
  const FeatureResult result = run(*extractor, recording, layout, label);
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  const std::vector<double> segment = {3, 2, 5, 5, 1, 0};
  const stats::Hjorth hjorth = stats::hjorth(segment);
  EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "ch1.hjorth_activity"), hjorth.activity);
  EXPECT_NEAR(hjorth.activity, 32.0 / 9.0, 1e-12);  // population variance
  EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "ch1.hjorth_mobility"), hjorth.mobility);
  EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "ch1.hjorth_complexity"),
                   hjorth.complexity);
  EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "ch1.peak"), 5.0);
  EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "ch1.mean"), 16.0 / 6.0);
  EXPECT_NEAR(value_of(*extractor, layout, result, "ch1.integral"), 1.6, 1e-12);
  EXPECT_NEAR(value_of(*extractor, layout, result, "ch1.peak_time"), 0.4 - 0.15, 1e-12);
}

TEST(GenericFeatures, StripHasPerChannelColumnsOnlyInAStableOrder) {
  const SkinLayout layout = make_strip_layout(3);
  const auto extractor = make_generic_extractor({});
  const std::vector<FeatureColumn> columns = extractor->columns(layout);
  // 26 per channel (7 summary, 11 shape, 8 envelope parts), the busiest channel's 26 and its
  // share of the activity, then the neighbours' correlation.
  ASSERT_EQ(columns.size(), 3u * 26 + 26 + 1 + 1);
  EXPECT_EQ(columns[0].name, "ch0.hjorth_activity");
  EXPECT_EQ(columns[6].name, "ch0.peak_time");
  EXPECT_EQ(columns[7].name, "ch0.median");
  EXPECT_EQ(columns[25].name, "ch0.envelope_7");
  EXPECT_EQ(columns[26].name, "ch1.hjorth_activity");
  EXPECT_EQ(columns[78].name, "busiest.hjorth_activity");
  EXPECT_EQ(columns[104].name, "busiest.activity_share");
  EXPECT_EQ(columns.back().name, "neighbours.correlation");
  for (const FeatureColumn& column : columns) EXPECT_FALSE(column.description.empty());
  EXPECT_EQ(make_generic_extractor({})->columns(make_grid_layout(2, 2)).back().name,
            "contact.spread");
}

TEST(GenericFeatures, RegionLimitsContactToItsGroup) {
  const SkinLayout layout = make_grid_layout(6, 6);
  Recording recording = blank_recording(layout, 40, 100.0);
  // Two touches at once: a moving one in rows 0-2, a still one in rows 3-5.
  for (int64_t sample = 10; sample < 30; ++sample) {
    press_blob(recording, 6, sample, 1, sample / 10);
    press_blob(recording, 6, sample, 4, 3);
  }
  const auto extractor = make_generic_extractor({});
  // The label covers only the touch: rest comes from the recording around it.
  Label touch = whole(recording);
  touch.t0 = 0.1;
  touch.t1 = 0.3;
  const FeatureResult all = run(*extractor, recording, layout, touch);
  touch.region = "row4";
  const FeatureResult lower = run(*extractor, recording, layout, touch);
  ASSERT_TRUE(lower.skip_reason.empty()) << lower.skip_reason;
  EXPECT_NEAR(value_of(*extractor, layout, all, "contact.max_area"), 1800.0, 1e-9);
  // Row 4 holds three taxels of the still touch only.
  EXPECT_NEAR(value_of(*extractor, layout, lower, "contact.max_area"), 300.0, 1e-9);
  EXPECT_NEAR(value_of(*extractor, layout, lower, "centroid.displacement"), 0.0, 1e-9);
  EXPECT_FALSE(run(*extractor, recording, layout, whole(recording, "elbow")).skip_reason.empty());
}

TEST(GenericFeatures, ReversedModalityTakesLowValuesAsContact) {
  // Proximity: far is 200; a finger at 20 over taxel 1, then over taxel 2 of three in an L.
  Eigen::MatrixXd values(3, 3);
  values << 200, 200, 200, 200, 20, 200, 200, 200, 20;
  const std::vector<Point2> positions = {{0, 0}, {10, 0}, {0, 10}};
  const ContactMotion motion =
      contact_motion(values, {}, positions, Eigen::VectorXd::Constant(3, 5.0), 0.2, true);
  EXPECT_DOUBLE_EQ(motion.max_area, 5.0);
  EXPECT_DOUBLE_EQ(motion.mean_area, 10.0 / 3.0);
  EXPECT_NEAR(motion.path_length, std::hypot(10.0, 10.0), 1e-12);
  const ContactMotion upright =
      contact_motion(values, {}, positions, Eigen::VectorXd::Constant(3, 5.0), 0.2, false);
  EXPECT_DOUBLE_EQ(upright.max_area, 10.0);  // the far readings, taken the wrong way round
}

TEST(GenericFeatures, TheBusiestChannelsColumnsDoNotDependOnWhereTheTouchLanded) {
  // The same press on channel 0 or on channel 2 of a strip: the per-channel columns differ,
  // the busiest channel's are the same (a corpus whose touches land anywhere).
  const SkinLayout layout = make_strip_layout(3);
  const auto extractor = make_generic_extractor({});
  const float press[] = {0, 0, 1, 4, 6, 3, 1, 0, 0, 0};
  std::vector<double> busiest[2];
  for (int which = 0; which < 2; ++which) {
    Recording recording = blank_recording(layout, 10, 10.0);
    const int64_t channel = which == 0 ? 0 : 2;
    for (int64_t sample = 0; sample < 10; ++sample) {
      recording.streams[0].samples(sample, channel) = press[sample];
      recording.streams[0].samples(sample, 1) = 0.1f * press[sample];  // a little crosstalk
    }
    const FeatureResult result = run(*extractor, recording, layout, whole(recording));
    ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
    const std::string name = "ch" + std::to_string(channel);
    EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "busiest.peak"), 6.0);
    EXPECT_DOUBLE_EQ(value_of(*extractor, layout, result, "busiest.hjorth_activity"),
                     value_of(*extractor, layout, result, name + ".hjorth_activity"));
    // Activity scales with the square: 1 / (1 + 0.01) of the total.
    EXPECT_NEAR(value_of(*extractor, layout, result, "busiest.activity_share"), 1.0 / 1.01, 1e-9);
    const std::vector<FeatureColumn> columns = extractor->columns(layout);
    for (size_t index = 0; index < columns.size(); ++index)
      if (columns[index].name.rfind("busiest.", 0) == 0)
        busiest[which].push_back(result.values[index]);
  }
  EXPECT_EQ(busiest[0], busiest[1]);
}

TEST(GenericFeatures, PeakOfAReversedModalityIsItsSmallestValue) {
  const std::vector<double> distance = {200, 150, 30, 30, 180};
  const ChannelSummary near = summarise_channel(distance, 10.0, true);
  EXPECT_EQ(near.peak, 30.0);
  EXPECT_EQ(near.peak_index, 2);
  EXPECT_EQ(summarise_channel(distance, 10.0).peak, 200.0);
  const SkinLayout nao = load_layout("nao");
  const auto columns = make_generic_extractor({})->columns(nao);
  // Proximity of the 32 cells, the busiest cell and its share, neighbours, the map.
  ASSERT_EQ(columns.size(), 32u * 26 + 27 + 1 + 5);
  EXPECT_NE(columns[3].description.find("smallest"), std::string::npos) << columns[3].description;
}

TEST(GenericFeatures, TaxelsRestingAtDifferentLevelsAreNotContact) {
  // Taxel 0 rests at 500, taxel 1 at 100 (raw counts differ per cell); only taxel 2 is
  // pressed (falls from 300 to 50). Noise of 2 counts on the others.
  Eigen::MatrixXd values(4, 3);
  values << 500, 100, 300, 502, 98, 50, 499, 101, 60, 501, 100, 300;
  const std::vector<Point2> positions = {{0, 0}, {10, 0}, {0, 10}};
  const ContactMotion motion =
      contact_motion(values, {}, positions, Eigen::VectorXd::Constant(3, 4.0), 0.2, true);
  EXPECT_DOUBLE_EQ(motion.max_area, 4.0);
  EXPECT_DOUBLE_EQ(motion.mean_area, 2.0);
  EXPECT_DOUBLE_EQ(motion.displacement, 0.0);
  // The same with rest levels from the whole recording: all four samples are one press.
  Eigen::RowVectorXd rest(3);
  rest << 500, 100, 300;
  const ContactMotion held = contact_motion(values.middleRows(1, 2), rest, positions,
                                            Eigen::VectorXd::Constant(3, 4.0), 0.2, true);
  EXPECT_DOUBLE_EQ(held.mean_area, 4.0);
}

TEST(GenericFeatures, QuietLevelIsALowPercentileIgnoringNan) {
  std::vector<double> values = {9, 1, 5, 3, 7, 2, 8, 4, 6, 10, 11};
  EXPECT_EQ(quiet_level(values, false), 2.0);  // floor(0.1 x 10) = element 1 in order
  EXPECT_EQ(quiet_level(values, true), 10.0);  // ceil(0.9 x 10) = element 9 in order
  values.push_back(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(quiet_level(values, false), 2.0);
  EXPECT_EQ(quiet_level(std::vector<double>{}, false), 0.0);
}

TEST(GenericFeatures, ConstantChannelsGiveFiniteZeros) {
  const SkinLayout layout = make_grid_layout(3, 3);
  Recording recording = blank_recording(layout, 10, 100.0);
  recording.streams[0].samples.setConstant(0.5f);
  const auto extractor = make_generic_extractor({});
  const FeatureResult result = run(*extractor, recording, layout, whole(recording));
  ASSERT_TRUE(result.skip_reason.empty());
  for (double value : result.values) EXPECT_TRUE(std::isfinite(value));
  EXPECT_EQ(value_of(*extractor, layout, result, "ch4.hjorth_mobility"), 0.0);
  EXPECT_EQ(value_of(*extractor, layout, result, "contact.max_area"), 0.0);
  EXPECT_EQ(value_of(*extractor, layout, result, "centroid.path_length"), 0.0);
}

TEST(GenericFeatures, ShortSegmentsHaveDefinedValuesAndEmptyOrNanOnesAreSkipped) {
  const SkinLayout layout = make_grid_layout(2, 2);
  Recording recording = blank_recording(layout, 10, 100.0);
  recording.streams[0].samples(3, 1) = 4.0f;
  const auto extractor = make_generic_extractor({});
  Label label = whole(recording);
  label.t0 = 0.025;
  label.t1 = 0.035;  // sample 3 only
  const FeatureResult single = run(*extractor, recording, layout, label);
  ASSERT_TRUE(single.skip_reason.empty()) << single.skip_reason;
  EXPECT_EQ(value_of(*extractor, layout, single, "ch1.peak"), 4.0);
  EXPECT_EQ(value_of(*extractor, layout, single, "ch1.hjorth_mobility"), 0.0);
  EXPECT_NEAR(value_of(*extractor, layout, single, "ch1.integral"), 0.04, 1e-12);
  for (double value : single.values) EXPECT_TRUE(std::isfinite(value));
  label.t0 = 0.031;  // between samples: none inside
  label.t1 = 0.035;
  EXPECT_EQ(run(*extractor, recording, layout, label).skip_reason, "segment holds no samples");
  recording.streams[0].samples(6, 3) = std::numeric_limits<float>::quiet_NaN();
  const std::string reason = run(*extractor, recording, layout, whole(recording)).skip_reason;
  EXPECT_NE(reason.find("channel ch3 at t=0.06"), std::string::npos) << reason;
}

TEST(GenericFeatures, BadParametersAndMismatchedRecordingsNameTheProblem) {
  Parameters unknown = Parameters::parse("treshold=0.3", "--params");
  EXPECT_THROW(make_generic_extractor(unknown), Error);
  Parameters too_high = Parameters::parse("threshold=1.5", "--params");
  EXPECT_THROW(make_generic_extractor(too_high), Error);
  Parameters modality = Parameters::parse("modality=force", "--params");
  try {
    make_generic_extractor(modality)->columns(make_grid_layout(2, 2));
    FAIL() << "unknown modality accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "--params");
    EXPECT_NE(error.message().find("modality=force"), std::string::npos);
  }
  const SkinLayout layout = make_grid_layout(2, 2);
  const Recording recording = blank_recording(make_grid_layout(3, 3), 10, 100.0);
  EXPECT_THROW(run(*make_generic_extractor({}), recording, layout, whole(recording)), Error);
}

// A skin whose layout adds virtual channels (sums its own preprocessing computes) records only
// its real ones: the stream's named channels are found in the layout, the rest read as 0.
TEST(GenericFeatures, AStreamOfSomeOfTheLayoutsChannelsIsReadByName) {
  const SkinLayout layout = make_grid_layout(4, 4);
  Recording full = blank_recording(layout, 40, 100.0);
  press_blob(full, 4, 20, 1, 1);
  Recording partial = full;
  Stream& stream = partial.streams[0];
  // Channels 14, 13, ..., 0: reversed, the last layout channel missing.
  const int64_t kept = 15;
  std::vector<std::string> names;
  SampleMatrix samples(stream.sample_count(), kept);
  for (int64_t column = 0; column < kept; ++column) {
    const int64_t channel = kept - 1 - column;
    names.push_back(layout.channels[static_cast<size_t>(channel)].name);
    samples.col(column) = stream.samples.col(channel);
  }
  stream.channels = names;
  stream.units.assign(static_cast<size_t>(kept), "");
  stream.samples = samples;
  const std::vector<int64_t> columns = layout_columns(stream, layout);
  EXPECT_EQ(columns, (std::vector<int64_t>{14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0, -1}));
  EXPECT_FALSE(in_layout_order(stream, layout));
  const Stream ordered = layout_ordered(stream, layout);
  EXPECT_TRUE(in_layout_order(ordered, layout));
  EXPECT_EQ(ordered.samples.col(5), full.streams[0].samples.col(5));
  EXPECT_TRUE(ordered.samples.col(15).isZero());

  const auto extractor = make_generic_extractor({});
  const FeatureResult from_full = run(*extractor, full, layout, whole(full));
  const FeatureResult from_partial = run(*extractor, partial, layout, whole(partial));
  ASSERT_TRUE(from_full.skip_reason.empty()) << from_full.skip_reason;
  ASSERT_TRUE(from_partial.skip_reason.empty()) << from_partial.skip_reason;
  // The blob never reaches the last taxel, so both give the same row.
  EXPECT_EQ(from_full.values, from_partial.values);

  // A channel the layout lacks is refused by name.
  stream.channels[0] = "elbow";
  try {
    layout_columns(stream, layout);
    FAIL() << "a stranger channel was accepted";
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("elbow"), std::string::npos) << error.message();
  }
}

// flux's stream holds 8 of its layout's 10 channels (the two virtual sums are computed by its
// own preprocessing): generic reads the missing ones as 0, as raw does, not an error.
TEST(GenericFeatures, AStreamWithSomeOfTheLayoutsChannelsReadsTheOthersAsZero) {
  const SkinLayout layout = make_strip_layout(3);
  Recording full = blank_recording(layout, 20, 100.0);
  for (int64_t k = 5; k < 15; ++k) full.streams[0].samples(k, 0) = static_cast<float>(k - 4);
  Recording partial = full;
  Stream& stream = partial.streams[0];
  stream.samples = SampleMatrix(full.streams[0].samples.leftCols(2));
  stream.channels = {layout.channels[1].name, layout.channels[0].name};  // out of order too
  stream.units = {"", ""};
  stream.samples.col(0) = full.streams[0].samples.col(1);
  stream.samples.col(1) = full.streams[0].samples.col(0);
  const auto extractor = make_generic_extractor({});
  const FeatureResult expected = run(*extractor, full, layout, whole(full));
  const FeatureResult got = run(*extractor, partial, layout, whole(partial));
  ASSERT_TRUE(got.skip_reason.empty()) << got.skip_reason;
  ASSERT_EQ(got.values.size(), expected.values.size());
  for (size_t k = 0; k < got.values.size(); ++k)
    EXPECT_TRUE(got.values[k] == expected.values[k] ||
                (std::isnan(got.values[k]) && std::isnan(expected.values[k])))
        << extractor->columns(layout)[k].name;
  // A channel the layout lacks is still an error.
  stream.channels[0] = "not-in-the-layout";
  EXPECT_THROW(run(*extractor, partial, layout, whole(partial)), Error);
}

TEST(FeatureRegistry, ListsGenericAndNamesAnUnknownPipeline) {
  const std::vector<std::string> names = feature_pipelines();
  EXPECT_NE(std::find(names.begin(), names.end(), "generic"), names.end());
  EXPECT_EQ(make_feature_extractor("generic")->name(), "generic");
  try {
    make_feature_extractor("kabolli");
    FAIL() << "unknown pipeline accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("kabolli"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("generic"), std::string::npos);
  }
}

// A saved model records its pipeline's settings with the defaults filled in: for every
// pipeline the recorded text builds a pipeline that records the same text again, and the
// values given stay as given.
TEST(FeatureRegistry, EffectiveParametersRebuildTheSamePipeline) {
  for (const std::string& name : feature_pipelines()) {
    const std::string effective = effective_pipeline_parameters(name, "", "test");
    EXPECT_EQ(effective_pipeline_parameters(name, effective, "test"), effective) << name;
  }
  const std::string kaboli = effective_pipeline_parameters("kaboli", "motion_hz=5", "test");
  EXPECT_NE(kaboli.find("motion_hz=5"), std::string::npos) << kaboli;
  EXPECT_NE(kaboli.find("motion_order=4"), std::string::npos) << kaboli;  // this build's default
  EXPECT_NE(kaboli.find("threshold_mm="), std::string::npos) << kaboli;
  EXPECT_THROW(effective_pipeline_parameters("kaboli", "motion_order=3", "test"), Error);
  EXPECT_THROW(effective_pipeline_parameters("kaboli", "speed=3", "test"), Error);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

TEST(GenericShape, EachDescriptorMatchesItsDefinition) {
  // A 5 Hz sine at 100 Hz over 2 s riding on a rest level of 10: all its energy below fs/16
  // (6.25 Hz), 20 mean crossings a second.
  std::vector<double> sine(200);
  for (size_t k = 0; k < sine.size(); ++k)
    sine[k] = 10.0 + std::sin(2.0 * M_PI * 5.0 * static_cast<double>(k) / 100.0);
  const ChannelShape wave = channel_shape(sine, 100.0, 10.0, false);
  EXPECT_NEAR(wave.band_low, 1.0, 1e-9);
  EXPECT_NEAR(wave.band_high, 0.0, 1e-9);
  EXPECT_NEAR(wave.zero_crossings, 10.0, 0.5);  // 20 crossings of the mean in 2 s
  EXPECT_NEAR(wave.median, 10.0, 0.05);
  EXPECT_NEAR(wave.q90, 10.95, 0.01);  // a sine's 90th percentile: sin(0.35 pi)
  // A 30 Hz sine: above fs/8 (12.5 Hz).
  for (size_t k = 0; k < sine.size(); ++k)
    sine[k] = std::sin(2.0 * M_PI * 30.0 * static_cast<double>(k) / 100.0);
  EXPECT_NEAR(channel_shape(sine, 100.0, 0.0, false).band_high, 1.0, 1e-9);

  // A press: rest 0 for 0.5 s, a ramp to 4 over 0.2 s, held 0.6 s, released in 0.2 s, rest
  // 0.5 s, at 100 Hz, with noise of 0.001.
  std::vector<double> press;
  for (int k = 0; k < 50; ++k) press.push_back(0.001 * ((k % 3) - 1));
  for (int k = 1; k <= 20; ++k) press.push_back(0.2 * k);
  for (int k = 0; k < 60; ++k) press.push_back(4.0 + 0.001 * ((k % 3) - 1));
  for (int k = 19; k >= 0; --k) press.push_back(0.2 * k);
  for (int k = 0; k < 50; ++k) press.push_back(0.001 * ((k % 3) - 1));
  const ChannelShape shape = channel_shape(press, 100.0, 0.0, false);
  EXPECT_NEAR(shape.onset_slope, 20.0, 1e-9);    // 0.2 per sample at 100 Hz
  EXPECT_NEAR(shape.release_slope, -20.0, 0.2);  // the hold's noise adds a little
  EXPECT_NEAR(shape.active_seconds, 1.0, 0.02);  // the ramps and the hold
  EXPECT_NEAR(shape.envelope[0], 0.0, 0.01);     // the first eighth is rest
  EXPECT_NEAR(shape.envelope[4], 4.0, 0.01);     // the middle is the hold
  EXPECT_DOUBLE_EQ(shape.peaks, 0.5);            // one press in 2 s, its noisy hold counted once
  // Segments of another length give the same envelope: the parts are fractions.
  std::vector<double> twice;
  for (double value : press) twice.insert(twice.end(), {value, value});
  EXPECT_NEAR(channel_shape(twice, 200.0, 0.0, false).envelope[4], shape.envelope[4], 1e-9);

  EXPECT_NEAR(correlation(press, press), 1.0, 1e-12);
  std::vector<double> inverted(press.size());
  for (size_t k = 0; k < press.size(); ++k) inverted[k] = -press[k];
  EXPECT_NEAR(correlation(press, inverted), -1.0, 1e-12);
  EXPECT_EQ(correlation(std::vector<double>(5, 1.0), press), 0.0);
  // A constant channel: every descriptor finite.
  const ChannelShape flat = channel_shape(std::vector<double>(10, 3.0), 10.0, std::nan(""), false);
  EXPECT_EQ(flat.band_low + flat.band_mid + flat.band_high, 0.0);
  EXPECT_EQ(flat.active_seconds, 0.0);
}

}  // namespace
}  // namespace tactile

// XDF files as LabRecorder 1.x writes them when clocks misbehave (issue 44), written by
// xdf_writer.h: clock offsets that drift (a span shorter by microseconds), a device clock reset
// mid-recording (stamps back by hours, offsets measured on both sides), and a marker at the
// data's end. LabRecorder 1.x writes a stream's header, its ClockOffset chunks (one measurement
// every 5 s, collection times on the stream's clock) between its Samples chunks, and a footer.
#include <gtest/gtest.h>

#include <cmath>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/layout/skin_layout.h"
#include "xdf_writer.h"

namespace tactile {
namespace {

using testing::refusal_of;
using testing::TemporaryDirectory;
using testing::XdfWriter;

const SkinLayout& counter_layout() {
  static const SkinLayout layout = make_strip_layout(1);
  return layout;
}

// One float32 channel holding the sample's index: a counter shows where each sample went.
void counter_samples(XdfWriter& writer, uint32_t id, int first, int count, double first_stamp,
                     double rate_hz) {
  std::vector<double> stamps;
  std::vector<std::vector<float>> values;
  for (int k = 0; k < count; ++k) {
    stamps.push_back(first_stamp + k / rate_hz);
    values.push_back({static_cast<float>(first + k)});
  }
  writer.float_samples(id, stamps, values);
}

//---- Drift -----------------------------------------------------------------------------------

TEST(XdfDrift, ASpanShortenedByMicrosecondsKeepsItsLastSample) {
  // A counter of 10 samples at 100 Hz whose clock offsets drift by -3 us over its 0.09 s: the
  // corrected span is 0.089997 s, 8.9997 steps. All 10 samples are read.
  TemporaryDirectory folder;
  XdfWriter writer;
  writer.stream_header(1, "Counter", "Counter", 1, 100.0, "float32");
  writer.clock_offset(1, 500.0, 0.125);
  counter_samples(writer, 1, 0, 10, 500.0, 100.0);
  writer.clock_offset(1, 500.09, 0.125 - 3e-6);
  writer.footer(1, 10);
  writer.save(folder.file("counter.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("counter.xdf"), counter_layout(), {});
  const Stream& stream = imported.recording.streams.front();
  ASSERT_EQ(stream.sample_count(), 10);
  for (int64_t row = 0; row < 10; ++row)
    EXPECT_NEAR(stream.samples(row, 0), static_cast<float>(row), 1e-3) << row;
  EXPECT_EQ(stream.samples(9, 0), 9.0f) << "the last grid point takes the last sample";
}

TEST(XdfDrift, TheGridRunsToThePointNearestTheLastStamp) {
  SampleMatrix values(3, 1);
  values << 0.0f, 1.0f, 2.0f;
  // 2 steps less 3 us: 3 points, not 2.
  const SampleMatrix shortened = resample_to_rate({0.0, 0.01, 0.02 - 3e-6}, values, 100.0, "s");
  ASSERT_EQ(shortened.rows(), 3);
  EXPECT_EQ(shortened(2, 0), 2.0f);
  // 2.4 steps: the grid ends at 2 steps, interpolated between the last two samples.
  const SampleMatrix late = resample_to_rate({0.0, 0.01, 0.024}, values, 100.0, "s");
  ASSERT_EQ(late.rows(), 3);
  EXPECT_NEAR(late(2, 0), 1.0f + 10.0f / 14.0f, 1e-5);
}

//---- Clock resets ----------------------------------------------------------------------------

// A counter at 10 Hz whose device clock was reset after 15 s (sample 150): its stamps go from
// 7214.9 back to 3.0, and LabRecorder measures an offset of 100 s before the reset and of
// 7312 s after it, so on the recorder's clock the samples run on without a break. Three
// measurements on each side, 5 s apart. A markers stream on the same device: "press start"
// before the reset, "press end" after it.
XdfWriter clock_reset_session(bool offsets_after_reset = true) {
  XdfWriter writer;
  writer.stream_header(1, "Counter", "Counter", 1, 10.0, "float32");
  writer.stream_header(2, "Presses", "Markers", 1, 0.0, "string");
  for (int k = 0; k < 3; ++k) {
    writer.clock_offset(1, 7200.0 + 5.0 * k, 100.0 + 1e-6 * k);
    writer.clock_offset(2, 7200.0 + 5.0 * k, 100.0 + 1e-6 * k);
    counter_samples(writer, 1, 50 * k, 50, 7200.0 + 5.0 * k, 10.0);
  }
  writer.string_samples(2, {7205.0}, {"press start"});
  for (int k = 0; k < 3; ++k) {
    if (offsets_after_reset) {
      writer.clock_offset(1, 4.0 + 5.0 * k, 7312.0 - 1e-6 * k);
      writer.clock_offset(2, 4.0 + 5.0 * k, 7312.0 - 1e-6 * k);
    }
    counter_samples(writer, 1, 150 + 50 * k, 50, 3.0 + 5.0 * k, 10.0);
  }
  writer.string_samples(2, {5.0}, {"press end"});
  writer.footer(1, 300);
  writer.footer(2, 2);
  return writer;
}

TEST(XdfClockReset, ResetsAreWhereCollectionTimesGoBackAndOffsetsJump) {
  const std::vector<std::pair<double, double>> offsets = {
      {7200.0, 100.0}, {7205.0, 100.0}, {7210.0, 100.0}, {4.0, 7312.0}, {9.0, 7312.0}};
  EXPECT_EQ(xdf_clock_resets(offsets), std::vector<size_t>{3});
  // A collection time that goes back with an offset that stays (measurements written late)
  // is no reset, nor is an offset that jumps by less than a second.
  EXPECT_TRUE(xdf_clock_resets({{20.0, 2.0}, {10.0, 1.9}, {30.0, 2.1}}).empty());
  // A clock set forward: the collection times jump far beyond the usual 5 s.
  EXPECT_EQ(xdf_clock_resets(
                {{0.0, 50.0}, {5.0, 50.0}, {10.0, 50.0}, {3610.0, -3540.0}, {3615.0, -3540.0}}),
            std::vector<size_t>{3});
  EXPECT_TRUE(xdf_clock_resets({{0.0, 50.0}, {5.0, 9000.0}}).empty()) << "too few to tell";
}

TEST(XdfClockReset, AStreamWhoseDeviceClockWasResetIsReadSegmentBySegment) {
  TemporaryDirectory folder;
  clock_reset_session().save(folder.file("reset.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("reset.xdf"), counter_layout(), {});
  const Stream& stream = imported.recording.streams.front();
  ASSERT_EQ(stream.sample_count(), 300);
  for (int64_t row = 0; row < 300; ++row)
    ASSERT_NEAR(stream.samples(row, 0), static_cast<float>(row), 1e-3) << row;
  EXPECT_EQ(imported.recording.metadata.at("xdf_first_timestamp"), "7300");
  // The markers, on the same device, are corrected by their own segments: press start at
  // 7205 + 100.000001 - 7300 = 5.000001 s, press end at 5 + 7311.9999998 - 7300 = 16.9999998 s
  // (the offsets' microseconds of drift, interpolated).
  ASSERT_EQ(imported.labels.size(), 1u);
  EXPECT_EQ(imported.labels[0].class_name, "press");
  EXPECT_NEAR(imported.labels[0].t0, 5.000001, 1e-9);
  EXPECT_NEAR(imported.labels[0].t1, 16.9999998, 1e-9);
}

TEST(XdfClockReset, AResetTheOffsetsDoNotShowIsRefusedAtTheSampleWhereTheStampsJumpBack) {
  // No measurement after the reset: nothing says where the new clock lies.
  TemporaryDirectory folder;
  clock_reset_session(false).save(folder.file("reset.xdf"));
  const std::string refusal =
      refusal_of([&] { import_xdf(folder.file("reset.xdf"), counter_layout(), {}); });
  EXPECT_NE(refusal.find("stream \"Counter\": sample 150's time stamp"), std::string::npos)
      << refusal;
  EXPECT_NE(refusal.find("is before sample 149's"), std::string::npos) << refusal;
}

//---- Markers at the end ----------------------------------------------------------------------

TEST(XdfMarkersAtTheEnd, AMarkerAtTheDatasEndMakesNoSliverOfALabel) {
  // 90 samples at 100 Hz (the data ends at 0.9 s) and a "stop" marker sent as the data stopped,
  // stamped 1.4e-13 s before the end: its label would be [0.89999999999986, 0.9).
  TemporaryDirectory folder;
  XdfWriter writer;
  writer.stream_header(1, "Counter", "Counter", 1, 100.0, "float32");
  writer.stream_header(2, "Events", "Markers", 1, 0.0, "string");
  counter_samples(writer, 1, 0, 90, 2000.0, 100.0);
  writer.string_samples(2, {2000.3, 2000.8999999999999}, {"stroke", "stop"});
  writer.footer(1, 90);
  writer.footer(2, 2);
  writer.save(folder.file("end.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("end.xdf"), counter_layout(), {});
  ASSERT_EQ(imported.recording.streams.front().sample_count(), 90);
  ASSERT_EQ(imported.labels.size(), 1u);
  EXPECT_EQ(imported.labels[0].class_name, "stroke");
  EXPECT_NEAR(imported.labels[0].t1, 0.9, 1e-9);
  const std::string dropped = imported.recording.metadata.at("dropped_labels");
  EXPECT_NE(dropped.find("marker 1 \"stop\" at 0.89999999999986"), std::string::npos) << dropped;
  EXPECT_NE(dropped.find("shorter than one sample (0.01 s)"), std::string::npos) << dropped;
}

TEST(XdfMarkersAtTheEnd, LabelsUnderOneSampleAreDroppedAndSaidOneSampleIsKept) {
  const XdfMarkerLabels paired = labels_from_markers(
      {{0.1, "tap start"}, {0.105, "tap end"}, {0.3, "pat"}, {0.31, "none"}, {0.9, "late"}}, 0.9,
      0.01, "m");
  ASSERT_EQ(paired.labels.size(), 1u);
  EXPECT_EQ(paired.labels[0].class_name, "pat") << "0.31 - 0.3 is one sample, give or take";
  ASSERT_EQ(paired.dropped.size(), 2u);
  EXPECT_EQ(paired.dropped[0],
            "marker 0 \"tap start\" at 0.1 s: its label [0.1, 0.105) is shorter than one sample "
            "(0.01 s)");
  EXPECT_EQ(paired.dropped[1], "marker 4 \"late\" at 0.9 s: at or after the data's end (0.9 s)");
}

}  // namespace
}  // namespace tactile

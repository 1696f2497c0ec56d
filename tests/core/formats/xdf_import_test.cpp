// XDF recordings (docs/IMPORT.md, "XDF"): files written per the specification by
// xdf_writer.h, checked in libxdf itself, then imported and checked value by value (the
// resampled grid, the dropout's gap, the interpolated points, the markers' labels, the clock
// offsets); stream choice, marker pairing and malformed files.
#include <gtest/gtest.h>
#include <xdf.h>

#include <cmath>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/xdf_files.h"
#include "tactile/layout/skin_layout.h"
#include "test_paths.h"
#include "xdf_writer.h"

namespace tactile {
namespace {

using testing::refusal_of;

using testing::TemporaryDirectory;
using testing::XdfGloveSample;
using testing::XdfWriter;

const SkinLayout& glove_layout() {
  static const SkinLayout layout = make_strip_layout(8);
  return layout;
}

TEST(XdfImport, TheWritersFilesLoadInLibxdfAsWritten) {
  // libxdf reads the writer's chunks as the writer meant them (the XML chunks end in a NUL
  // byte here: libxdf reads past the buffer of one without).
  TemporaryDirectory folder;
  testing::xdf_glove_session(true).save(folder.file("glove.xdf"));
  Xdf xdf;
  ASSERT_EQ(xdf.load_xdf(folder.file("glove.xdf")), 0);
  ASSERT_EQ(xdf.streams.size(), 2u);
  const Xdf::Stream& glove = xdf.streams[0];
  EXPECT_EQ(glove.info.name, "TactileGlove");
  EXPECT_EQ(glove.info.channel_count, 8);
  EXPECT_EQ(glove.info.nominal_srate, 100.0);
  const auto samples = testing::xdf_glove_samples();
  ASSERT_EQ(glove.time_stamps.size(), samples.size());
  ASSERT_EQ(glove.time_series.size(), 8u);
  for (size_t k = 0; k < samples.size(); ++k) {
    // libxdf itself adds the clock offset measured last (+0.25 s here).
    EXPECT_NEAR(glove.time_stamps[k], samples[k].stamp + 0.25, 1e-9) << k;
    EXPECT_EQ(glove.time_series[3][k], samples[k].value(3)) << k;
  }
  const auto markers = testing::xdf_glove_markers();
  size_t events = 0;
  for (const auto& [event, stream] : xdf.eventMap) {
    if (stream != 1) continue;
    ASSERT_LT(events, markers.size());
    EXPECT_EQ(event.first, markers[events].text);
    EXPECT_NEAR(event.second, markers[events].stamp + 0.3, 1e-9);
    ++events;
  }
  EXPECT_EQ(events, markers.size());
}

TEST(XdfImport, TheScanListsEveryStreamWithWhatItDeclares) {
  TemporaryDirectory folder;
  testing::xdf_glove_session().save(folder.file("glove.xdf"));
  const std::vector<XdfStreamInfo> streams = scan_xdf(folder.file("glove.xdf"));
  ASSERT_EQ(streams.size(), 2u);
  EXPECT_EQ(streams[0].name, "TactileGlove");
  EXPECT_EQ(streams[0].type, "Tactile");
  EXPECT_EQ(streams[0].format, "float32");
  EXPECT_EQ(streams[0].channels, 8);
  EXPECT_EQ(streams[0].rate_hz, 100.0);
  EXPECT_EQ(streams[0].samples, 55);
  EXPECT_EQ(streams[0].sample_chunks.size(), 3u);
  ASSERT_EQ(streams[0].clock_offsets.size(), 2u);
  EXPECT_EQ(streams[0].clock_offsets[1], std::make_pair(1001.0, 0.25));
  EXPECT_EQ(streams[1].name, "Touches");
  EXPECT_EQ(streams[1].format, "string");
  EXPECT_EQ(streams[1].rate_hz, 0.0);
  EXPECT_EQ(streams[1].samples, 8);
}

TEST(XdfImport, TheGloveIsResampledOntoItsRateWithTheDropoutAGap) {
  TemporaryDirectory folder;
  testing::xdf_glove_session().save(folder.file("glove.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("glove.xdf"), glove_layout(), {});
  const Recording& recording = imported.recording;
  EXPECT_EQ(recording.id, "glove");
  EXPECT_EQ(recording.layout_id, glove_layout().id);
  EXPECT_EQ(recording.metadata.at("xdf_stream"), "TactileGlove");
  EXPECT_EQ(recording.metadata.at("xdf_markers"), "Touches");
  // The first stamp, 999.998, plus the glove's clock offset of 0.25 s.
  EXPECT_NEAR(std::stod(recording.metadata.at("xdf_first_timestamp")), 1000.248, 1e-9);
  ASSERT_EQ(recording.streams.size(), 1u);
  const Stream& stream = recording.streams.front();
  EXPECT_EQ(stream.rate_hz, 100.0);
  EXPECT_TRUE(stream.timestamps.empty());
  // Stamps 999.998 .. 1000.591: 0.593 s at 100 Hz, 60 grid points.
  ASSERT_EQ(stream.sample_count(), 60);
  ASSERT_EQ(stream.channel_count(), 8);

  // Every grid point against the samples around it, found here by a plain search.
  const auto samples = testing::xdf_glove_samples();
  const double first = samples.front().stamp;
  for (int64_t row = 0; row < 60; ++row) {
    const double t = first + 0.01 * static_cast<double>(row);
    size_t below = 0;
    for (size_t k = 0; k < samples.size(); ++k)
      if (samples[k].stamp <= t + 1e-12) below = k;
    for (int channel = 0; channel < 8; ++channel) {
      const float got = stream.samples(row, channel);
      if (below + 1 == samples.size() || std::abs(samples[below].stamp - t) < 1e-9) {
        EXPECT_NEAR(got, samples[below].value(channel), 1e-4) << row;
        continue;
      }
      const XdfGloveSample& a = samples[below];
      const XdfGloveSample& b = samples[below + 1];
      if (b.stamp - a.stamp > 0.015) {
        EXPECT_TRUE(std::isnan(got)) << "row " << row << " channel " << channel;
      } else {
        const double weight = (t - a.stamp) / (b.stamp - a.stamp);
        EXPECT_NEAR(got, a.value(channel) + weight * (b.value(channel) - a.value(channel)), 1e-4)
            << row;
      }
    }
  }
  // By hand: row 0 is sample 0; the dropout (samples 31-35 missing, 30 at 1000.298 and 36 at
  // 1000.360) leaves rows 31-36 gaps; row 37 (1000.368) is 2/3 of the way from sample 36 to
  // 37 (1000.372); row 11 (1000.108) lies between the deduced stamps 1000.101 and 1000.111.
  EXPECT_EQ(stream.samples(0, 0), 0.25f);
  EXPECT_EQ(stream.samples(0, 7), 700.25f);
  for (int64_t row = 31; row <= 36; ++row) EXPECT_TRUE(std::isnan(stream.samples(row, 2))) << row;
  EXPECT_FALSE(std::isnan(stream.samples(30, 2)));
  EXPECT_NEAR(stream.samples(30, 2), 230.25f, 1e-3);
  EXPECT_NEAR(stream.samples(37, 0), 36.25 + 2.0 / 3.0, 1e-4);
  EXPECT_NEAR(stream.samples(37, 5), 536.25 + 2.0 / 3.0, 1e-4);
  EXPECT_NEAR(stream.samples(11, 1), 110.25 + 0.7, 1e-4);
}

TEST(XdfImport, MarkersBecomeGroundTruthLabelsOnTheGlovesClock) {
  TemporaryDirectory folder;
  testing::xdf_glove_session().save(folder.file("glove.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("glove.xdf"), glove_layout(), {});
  // A marker at m is at m + 0.3 - (999.998 + 0.25) = m - 999.948 s of the recording.
  ASSERT_EQ(imported.labels.size(), 4u);
  const std::vector<std::tuple<std::string, double, double>> expected = {{"stroke", 0.152, 0.252},
                                                                         {"pat", 0.302, 0.452},
                                                                         {"poke", 0.502, 0.552},
                                                                         {"Tap", 0.572, 0.60}};
  for (size_t k = 0; k < expected.size(); ++k) {
    const Label& label = imported.labels[k];
    EXPECT_EQ(label.class_name, std::get<0>(expected[k]));
    EXPECT_NEAR(label.t0, std::get<1>(expected[k]), 1e-9) << k;
    EXPECT_NEAR(label.t1, std::get<2>(expected[k]), 1e-9) << k;  // Tap: clipped to the end
    EXPECT_EQ(label.region, "all");
    EXPECT_EQ(label.annotator, "import");
    EXPECT_EQ(label.source, LabelSource::kGroundTruth);
  }
}

TEST(XdfImport, TheCommittedFixtureIsTheWritersSession) {
  const std::string fixture = test::test_data_dir() + "/interop/glove_session.xdf";
  EXPECT_EQ(testing::read_text(fixture), testing::xdf_glove_session().bytes());
  EXPECT_EQ(import_xdf(fixture, glove_layout(), {}).labels.size(), 4u);
}

TEST(XdfImport, LoadingPrintsNothingAndLeavesOtherOutputAlone) {
  TemporaryDirectory folder;
  testing::xdf_glove_session().save(folder.file("glove.xdf"));
  ::testing::internal::CaptureStdout();
  import_xdf(folder.file("glove.xdf"), glove_layout(), {});
  std::cout << "after" << std::flush;
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "after");
}

XdfWriter two_numeric_streams() {
  XdfWriter writer;
  writer.stream_header(7, "TactileGlove", "Tactile", 8, 100.0, "float32");
  writer.stream_header(9, "Wrist", "Accelerometer", 3, 50.0, "int16");
  writer.float_samples(7, {1.0, 1.01}, {std::vector<float>(8, 1.0f), std::vector<float>(8, 2.0f)});
  std::string content =
      XdfWriter::id_bytes(9) + XdfWriter::length_bytes(1) + XdfWriter::stamp_bytes(1.0);
  const int16_t axes[3] = {1, 2, 3};
  content += XdfWriter::raw(axes, 6);
  writer.chunk(3, content);
  return writer;
}

TEST(XdfImport, SeveralCandidateStreamsAreListedAndOneIsChosenByNameOrType) {
  TemporaryDirectory folder;
  two_numeric_streams().save(folder.file("two.xdf"));
  const std::string path = folder.file("two.xdf");
  const std::string refusal = refusal_of([&] { import_xdf(path, glove_layout(), {}); });
  EXPECT_NE(refusal.find("--stream: " + path + " has 2 numeric streams with a nominal rate"),
            std::string::npos)
      << refusal;
  EXPECT_NE(
      refusal.find("\"TactileGlove\" (type \"Tactile\", 8 float32 channels, 100 Hz, 2 samples)"),
      std::string::npos)
      << refusal;
  EXPECT_NE(refusal.find("\"Wrist\" (type \"Accelerometer\", 3 int16 channels, 50 Hz, 1 samples)"),
            std::string::npos)
      << refusal;
  EXPECT_EQ(import_xdf(path, glove_layout(), {"TactileGlove", ""})
                .recording.streams.front()
                .sample_count(),
            2);
  EXPECT_EQ(import_xdf(path, glove_layout(), {"type:Tactile", ""})
                .recording.streams.front()
                .sample_count(),
            2);
  // The wrist's 3 channels are not the glove layout's 8.
  EXPECT_NE(refusal_of([&] {
              import_xdf(path, glove_layout(), {"Wrist", ""});
            }).find("stream \"Wrist\": has 3 channels, layout " + glove_layout().id + " has 8"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              import_xdf(path, glove_layout(), {"Glove", ""});
            }).find("has no 'Glove' among its"),
            std::string::npos);
  // No markers stream: no labels, no refusal; one named that is not there is refused.
  EXPECT_TRUE(import_xdf(path, glove_layout(), {"TactileGlove", ""}).labels.empty());
  EXPECT_NE(refusal_of([&] {
              import_xdf(path, glove_layout(), {"TactileGlove", "Touches"});
            }).find("--markers"),
            std::string::npos);
}

TEST(XdfImport, EmptyTicksOfAMarkersStreamWithARateAreNoMarkers) {
  TemporaryDirectory folder;
  XdfWriter writer;
  writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
  writer.stream_header(2, "Ticks", "Markers", 1, 10.0, "string");
  std::vector<double> stamps;
  std::vector<std::vector<float>> values;
  for (int k = 0; k <= 100; ++k) {
    stamps.push_back(0.01 * k);
    values.emplace_back(8, 0.0f);
  }
  writer.float_samples(1, stamps, values);
  writer.string_samples(2, {0.0, 0.1, 0.2, 0.3, 0.4, 0.5}, {"", "pat", "", "", "none", ""});
  writer.save(folder.file("ticks.xdf"));
  const ImportedRecording imported = import_xdf(folder.file("ticks.xdf"), glove_layout(), {});
  ASSERT_EQ(imported.labels.size(), 1u);
  EXPECT_EQ(imported.labels[0].class_name, "pat");
  EXPECT_NEAR(imported.labels[0].t0, 0.1, 1e-9);
  EXPECT_NEAR(imported.labels[0].t1, 0.4, 1e-9);  // "none" ends it, not the empty ticks
}

std::vector<Label> paired(const std::vector<XdfMarker>& markers, double end = 10.0) {
  return labels_from_markers(markers, end, 0.01, "m").labels;
}

TEST(XdfMarkers, APlainMarkerLastsUntilTheNextAndNoneClosesIt) {
  const std::vector<Label> labels = paired(
      {{1.0, "stroke"}, {2.0, "pat"}, {3.0, "none"}, {4.0, "poke"}, {5.0, ""}, {6.0, "tap"}});
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[0].class_name, "stroke");
  EXPECT_EQ(labels[0].t0, 1.0);
  EXPECT_EQ(labels[0].t1, 2.0);
  EXPECT_EQ(labels[1].class_name, "pat");
  EXPECT_EQ(labels[1].t1, 3.0);
  EXPECT_EQ(labels[2].class_name, "poke");
  EXPECT_EQ(labels[2].t1, 5.0);
  EXPECT_EQ(labels[3].class_name, "tap");  // open at the end: ends with the recording
  EXPECT_EQ(labels[3].t1, 10.0);
}

TEST(XdfMarkers, StartAndEndPairWhateverTheirCase) {
  const std::vector<Label> labels = paired({{1.0, "Stroke START"},
                                            {2.5, "Stroke end"},
                                            {3.0, "pat begin"},
                                            {4.0, "pat End"},
                                            {5.0, "poke"},
                                            {6.0, "slap start"},
                                            {7.0, "slap end"}});
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[0].class_name, "Stroke");
  EXPECT_EQ(labels[0].t1, 2.5);
  EXPECT_EQ(labels[1].class_name, "pat");
  EXPECT_EQ(labels[2].class_name, "poke");  // closed by the start that follows it
  EXPECT_EQ(labels[2].t1, 6.0);
  EXPECT_EQ(labels[3].class_name, "slap");
  EXPECT_EQ(labels[3].t0, 6.0);
  EXPECT_EQ(labels[3].t1, 7.0);
}

TEST(XdfMarkers, LabelsAreClippedToTheRecordingAndEmptyOnesDropped) {
  const std::vector<Label> labels =
      paired({{-1.0, "a"}, {0.5, "b"}, {0.5, "c"}, {9.0, "d start"}, {12.0, "d end"}});
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].class_name, "a");
  EXPECT_EQ(labels[0].t0, 0.0);
  EXPECT_EQ(labels[1].class_name, "c");  // b lasted no time
  EXPECT_EQ(labels[2].t1, 10.0);
}

TEST(XdfMarkers, PairsThatDoNotCloseAreRefusedNamingTheMarkers) {
  EXPECT_EQ(
      refusal_of([] {
        paired({{1.0, "pat start"}, {2.0, "poke"}});
      }),
      "m marker 1: \"poke\" at 2 s inside \"pat start\" at 1 s, which only \"pat end\" closes");
  EXPECT_EQ(refusal_of([] {
              paired({{1.0, "pat end"}});
            }),
            "m marker 0: \"pat end\" at 1 s ends no \"pat start\"");
  EXPECT_EQ(refusal_of([] {
              paired({{1.0, "stroke"}, {2.0, "pat start"}});
            }),
            "m marker 1: \"pat start\" at 2 s is never ended");
  EXPECT_EQ(
      refusal_of([] {
        paired({{1.0, "pat start"}, {2.0, "poke end"}});
      }),
      "m marker 1: \"poke end\" at 2 s inside \"pat start\" at 1 s, which only \"pat end\" closes");
}

TEST(XdfClock, OffsetsAreInterpolatedBetweenMeasurementsAndHeldOutside) {
  const std::vector<std::pair<double, double>> offsets = {{10.0, 1.0}, {20.0, 2.0}, {30.0, 0.0}};
  EXPECT_EQ(clock_corrected(5.0, offsets), 6.0);
  EXPECT_EQ(clock_corrected(10.0, offsets), 11.0);
  EXPECT_DOUBLE_EQ(clock_corrected(12.5, offsets), 12.5 + 1.25);
  EXPECT_DOUBLE_EQ(clock_corrected(25.0, offsets), 25.0 + 1.0);
  EXPECT_EQ(clock_corrected(40.0, offsets), 40.0);
  EXPECT_EQ(clock_corrected(3.0, {}), 3.0);
}

TEST(XdfClock, OffsetsWrittenOutOfOrderAreUsedInTheOrderOfTheirCollectionTimes) {
  TemporaryDirectory folder;
  XdfWriter writer;
  writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
  writer.clock_offset(1, 20.0, 2.0);
  writer.clock_offset(1, 10.0, 1.0);
  writer.float_samples(1, {15.0}, {std::vector<float>(8, 1.0f)});
  writer.save(folder.file("late.xdf"));
  // The scan keeps the file's order (a clock reset is told by it); the import sorts.
  const std::vector<XdfStreamInfo> streams = scan_xdf(folder.file("late.xdf"));
  ASSERT_EQ(streams.front().clock_offsets.size(), 2u);
  EXPECT_EQ(streams.front().clock_offsets.front(), std::make_pair(20.0, 2.0));
  // 15 s is half way: offset 1.5 s.
  const ImportedRecording imported = import_xdf(folder.file("late.xdf"), glove_layout(), {});
  EXPECT_EQ(imported.recording.metadata.at("xdf_first_timestamp"), "16.5");
}

TEST(XdfResample, TwoSamplesUpToOneAndAHalfStepsApartAreInterpolatedFurtherIsAGap) {
  SampleMatrix values(2, 1);
  values << 0.0f, 3.0f;
  // 100 Hz: 0.015 s apart interpolates, 0.0151 s is a gap.
  const SampleMatrix near = resample_to_rate({0.0, 0.015}, values, 100.0, "s");
  ASSERT_EQ(near.rows(), 2);
  EXPECT_EQ(near(0, 0), 0.0f);
  EXPECT_NEAR(near(1, 0), 2.0f, 1e-5);
  // The grid runs to the point nearest the last stamp: 0.0151 s is nearer 0.02 than 0.01, so
  // that point takes the last sample, and 0.01 between the two is the gap.
  const SampleMatrix far = resample_to_rate({0.0, 0.0151}, values, 100.0, "s");
  ASSERT_EQ(far.rows(), 3);
  EXPECT_TRUE(std::isnan(far(1, 0)));
  EXPECT_EQ(far(2, 0), 3.0f);
  EXPECT_EQ(refusal_of([&] {
              resample_to_rate({0.0, -1.0}, values, 100.0, "s");
            }),
            "s: sample 1's time stamp -1 is before sample 0's 0");
  // A span that would need far more grid points than samples is refused before allocating.
  EXPECT_NE(refusal_of([&] {
              resample_to_rate({0.0, 1.0e9}, values, 100.0, "s");
            }).find("more than 8 grid points"),
            std::string::npos);
}

//---- Malformed files ----------------------------------------------------------------------

std::string scan_refusal(const std::string& bytes) {
  TemporaryDirectory folder;
  testing::write_text(folder.file("bad.xdf"), bytes);
  return refusal_of([&] { import_xdf(folder.file("bad.xdf"), glove_layout(), {}); });
}

std::string glove_header() {
  XdfWriter writer;
  writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
  return writer.bytes();
}

TEST(XdfImport, MalformedFilesAreRefusedNamingTheChunkAndItsByte) {
  EXPECT_NE(scan_refusal("XDF").find("not an XDF file"), std::string::npos);
  EXPECT_NE(scan_refusal("PK\x03\x04....").find("no \"XDF:\" at byte 0"), std::string::npos);
  // A chunk longer than the file (a recording cut short).
  const std::string header = glove_header();
  const std::string truncated = header + std::string("\x04\xff\xff\x00\x00\x03\x00", 7);
  EXPECT_NE(scan_refusal(truncated).find("chunk 2 at byte " + std::to_string(header.size()) +
                                         ": declares 65535 bytes, 2 are left in the file"),
            std::string::npos)
      << scan_refusal(truncated);
  EXPECT_NE(scan_refusal(header + "\x03\x01").find("length width 3 (XDF allows 1, 4 or 8)"),
            std::string::npos);
  {
    // One float sample short of its eight channels.
    XdfWriter writer;
    writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
    writer.float_samples(1, {1.0}, {std::vector<float>(7, 0.0f)});
    EXPECT_NE(scan_refusal(writer.bytes())
                  .find("sample 0: ends inside its values (28 bytes left, 32 for 8 float32)"),
              std::string::npos)
        << scan_refusal(writer.bytes());
  }
  {
    // Bytes after the samples (libxdf would read them as the next chunk).
    XdfWriter writer;
    writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
    writer.float_samples(1, {1.0}, {std::vector<float>(9, 0.0f)});
    EXPECT_NE(scan_refusal(writer.bytes()).find("4 bytes after its 1 samples"), std::string::npos);
  }
  {
    // A sample count the chunk cannot hold: refused before walking it.
    XdfWriter writer;
    writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "float32");
    writer.chunk(3, XdfWriter::id_bytes(1) + XdfWriter::length_bytes(0xffffffffu) + "\x08");
    EXPECT_NE(scan_refusal(writer.bytes()).find("4294967295 samples declared in 1 bytes"),
              std::string::npos);
  }
  {
    XdfWriter writer;
    writer.float_samples(4, {1.0}, {std::vector<float>(8, 0.0f)});
    EXPECT_NE(scan_refusal(writer.bytes())
                  .find("(stream 4): samples or clock offsets before the stream's header"),
              std::string::npos);
  }
  {
    XdfWriter writer;
    writer.stream_header(1, "TactileGlove", "Tactile", 100000000, 100.0, "float32");
    EXPECT_NE(scan_refusal(writer.bytes()).find("channel_count '100000000'"), std::string::npos);
  }
  {
    XdfWriter writer;
    writer.stream_header(2, "Touches", "Markers", 2, 0.0, "string");
    EXPECT_NE(scan_refusal(writer.bytes()).find("a string stream of 2 channels"),
              std::string::npos);
  }
  {
    XdfWriter writer;
    writer.chunk(2, XdfWriter::id_bytes(1) + "<info><name>x</name>");
    EXPECT_NE(scan_refusal(writer.bytes()).find("stream header is not XML"), std::string::npos);
  }
  {
    // A damaged header's control bytes are quoted printable, not sent to the terminal.
    XdfWriter writer;
    writer.chunk(2, XdfWriter::id_bytes(1) +
                        "<info><name>g</name><channel_count>8\x01\x7f</channel_count>"
                        "<nominal_srate>100</nominal_srate><channel_format>float32"
                        "</channel_format></info>");
    EXPECT_NE(scan_refusal(writer.bytes()).find("channel_count '8\\x01\\x7F': a whole number"),
              std::string::npos)
        << scan_refusal(writer.bytes());
  }
  {
    XdfWriter writer;
    writer.stream_header(1, "TactileGlove", "Tactile", 8, 100.0, "complex64");
    EXPECT_NE(scan_refusal(writer.bytes()).find("channel_format 'complex64'"), std::string::npos);
  }
  {
    // A markers stream only: nothing to import.
    XdfWriter writer;
    writer.stream_header(2, "Touches", "Markers", 1, 0.0, "string");
    EXPECT_NE(scan_refusal(writer.bytes()).find("has no numeric streams with a nominal rate"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace tactile

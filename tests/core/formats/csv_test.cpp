#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/csv_files.h"

namespace tactile {
namespace {

using testing::bit_equal;
using testing::refusal_of;
using testing::TemporaryDirectory;
using testing::write_text;

// Name + number; built with append, as GCC 12 warns falsely (-Wrestrict) on "s" + string.
std::string numbered(std::string name, int number) { return name.append(std::to_string(number)); }

SkinLayout strip_layout(int channels, std::vector<std::string> classes = {}) {
  SkinLayout layout;
  layout.id = numbered("strip:", channels);
  for (int index = 0; index < channels; ++index)
    layout.channels.push_back({numbered("s", index), "N", "force"});
  layout.classes = std::move(classes);
  return layout;
}

//---- long

TEST(CsvLong, TimeColumnGivesRateAndStartWithCrLfAndTrailingBlankLine) {
  TemporaryDirectory directory;
  const std::string path = directory.file("press.csv");
  write_text(path, "time,a,b,c\r\n2.5,1,2,3\r\n2.51,4,5,6.5\r\n2.52,-7,8e-3,9\r\n\r\n");
  const Recording recording = import_csv_long(path, strip_layout(3), {});
  EXPECT_EQ(recording.id, "press");
  EXPECT_EQ(recording.layout_id, "strip:3");
  ASSERT_EQ(recording.streams.size(), 1u);
  const Stream& stream = recording.streams[0];
  EXPECT_EQ(stream.name, "skin");
  EXPECT_EQ(stream.rate_hz, 100.0);
  EXPECT_EQ(stream.start_time, 2.5);
  EXPECT_TRUE(stream.timestamps.empty());
  EXPECT_EQ(stream.channels, (std::vector<std::string>{"s0", "s1", "s2"}));
  EXPECT_EQ(stream.units, (std::vector<std::string>{"N", "N", "N"}));
  ASSERT_EQ(stream.sample_count(), 3);
  EXPECT_EQ(stream.samples(1, 2), 6.5f);
  EXPECT_EQ(stream.samples(2, 0), -7.0f);
  EXPECT_EQ(stream.samples(2, 1), 8e-3f);
}

TEST(CsvLong, QuotedHeaderNamesAreRead) {
  TemporaryDirectory directory;
  const std::string path = directory.file("quoted.csv");
  write_text(path, "\"t\",\"left, arm\",\"say \"\"hi\"\"\"\n0,1,2\n0.5,3,4\n");
  const Recording recording = import_csv_long(path, strip_layout(2), {});
  EXPECT_EQ(recording.streams[0].rate_hz, 2.0);
  EXPECT_EQ(recording.streams[0].samples(1, 1), 4.0f);
}

TEST(CsvLong, IrregularTimeStepsKeepTheTimestamps) {
  TemporaryDirectory directory;
  const std::string path = directory.file("irregular.csv");
  write_text(path, "t,a\n0,1\n0.01,2\n0.02,3\n0.05,4\n0.06,5\n");
  const Stream stream = import_csv_long(path, strip_layout(1), {}).streams[0];
  EXPECT_DOUBLE_EQ(stream.rate_hz, 100.0);  // the median step
  EXPECT_EQ(stream.timestamps, (std::vector<double>{0, 0.01, 0.02, 0.05, 0.06}));
}

TEST(CsvLong, StepsWithinOnePercentStayRegular) {
  TemporaryDirectory directory;
  const std::string path = directory.file("jitter.csv");
  write_text(path, "t,a\n0,1\n0.01,2\n0.02005,3\n0.03,4\n");
  const Stream stream = import_csv_long(path, strip_layout(1), {}).streams[0];
  EXPECT_TRUE(stream.timestamps.empty());
}

TEST(CsvLong, RateOptionReplacesAMissingTimeColumn) {
  TemporaryDirectory directory;
  const std::string path = directory.file("no_time.csv");
  write_text(path, "a,b\n1,2\n3,4\n5,6\n");
  CsvLongOptions options;
  options.rate_hz = 50.0;
  options.stream_name = "pressure";
  const Stream stream = import_csv_long(path, strip_layout(2), options).streams[0];
  EXPECT_EQ(stream.name, "pressure");
  EXPECT_EQ(stream.rate_hz, 50.0);
  EXPECT_EQ(stream.sample_count(), 3);
  EXPECT_EQ(stream.samples(2, 0), 5.0f);

  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":1: no time column and no rate given");
}

TEST(CsvLong, ColumnCountMismatchWithTheLayoutIsAnError) {
  TemporaryDirectory directory;
  const std::string path = directory.file("four.csv");
  write_text(path, "time,a,b,c\n0,1,2,3\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(4), {}); }),
            path + ":1: 4 columns, but layout 'strip:4' has 4 channels (plus the time column)");
}

TEST(CsvLong, RaggedRowNamesItsLineAndFirstMissingColumn) {
  TemporaryDirectory directory;
  const std::string path = directory.file("ragged.csv");
  write_text(path, "t,a,b,c\n0,1,2,3\n0.1,4,5\n0.2,7,8,9\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(3), {}); }),
            path + ":3 column 4: row has 3 cells, header has 4");
  write_text(path, "t,a,b,c\n0,1,2,3\n0.1,4,5,6\n0.2,7,8,9,10\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(3), {}); }),
            path + ":4 column 5: row has 5 cells, header has 4");
}

TEST(CsvLong, NonNumericCellNamesLineAndColumn) {
  TemporaryDirectory directory;
  const std::string path = directory.file("text.csv");
  write_text(path, "t,a,b\n0,1,2\n0.1,3,4\n0.2,5,abc\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":4 column 3: not a number: 'abc'");
  write_text(path, "t,a,b\n0,1,\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":2 column 3: empty cell");
}

TEST(CsvLong, NanAndInfiniteCellsAreRefused) {
  TemporaryDirectory directory;
  const std::string path = directory.file("nan.csv");
  write_text(path, "t,a,b\n0,1,2\n0.1,NaN,4\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":3 column 2: NaN and infinite values are not accepted: 'NaN'");
  write_text(path, "t,a,b\n0,1,2\n0.1,3,-inf\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":3 column 3: NaN and infinite values are not accepted: '-inf'");
  write_text(path, "t,a,b\n0,1,2\n0.1,3,1e39\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":3 column 3: value '1e39' is out of range");
}

TEST(CsvLong, EmptyAndHeaderOnlyFilesAreErrors) {
  TemporaryDirectory directory;
  const std::string path = directory.file("empty.csv");
  write_text(path, "");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }), path + ": empty file");
  write_text(path, "\n  \r\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }), path + ": empty file");
  write_text(path, "t,a,b\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ": a header but no data rows");
}

TEST(CsvLong, MissingHeaderIsAnErrorRatherThanALostRow) {
  TemporaryDirectory directory;
  const std::string path = directory.file("headless.csv");
  write_text(path, "0,1,2\n0.1,3,4\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(2), {}); }),
            path + ":1: expected a header row, found numbers");
}

TEST(CsvLong, NonIncreasingTimeNamesItsLine) {
  TemporaryDirectory directory;
  const std::string path = directory.file("time.csv");
  write_text(path, "t,a\n0,1\n0.1,2\n0.1,3\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(1), {}); }),
            path + ":4 column 1: time 0.1 does not increase on the previous row");
}

TEST(CsvLong, BlankLineInsideTheDataIsAnError) {
  TemporaryDirectory directory;
  const std::string path = directory.file("gap.csv");
  write_text(path, "t,a\n0,1\n\n0.2,3\n");
  EXPECT_EQ(refusal_of([&] { import_csv_long(path, strip_layout(1), {}); }),
            path + ":3: blank line inside the data");
}

//---- long with class and grouping columns

TEST(CsvTable, WithoutClassOrGroupColumnsItIsTheLongImport) {
  TemporaryDirectory directory;
  const std::string path = directory.file("plain.csv");
  write_text(path, "time,a,b\n0,1,2\n0.02,3,4\n0.05,5,6\n");
  const std::vector<ImportedRecording> table = import_csv_table(path, strip_layout(2), {});
  ASSERT_EQ(table.size(), 1u);
  EXPECT_TRUE(table[0].labels.empty());
  const Recording long_shape = import_csv_long(path, strip_layout(2), {});
  EXPECT_EQ(table[0].recording.id, long_shape.id);
  EXPECT_EQ(table[0].recording.metadata, long_shape.metadata);
  const Stream& stream = table[0].recording.streams[0];
  EXPECT_EQ(stream.timestamps, (std::vector<double>{0, 0.02, 0.05}));
  EXPECT_EQ(stream.rate_hz, long_shape.streams[0].rate_hz);
  EXPECT_TRUE(testing::bit_equal(stream.samples, long_shape.streams[0].samples));
}

TEST(CsvTable, GroupsSplitRowsAndNameTheirErrorsPrecisely) {
  TemporaryDirectory directory;
  const std::string path = directory.file("groups.csv");
  write_text(path, "subject,t,a,gesture\ns1,0,1,pat\ns2,0,2,\ns1,0.1,3,pat\ns2,0.1,4,poke\n");
  CsvTableOptions options;
  options.class_column = "gesture";
  options.group_columns = {"subject"};
  const std::vector<ImportedRecording> groups = import_csv_table(path, strip_layout(1), options);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[1].recording.id, "groups-s2");
  EXPECT_EQ(groups[1].recording.streams[0].samples(1, 0), 4.0f);
  ASSERT_EQ(groups[1].labels.size(), 1u);
  EXPECT_EQ(groups[1].labels[0].class_name, "poke");

  write_text(path, "subject,t,a,gesture\ns1,0,1,pat\ns2,0,2,\ns1,0,3,pat\n");
  EXPECT_EQ(refusal_of([&] { import_csv_table(path, strip_layout(1), options); }),
            path + ":4 column 2: time 0 does not increase on the group's previous row");
  write_text(path, "subject,t,a,b,gesture\ns1,0,1,2,pat\n");
  EXPECT_EQ(
      refusal_of([&] { import_csv_table(path, strip_layout(1), options); }),
      path + ":1: 3 sample columns, but layout 'strip:1' has 1 channels (plus the time column)");
}

//---- wide

class CsvWide : public ::testing::Test {
 protected:
  CsvWideOptions options(const std::string& labels_text) {
    write_text(labels, labels_text);
    CsvWideOptions result;
    result.samples_per_capture = 3;
    result.labels_path = labels;
    result.class_names = {"poke", "pat", "slap"};
    result.rate_hz = 10.0;
    return result;
  }
  TemporaryDirectory directory;
  std::string captures = directory.file("captures.csv");
  std::string labels = directory.file("labels.csv");
};

TEST_F(CsvWide, CapturesAreLaidEndToEndChannelMajorWithGroundTruthLabels) {
  write_text(captures, "1,2,3,10,20,30\n4,5,6,40,50,60\n7,8,9,70,80,90\n");
  // A header line is tolerated; lines are names or 0-based indices.
  const ImportedRecording imported =
      import_csv_wide(captures, strip_layout(2), options("gesture\n1\nslap\r\n0\n"));
  const Stream& stream = imported.recording.streams[0];
  EXPECT_EQ(imported.recording.id, "captures");
  EXPECT_EQ(stream.rate_hz, 10.0);
  ASSERT_EQ(stream.sample_count(), 9);
  ASSERT_EQ(stream.channel_count(), 2);
  EXPECT_EQ(stream.samples(0, 0), 1.0f);
  EXPECT_EQ(stream.samples(2, 1), 30.0f);
  EXPECT_EQ(stream.samples(3, 0), 4.0f);
  EXPECT_EQ(stream.samples(8, 1), 90.0f);
  ASSERT_EQ(imported.labels.size(), 3u);
  EXPECT_EQ(imported.labels[0].class_name, "pat");
  EXPECT_EQ(imported.labels[1].class_name, "slap");
  EXPECT_EQ(imported.labels[2].class_name, "poke");
  const Label& second = imported.labels[1];
  EXPECT_DOUBLE_EQ(second.t0, 0.3);
  EXPECT_DOUBLE_EQ(second.t1, 0.6);
  EXPECT_EQ(second.recording, "captures");
  EXPECT_EQ(second.region, "all");
  EXPECT_EQ(second.source, LabelSource::kGroundTruth);
  EXPECT_EQ(second.annotator, "import");
}

TEST_F(CsvWide, ByteOrderMarkOfSpreadsheetsIsNotPartOfTheFirstNumber) {
  write_text(captures,
             "\xEF\xBB\xBF"
             "1.5,2,3\r\n4,5,6\r\n");
  const ImportedRecording imported =
      import_csv_wide(captures, strip_layout(1), options("\xEF\xBB\xBFpat\r\npoke\r\n"));
  EXPECT_EQ(imported.recording.streams[0].samples(0, 0), 1.5f);
  EXPECT_EQ(imported.labels[0].class_name, "pat");
}

TEST_F(CsvWide, LayoutClassesAreTheDefaultVocabulary) {
  write_text(captures, "1,2,3\n4,5,6\n");
  CsvWideOptions wide = options("2\ntickle\n");
  wide.class_names.clear();
  const ImportedRecording imported =
      import_csv_wide(captures, strip_layout(1, {"pat", "rub", "tickle"}), wide);
  EXPECT_EQ(imported.labels[0].class_name, "tickle");
  EXPECT_EQ(imported.labels[1].class_name, "tickle");
}

TEST_F(CsvWide, RowLengthNotAMultipleOfTheCaptureIsAnError) {
  write_text(captures, "1,2,3,4,5\n");
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(2), options("0\n")); }),
            captures + ":1: row has 5 values, not a multiple of samples_per_capture 3");
}

TEST_F(CsvWide, ChannelCountMismatchIsAnError) {
  write_text(captures, "1,2,3,4,5,6,7,8,9\n");
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(2), options("0\n")); }),
            captures + ":1: row has 3 channels of 3 samples, layout 'strip:2' has 2");
}

TEST_F(CsvWide, RaggedRowNamesItsLine) {
  write_text(captures, "1,2,3,4,5,6\n1,2,3,4,5,6\n1,2,3,4,5\n");
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(2), options("0\n1\n2\n")); }),
            captures + ":3 column 6: row has 5 cells, earlier rows have 6");
}

TEST_F(CsvWide, HeaderRowInTheCapturesIsNotANumber) {
  write_text(captures, "c0,c1,c2,c3,c4,c5\n1,2,3,4,5,6\n");
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(2), options("0\n0\n")); }),
            captures + ":1 column 1: not a number: 'c0'");
}

TEST_F(CsvWide, UnknownClassNamesItsLine) {
  write_text(captures, "1,2,3\n4,5,6\n7,8,9\n");
  EXPECT_EQ(
      refusal_of([&] { import_csv_wide(captures, strip_layout(1), options("pat\npoke\nhug\n")); }),
      labels + ":3 column 1: unknown class 'hug' (classes: poke, pat, slap; or a 0-based index)");
  EXPECT_EQ(
      refusal_of([&] { import_csv_wide(captures, strip_layout(1), options("pat\n3\npoke\n")); }),
      labels + ":2 column 1: unknown class '3' (classes: poke, pat, slap; or a 0-based index)");
}

TEST_F(CsvWide, LabelCountMustEqualCaptureCount) {
  write_text(captures, "1,2,3\n4,5,6\n7,8,9\n");
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(1), options("pat\npoke\n")); }),
            labels + ": 2 labels for 3 captures in " + captures);
}

TEST_F(CsvWide, OptionsAreChecked) {
  write_text(captures, "1,2,3\n");
  CsvWideOptions wide = options("pat\n");
  wide.samples_per_capture = 0;
  EXPECT_EQ(refusal_of([&] { import_csv_wide(captures, strip_layout(1), wide); }),
            "samples_per_capture: must be a positive number of samples");
  wide = options("pat\n");
  wide.rate_hz = 0.0;
  EXPECT_NE(refusal_of([&] { import_csv_wide(captures, strip_layout(1), wide); }).find("rate_hz: "),
            std::string::npos);
}

//---- export

Stream random_stream(int64_t samples, int channels, uint32_t seed) {
  std::mt19937 generator(seed);
  std::uniform_int_distribution<uint32_t> bits;
  Stream stream;
  stream.name = "skin";
  for (int channel = 0; channel < channels; ++channel)
    stream.channels.push_back(numbered("s", channel));
  stream.samples.resize(samples, channels);
  for (int64_t index = 0; index < stream.samples.size(); ++index) {
    float value;
    do value = std::bit_cast<float>(bits(generator));
    while (!std::isfinite(value));
    stream.samples.data()[index] = value;
  }
  stream.samples(0, 0) = -0.0f;
  stream.samples(1, 0) = std::numeric_limits<float>::denorm_min();
  stream.samples(2, 0) = 3e-39f;  // subnormal
  stream.samples(3, 0) = std::numeric_limits<float>::lowest();
  return stream;
}

TEST(CsvExport, ExportThenImportIsBitExact) {
  TemporaryDirectory directory;
  Recording recording;
  recording.id = "round";
  Stream stream = random_stream(2000, 3, 5);
  stream.rate_hz = 250.0;
  stream.start_time = 1.5;
  recording.streams = {stream};
  const std::string path = directory.file("round.csv");
  export_csv_long(path, recording);
  const Stream back = import_csv_long(path, strip_layout(3), {}).streams[0];
  EXPECT_TRUE(bit_equal(back.samples, stream.samples));
  EXPECT_EQ(back.rate_hz, 250.0);
  EXPECT_EQ(back.start_time, 1.5);
  EXPECT_TRUE(back.timestamps.empty());
  EXPECT_TRUE(std::signbit(back.samples(0, 0)));
}

TEST(CsvExport, IrregularStreamKeepsItsTimestampsThroughCsv) {
  TemporaryDirectory directory;
  Recording recording;
  Stream stream = random_stream(6, 1, 6);
  stream.name = "events";
  stream.rate_hz = 10.0;
  stream.timestamps = {0.1, 0.2, 0.35, 0.4, 0.9, 1.0000000000000002};
  Stream other = random_stream(4, 1, 7);
  other.rate_hz = 1.0;
  recording.streams = {other, stream};
  const std::string path = directory.file("events.csv");
  export_csv_long(path, recording, "events");
  const Stream back = import_csv_long(path, strip_layout(1), {}).streams[0];
  EXPECT_EQ(back.timestamps, stream.timestamps);
  EXPECT_TRUE(bit_equal(back.samples, stream.samples));
  EXPECT_EQ(refusal_of([&] { export_csv_long(path, recording, "pressure"); }),
            "recording : no stream 'pressure' (streams: skin, events)");
}

TEST(CsvExport, ExportFromAFileEqualsExportFromMemory) {
  TemporaryDirectory directory;
  Recording recording;
  recording.id = "file";
  Stream stream = random_stream(70000, 2, 8);  // more than one export block
  stream.rate_hz = 1000.0;
  stream.start_time = -2.0;
  stream.channels = {"left, arm", "right"};
  recording.streams = {stream};
  const std::string h5 = directory.file("file.h5");
  write_recording(h5, recording);
  export_csv_long(directory.file("memory.csv"), recording);
  export_csv_long(directory.file("file.csv"), RecordingFile(h5));
  const std::string text = testing::read_text(directory.file("file.csv"));
  EXPECT_EQ(text, testing::read_text(directory.file("memory.csv")));
  EXPECT_EQ(text.substr(0, text.find('\n')), "time_s,\"left, arm\",right");
}

TEST(CsvExport, FailedExportLeavesNothingBehind) {
  TemporaryDirectory directory;
  Recording recording;
  Stream stream = random_stream(10, 1, 9);
  stream.rate_hz = 0.0;  // no time base
  recording.streams = {stream};
  EXPECT_THROW(export_csv_long(directory.file("x.csv"), recording), Error);
  recording.streams[0].rate_hz = 10.0;
  EXPECT_THROW(export_csv_long(directory.file("missing/x.csv"), recording), Error);
  EXPECT_EQ(directory.entry_count(), 0);
}

}  // namespace
}  // namespace tactile

#include "tactile/io/hdf5_file.h"

#include <gtest/gtest.h>

#include <span>
// The tests damage files through HDF5's own API to check each error path; Debian
// installs the serial headers under hdf5/serial.
#include <hdf5/serial/hdf5.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

#include "io_test_files.h"
#include "tactile/error.h"

namespace tactile {
namespace {

using testing::bit_equal;
using testing::TemporaryDirectory;

// Random finite floats of every magnitude (uniform bit patterns), with the values
// that lossy paths get wrong placed at the start: subnormals, -0.0, the extremes.
SampleMatrix random_samples(int64_t samples, int64_t channels, uint32_t seed) {
  std::mt19937 generator(seed);
  std::uniform_int_distribution<uint32_t> bits;
  SampleMatrix matrix(samples, channels);
  for (int64_t index = 0; index < matrix.size(); ++index) {
    float value;
    do value = std::bit_cast<float>(bits(generator));
    while (!std::isfinite(value));
    matrix.data()[index] = value;
  }
  const float specials[] = {-0.0f,
                            std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::denorm_min(),
                            1e-40f,
                            std::numeric_limits<float>::min() / 3.0f,
                            std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::lowest(),
                            0.1f};
  for (size_t index = 0; index < std::size(specials) && index < size_t(matrix.size()); ++index)
    matrix.data()[index] = specials[index];
  return matrix;
}

Recording three_stream_recording() {
  Recording recording;
  recording.id = "subject-07_trial-3";
  recording.layout_id = "nao";
  recording.metadata = {
      {"subject", "Zoë Ünal"}, {"condition", "stationary"}, {"température", "21 °C — 東京"}};
  // Not in alphabetical order: the file keeps the order of writing.
  Stream skin;
  skin.name = "skin";
  skin.rate_hz = 250.0;
  skin.start_time = 12.5;
  skin.channels = {"c01.f1", "c01.f2", "c01.f3"};
  skin.units = {"N", "N", "N"};
  skin.samples = random_samples(1000, 3, 1);
  Stream imu;
  imu.name = "imu";
  imu.rate_hz = 100.0;
  imu.channels = {"ax", "ay"};
  imu.units = {"g", ""};
  imu.samples = random_samples(37, 2, 2);
  // Irregular sampling: strictly increasing gaps of varying size.
  for (int index = 0; index < 37; ++index)
    imu.timestamps.push_back(0.01 * index + 1e-3 * (index % 5) * (index % 3));
  Stream events;
  events.name = "aux";
  events.rate_hz = 1.0;
  events.channels = {"marker"};
  events.samples = SampleMatrix(0, 1);
  recording.streams = {skin, imu, events};
  return recording;
}

TEST(Hdf5File, RoundTripIsBitExact) {
  TemporaryDirectory directory;
  const std::string path = directory.file("round.h5");
  const Recording original = three_stream_recording();
  write_recording(path, original);
  const Recording loaded = read_recording(path);

  EXPECT_EQ(loaded.id, original.id);
  EXPECT_EQ(loaded.layout_id, "nao");
  EXPECT_EQ(loaded.metadata, original.metadata);
  ASSERT_EQ(loaded.streams.size(), 3u);
  for (size_t index = 0; index < 3; ++index) {
    const Stream& expected = original.streams[index];
    const Stream& actual = loaded.streams[index];
    SCOPED_TRACE(expected.name);
    EXPECT_EQ(actual.name, expected.name);
    EXPECT_EQ(actual.rate_hz, expected.rate_hz);
    EXPECT_EQ(actual.start_time, expected.start_time);
    EXPECT_EQ(actual.channels, expected.channels);
    // A stream written without units reads back with one empty unit per channel.
    EXPECT_EQ(actual.units, expected.units.empty()
                                ? std::vector<std::string>(expected.channels.size())
                                : expected.units);
    EXPECT_TRUE(bit_equal(actual.samples, expected.samples));
    EXPECT_EQ(actual.timestamps, expected.timestamps);
  }
  EXPECT_TRUE(std::signbit(loaded.streams[0].samples(0, 0)));
  EXPECT_EQ(loaded.streams[0].samples(1, 0), std::numeric_limits<float>::denorm_min());
}

TEST(Hdf5File, OpeningReportsShapesWithoutReadingSamples) {
  TemporaryDirectory directory;
  const std::string path = directory.file("info.h5");
  const Recording original = three_stream_recording();
  write_recording(path, original);
  const RecordingFile file(path);
  EXPECT_EQ(file.recording_id(), "subject-07_trial-3");
  EXPECT_EQ(file.layout_id(), "nao");
  EXPECT_EQ(file.metadata().at("température"), "21 °C — 東京");
  ASSERT_EQ(file.streams().size(), 3u);
  const StreamInfo& skin = file.streams()[0];
  EXPECT_EQ(skin.name, "skin");
  EXPECT_EQ(skin.sample_count, 1000);
  EXPECT_FALSE(skin.has_timestamps);
  EXPECT_DOUBLE_EQ(skin.duration(), 4.0);
  const StreamInfo& imu = file.stream("imu");
  EXPECT_TRUE(imu.has_timestamps);
  EXPECT_DOUBLE_EQ(imu.duration(), original.streams[1].duration());
  EXPECT_EQ(file.stream("aux").sample_count, 0);
  EXPECT_EQ(file.overview_block(), 256);
  EXPECT_THROW(file.stream("pressure"), Error);
}

TEST(Hdf5File, PartialReadsEqualTheSliceOfTheFullMatrix) {
  TemporaryDirectory directory;
  const std::string path = directory.file("long.h5");
  Recording recording;
  recording.id = "long";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 1000.0;
  stream.channels = {"a", "b", "c"};
  // Longer than several chunks of 8192 samples, so a range straddles chunks.
  stream.samples = random_samples(70000, 3, 3);
  recording.streams = {stream};
  write_recording(path, recording);

  const RecordingFile file(path);
  const SampleMatrix slice = file.read("skin", 65000, 2000);
  EXPECT_TRUE(bit_equal(slice, stream.samples.middleRows(65000, 2000)));
  const std::vector<float> channel = file.read_channel("skin", 2, 69990, 10);
  ASSERT_EQ(channel.size(), 10u);
  for (int index = 0; index < 10; ++index)
    EXPECT_EQ(std::bit_cast<uint32_t>(channel[size_t(index)]),
              std::bit_cast<uint32_t>(stream.samples(69990 + index, 2)));
  EXPECT_EQ(file.read("skin", 70000, 0).rows(), 0);
  EXPECT_THROW(file.read("skin", 69999, 2), Error);
  EXPECT_THROW(file.read("skin", -1, 2), Error);
  EXPECT_THROW(file.read_channel("skin", 3, 0, 1), Error);
  EXPECT_TRUE(file.read_timestamps("skin").empty());
}

TEST(Hdf5File, OverviewHoldsTheMinAndMaxOfEachBlock) {
  TemporaryDirectory directory;
  const std::string path = directory.file("overview.h5");
  Recording recording;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.channels = {"a", "b"};
  // 1000 samples: three full blocks of 256 and a last one of 232.
  std::mt19937 generator(11);
  std::normal_distribution<float> normal(0.0f, 5.0f);
  stream.samples = SampleMatrix(1000, 2);
  for (int64_t index = 0; index < stream.samples.size(); ++index)
    stream.samples.data()[index] = normal(generator);
  recording.streams = {stream};
  write_recording(path, recording);

  const auto [minima, maxima] = RecordingFile(path).read_overview("skin");
  ASSERT_EQ(minima.rows(), 4);
  ASSERT_EQ(minima.cols(), 2);
  for (int channel = 0; channel < 2; ++channel) {
    for (int block = 0; block < 4; ++block) {
      float low = std::numeric_limits<float>::infinity();
      float high = -low;
      for (int index = block * 256; index < std::min(1000, (block + 1) * 256); ++index) {
        low = std::min(low, stream.samples(index, channel));
        high = std::max(high, stream.samples(index, channel));
      }
      EXPECT_EQ(minima(block, channel), low) << "block " << block << " channel " << channel;
      EXPECT_EQ(maxima(block, channel), high) << "block " << block << " channel " << channel;
    }
  }
}

TEST(Hdf5File, OverviewSkipsNanGaps) {
  TemporaryDirectory directory;
  const std::string path = directory.file("gaps.h5");
  Recording recording;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.channels = {"a"};
  stream.samples = SampleMatrix::Constant(300, 1, std::nanf(""));
  stream.samples(10, 0) = 2.0f;
  stream.samples(20, 0) = -3.0f;
  recording.streams = {stream};
  write_recording(path, recording);
  const auto [minima, maxima] = RecordingFile(path).read_overview("skin");
  EXPECT_EQ(minima(0, 0), -3.0f);
  EXPECT_EQ(maxima(0, 0), 2.0f);
  EXPECT_TRUE(std::isnan(minima(1, 0)));  // a block with no number at all
}

TEST(Hdf5File, SamplesAreChunkedPerChannelAndCompressed) {
  TemporaryDirectory directory;
  const std::string path = directory.file("chunks.h5");
  Recording recording;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 1000.0;
  stream.channels = {"a", "b"};
  stream.samples = SampleMatrix::Zero(70000, 2);
  recording.streams = {stream};
  write_recording(path, recording);

  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t dataset = H5Dopen2(file, "streams/skin/samples", H5P_DEFAULT);
  const hid_t properties = H5Dget_create_plist(dataset);
  hsize_t chunk[2] = {0, 0};
  EXPECT_EQ(H5Pget_chunk(properties, 2, chunk), 2);
  EXPECT_EQ(chunk[0], 1u);
  EXPECT_EQ(chunk[1], 8192u);
  std::vector<H5Z_filter_t> filters;
  for (int index = 0; index < H5Pget_nfilters(properties); ++index)
    filters.push_back(H5Pget_filter2(properties, unsigned(index), nullptr, nullptr, nullptr, 0,
                                     nullptr, nullptr));
  // Fletcher32 last: the checksum covers the bytes as stored.
  EXPECT_EQ(filters, (std::vector<H5Z_filter_t>{H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE,
                                                H5Z_FILTER_FLETCHER32}));
  H5Pclose(properties);
  H5Dclose(dataset);
  H5Fclose(file);
}

TEST(Hdf5File, TruncatedFileIsAnErrorNamingTheFile) {
  TemporaryDirectory directory;
  const std::string path = directory.file("whole.h5");
  write_recording(path, three_stream_recording());
  const std::string bytes = testing::read_text(path);
  const std::string truncated = directory.file("half.h5");
  testing::write_text(truncated, bytes.substr(0, bytes.size() / 2));
  try {
    RecordingFile file(truncated);
    file.read_all();
    FAIL() << "a truncated file was read";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.where()).find("half.h5"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("truncated"), std::string::npos) << error.what();
  }
}

TEST(Hdf5File, GarbageAndMissingFilesAreErrors) {
  TemporaryDirectory directory;
  const std::string garbage = directory.file("garbage.h5");
  testing::write_text(garbage, "time,a,b\n0,1,2\n");
  try {
    RecordingFile file(garbage);
    FAIL() << "a text file was opened as HDF5";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), garbage);
    EXPECT_EQ(error.message(), "not an HDF5 file");
  }
  EXPECT_THROW(RecordingFile(directory.file("absent.h5")), Error);
}

// A recording held in memory (received, or fed by the fuzzer) reads as the same file on disk.
TEST(Hdf5File, FileImageInMemoryReadsAsTheFile) {
  TemporaryDirectory directory;
  const std::string path = directory.file("image.h5");
  const Recording original = three_stream_recording();
  write_recording(path, original);
  const std::string bytes = testing::read_text(path);
  const std::span<const uint8_t> image(reinterpret_cast<const uint8_t*>(bytes.data()),
                                       bytes.size());
  const RecordingFile file = RecordingFile::from_image(image, "memory.h5");
  EXPECT_EQ(file.path(), "memory.h5");
  EXPECT_EQ(file.format_version(), 2);
  const Recording loaded = file.read_all();
  ASSERT_EQ(loaded.streams.size(), original.streams.size());
  for (size_t index = 0; index < loaded.streams.size(); ++index)
    EXPECT_TRUE(bit_equal(loaded.streams[index].samples, original.streams[index].samples));
  EXPECT_EQ(loaded.metadata, original.metadata);
  // Half an image, an empty one and text are refused naming the image.
  for (const std::string& bad :
       {bytes.substr(0, bytes.size() / 2), std::string(), std::string("time,a\n0,1\n")}) {
    try {
      const std::span<const uint8_t> part(reinterpret_cast<const uint8_t*>(bad.data()), bad.size());
      RecordingFile::from_image(part, "memory.h5").read_all();
      FAIL() << "a damaged image of " << bad.size() << " bytes was read";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.where()).find("memory.h5"), std::string::npos) << error.what();
    }
  }
}

// Opens a written file read-write and lets `damage` change it with HDF5's API.
template <typename Damage>
void damage_file(const std::string& path, Damage damage) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  damage(file);
  H5Fclose(file);
}

std::string open_error(const std::string& path) {
  try {
    RecordingFile file(path);
  } catch (const Error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(Hdf5File, WrongFormatVersionIsRefused) {
  TemporaryDirectory directory;
  const std::string path = directory.file("future.h5");
  write_recording(path, three_stream_recording());
  damage_file(path, [](hid_t file) {
    const hid_t attribute = H5Aopen(file, "format_version", H5P_DEFAULT);
    const int64_t version = 3;
    H5Awrite(attribute, H5T_NATIVE_INT64, &version);
    H5Aclose(attribute);
  });
  const std::string message = open_error(path);
  EXPECT_NE(message.find("future.h5:/ attribute format_version"), std::string::npos) << message;
  EXPECT_NE(message.find("version 3 is not supported"), std::string::npos) << message;
}

TEST(Hdf5File, MissingDatasetAndAttributeAreNamed) {
  TemporaryDirectory directory;
  const std::string no_overview = directory.file("no_overview.h5");
  write_recording(no_overview, three_stream_recording());
  damage_file(no_overview,
              [](hid_t file) { H5Ldelete(file, "streams/imu/overview_max", H5P_DEFAULT); });
  EXPECT_EQ(open_error(no_overview), no_overview + ":/streams/imu/overview_max: missing dataset");

  const std::string no_rate = directory.file("no_rate.h5");
  write_recording(no_rate, three_stream_recording());
  damage_file(no_rate,
              [](hid_t file) { H5Adelete_by_name(file, "streams/skin", "rate_hz", H5P_DEFAULT); });
  EXPECT_EQ(open_error(no_rate), no_rate + ":/streams/skin attribute rate_hz: missing attribute");
}

TEST(Hdf5File, ShapeMismatchIsNamed) {
  TemporaryDirectory directory;
  const std::string path = directory.file("shape.h5");
  write_recording(path, three_stream_recording());
  // Replace the time stamps of "imu" (37 samples) by 36 values.
  damage_file(path, [](hid_t file) {
    H5Ldelete(file, "streams/imu/timestamps", H5P_DEFAULT);
    const hsize_t count = 36;
    const hid_t space = H5Screate_simple(1, &count, nullptr);
    const hid_t dataset = H5Dcreate2(file, "streams/imu/timestamps", H5T_IEEE_F64LE, space,
                                     H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(dataset);
    H5Sclose(space);
  });
  EXPECT_EQ(open_error(path), path + ":/streams/imu/timestamps: shape [36], expected [37]");
}

TEST(Hdf5File, WritingIntoAMissingDirectoryFailsAndLeavesNothing) {
  TemporaryDirectory directory;
  const std::string path = directory.file("no/such/dir/x.h5");
  try {
    write_recording(path, three_stream_recording());
    FAIL() << "wrote into a missing directory";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path);
  }
  EXPECT_EQ(directory.entry_count(), 0);
}

TEST(Hdf5File, ExistingFileIsReplacedWholeOrKept) {
  TemporaryDirectory directory;
  const std::string path = directory.file("replace.h5");
  Recording first = three_stream_recording();
  write_recording(path, first);
  Recording second = three_stream_recording();
  second.id = "second";
  second.streams.resize(1);
  write_recording(path, second);
  EXPECT_EQ(RecordingFile(path).recording_id(), "second");
  EXPECT_EQ(RecordingFile(path).streams().size(), 1u);
  EXPECT_EQ(directory.entry_count(), 1);  // no temporary file left beside it

  // A recording that cannot be written leaves the previous file as it was.
  Recording broken = second;
  broken.id = "broken";
  broken.streams[0].channels.pop_back();
  EXPECT_THROW(write_recording(path, broken), Error);
  EXPECT_EQ(RecordingFile(path).recording_id(), "second");
  EXPECT_EQ(directory.entry_count(), 1);
}

TEST(Hdf5File, InvalidStreamsAreRefusedBeforeWriting) {
  TemporaryDirectory directory;
  const std::string path = directory.file("invalid.h5");
  Recording recording = three_stream_recording();
  recording.streams[1].name = "skin";
  EXPECT_THROW(write_recording(path, recording), Error);
  recording = three_stream_recording();
  recording.streams[0].name = "a/b";
  EXPECT_THROW(write_recording(path, recording), Error);
  recording = three_stream_recording();
  recording.streams[1].timestamps.pop_back();
  try {
    write_recording(path, recording);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.what(), path + ":/streams/imu: 36 time stamps for 37 samples");
  }
  EXPECT_EQ(directory.entry_count(), 0);
}

}  // namespace
}  // namespace tactile

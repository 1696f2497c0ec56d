// Recordings that cannot lie: format 2 covers every byte with a checksum, a damaged
// byte is refused where it is read and named by verify, sizes are checked against
// the file before anything is allocated, files of format 1 open and upgrade.
#include <gtest/gtest.h>
#include <hdf5/serial/hdf5.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/verify/verify.h"
#include "test_paths.h"

namespace tactile {
namespace {

using testing::refusal_of;

using testing::TemporaryDirectory;

const std::string kFormat1 = tactile::test::test_data_dir() + "/format_v1/fur-s01-t01.h5";

Recording ramp_recording() {
  Recording recording;
  recording.id = "ramp";
  recording.layout_id = "grid:1x3";
  recording.metadata = {{"subject", "s01"}, {"note", "ünïcödé"}};
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 100.0;
  stream.channels = {"alpha", "beta", "gamma"};
  stream.units = {"N", "N", ""};
  stream.samples.resize(20000, 3);
  for (int row = 0; row < 20000; ++row)
    for (int column = 0; column < 3; ++column)
      stream.samples(row, column) =
          static_cast<float>(row % 977) * 0.5f + static_cast<float>(column);
  recording.streams = {stream};
  return recording;
}

// The file offset and stored size of chunk `index` of a dataset.
std::pair<haddr_t, hsize_t> chunk_place(const std::string& path, const char* dataset_name,
                                        hsize_t index) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, dataset_name, H5P_DEFAULT);
  hsize_t offset[2] = {0, 0};
  unsigned mask = 0;
  haddr_t address = 0;
  hsize_t size = 0;
  const hid_t space = H5Dget_space(dataset);
  H5Dget_chunk_info(dataset, space, index, offset, &mask, &address, &size);
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(file);
  return {address, size};
}

void flip_byte(const std::string& path, uint64_t offset) {
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekg(static_cast<std::streamoff>(offset));
  char byte = 0;
  file.get(byte);
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(static_cast<char>(byte ^ 0x10));
}

TEST(RecordingFormat2, EveryByteIsUnderACheckAndNoStringIsVariable) {
  TemporaryDirectory directory;
  const std::string path = directory.file("ramp.h5");
  write_recording(path, ramp_recording());
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  H5F_info2_t info{};
  ASSERT_GE(H5Fget_info2(file, &info), 0);
  EXPECT_EQ(info.super.version, 3u);  // the 1.10 superblock, with its checksum
  H5Fclose(file);
  EXPECT_EQ(RecordingFile(path).format_version(), 2);
  // verify walks every object: Fletcher32 on each chunked dataset, nothing
  // contiguous, no variable-length strings, overview equal to the samples.
  const auto problems = verify_recording(path);
  EXPECT_TRUE(problems.empty()) << problems.front().message;
}

TEST(RecordingFormat2, ADamagedSampleChunkIsRefusedWhereItIsRead) {
  TemporaryDirectory directory;
  const std::string path = directory.file("ramp.h5");
  write_recording(path, ramp_recording());
  // Chunks are [1][8192]: chunk 4 is channel beta, samples [8192, 16384).
  const auto [address, size] = chunk_place(path, "streams/skin/samples", 4);
  ASSERT_GT(size, 0u);
  flip_byte(path, address + size / 2);
  const RecordingFile file(path);  // the metadata is intact
  EXPECT_NO_THROW(file.read_channel("skin", 0, 8192, 8192));
  EXPECT_NO_THROW(file.read_channel("skin", 1, 0, 8192));
  const std::string message = refusal_of([&] { file.read_channel("skin", 1, 9000, 10); });
  EXPECT_NE(message.find(path + ":/streams/skin/samples"), std::string::npos) << message;
  EXPECT_NE(message.find("Fletcher32 checksum"), std::string::npos) << message;
  EXPECT_THROW(read_recording(path), Error);
  const auto problems = verify_recording(path);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].message.find("channel beta, samples [8192, 16384)"), std::string::npos)
      << problems[0].message;
}

TEST(RecordingFormat2, ADamagedByteOfMetadataIsRefusedOnOpening) {
  TemporaryDirectory directory;
  const std::string path = directory.file("ramp.h5");
  write_recording(path, ramp_recording());
  const std::string before = testing::read_text(path);
  // The channel names live in an uncompressed chunk, 5 bytes each.
  const size_t names = before.find(std::string("alphabeta\0gamma", 15));
  ASSERT_NE(names, std::string::npos);
  flip_byte(path, names + 6);  // "beta" becomes "bUta"
  const std::string message = refusal_of([&] { RecordingFile file(path); });
  EXPECT_NE(message.find(path + ":/streams/skin/channels"), std::string::npos) << message;
  // The superblock has a checksum too.
  write_recording(path, ramp_recording());
  flip_byte(path, 20);
  EXPECT_FALSE(refusal_of([&] { RecordingFile file(path); }).empty());
}

TEST(RecordingFormat2, TwoChannelsOfOneNameAreRefused) {
  TemporaryDirectory directory;
  Recording recording = ramp_recording();
  recording.streams[0].channels = {"a", "b", "a"};
  const std::string message =
      refusal_of([&] { write_recording(directory.file("x.h5"), recording); });
  EXPECT_NE(message.find("channel name 'a' is used by channels 0 and 2"), std::string::npos)
      << message;
  EXPECT_EQ(directory.entry_count(), 0);
}

TEST(RecordingFormat2, ASizeTheFileCannotHoldIsRefusedBeforeAnythingIsAllocated) {
  TemporaryDirectory directory;
  const std::string path = directory.file("huge.h5");
  write_recording(path, ramp_recording());
  // Replace the samples by a dataset that declares 2^40 samples per channel but
  // stores none: a reader that trusted the shape would ask for 12 TiB.
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(file, "streams/skin/samples", H5P_DEFAULT), 0);
  const hsize_t shape[2] = {3, hsize_t{1} << 40};
  const hsize_t chunk[2] = {1, 8192};
  const hid_t space = H5Screate_simple(2, shape, nullptr);
  const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(properties, 2, chunk);
  H5Pset_deflate(properties, 4);
  const hid_t dataset = H5Dcreate2(file, "streams/skin/samples", H5T_IEEE_F32LE, space, H5P_DEFAULT,
                                   properties, H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  H5Dclose(dataset);
  H5Pclose(properties);
  H5Sclose(space);
  H5Fclose(file);
  const std::string message = refusal_of([&] { RecordingFile opened(path); });
  EXPECT_NE(message.find(path + ":/streams/skin/samples: declares 13194139533312 bytes of data"),
            std::string::npos)
      << message;
}

TEST(RecordingFormat2, AHeaderDeclaringTwoToTheFortyChannelsIsRefusedBeforeAnythingIsAllocated) {
  TemporaryDirectory directory;
  const std::string path = directory.file("channels.h5");
  write_recording(path, ramp_recording());
  // The channel names become a dataset of 2^40 fixed-length names that stores none: a reader
  // that trusted it would ask for 16 TiB of names before reading a sample.
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(file, "streams/skin/channels", H5P_DEFAULT), 0);
  const hsize_t shape[1] = {hsize_t{1} << 40};
  const hsize_t chunk[1] = {4096};
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, 16);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate_simple(1, shape, nullptr);
  const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(properties, 1, chunk);
  H5Pset_fletcher32(properties);
  const hid_t dataset =
      H5Dcreate2(file, "streams/skin/channels", type, space, H5P_DEFAULT, properties, H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  H5Dclose(dataset);
  H5Pclose(properties);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(file);
  const std::string message = refusal_of([&] { RecordingFile opened(path); });
  EXPECT_NE(message.find(path + ":/streams/skin/channels"), std::string::npos) << message;
  EXPECT_NE(message.find("declares"), std::string::npos) << message;
}

TEST(RecordingFormat1, AFileOfTheEarlierFormatStillOpens) {
  const RecordingFile file(kFormat1);
  EXPECT_EQ(file.format_version(), 1);
  EXPECT_EQ(file.layout_id(), "fur");
  EXPECT_EQ(file.recording_id(), "fur-s01-t01");
  ASSERT_EQ(file.streams().size(), 1u);
  EXPECT_EQ(file.streams()[0].channels.size(), 160u);
  EXPECT_EQ(file.streams()[0].sample_count, 471);
  EXPECT_EQ(file.metadata().at("skin"), "fur");
  const Recording recording = file.read_all();
  EXPECT_EQ(recording.streams[0].samples.rows(), 471);
  const auto problems = verify_recording(kFormat1);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].message.find("format 1 carries no checksums"), std::string::npos);
}

TEST(RecordingFormat1, UpgradeRewritesItWithTheSameContentAndVerifiesIt) {
  TemporaryDirectory directory;
  const std::string path = directory.file("old.h5");
  std::filesystem::copy_file(kFormat1, path);
  const Recording before = read_recording(path);
  const UpgradeResult result = upgrade_file(path);
  EXPECT_EQ(result.from_version, 1);
  EXPECT_EQ(result.to_version, 2);
  EXPECT_EQ(RecordingFile(path).format_version(), 2);
  const Recording after = read_recording(path);
  EXPECT_EQ(after.metadata, before.metadata);
  EXPECT_EQ(after.streams[0].channels, before.streams[0].channels);
  ASSERT_EQ(after.streams[0].samples.size(), before.streams[0].samples.size());
  EXPECT_EQ(std::memcmp(after.streams[0].samples.data(), before.streams[0].samples.data(),
                        sizeof(float) * after.streams[0].samples.size()),
            0);
  EXPECT_TRUE(verify_recording(path).empty());
  EXPECT_EQ(directory.entry_count(), 1);  // no temporary left
  EXPECT_FALSE(upgrade_file(path).rewritten());
}

TEST(RecordingFormat1, AFailedUpgradeLeavesTheOriginalAsItWas) {
  TemporaryDirectory directory;
  const std::string path = directory.file("cut.h5");
  std::string bytes = testing::read_text(kFormat1);
  bytes.resize(bytes.size() - 5000);  // a half-copied file
  testing::write_text(path, bytes);
  EXPECT_THROW(upgrade_file(path), Error);
  EXPECT_EQ(testing::read_text(path), bytes);
  EXPECT_EQ(directory.entry_count(), 1);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// h5py (python3-h5py, Debian's) reads the file as docs/FILE_FORMAT.md says.
TEST(RecordingFormat2, H5pyReadsTheFileAsDocumented) {
  const std::string python = "/usr/bin/python3";
  if (std::system((python + " -c 'import h5py' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "python3-h5py is not installed";
  TemporaryDirectory directory;
  const std::string path = directory.file("ramp.h5");
  const Recording recording = ramp_recording();
  write_recording(path, recording);
  const std::string script = directory.file("read.py");
  testing::write_text(script,
                      "import h5py, sys\n"
                      "f = h5py.File(sys.argv[1], 'r')\n"
                      "x = f['streams/skin/samples'][:]\n"
                      "names = f['streams/skin/channels'].asstr()[:]\n"
                      "units = f['streams/skin/units'].asstr()[:]\n"
                      "rate = f['streams/skin'].attrs['rate_hz']\n"
                      "print(x.shape[0], x.shape[1], x.dtype, ','.join(names), ','.join(units),\n"
                      "      rate, repr(float(x[1, 12345])), f.attrs['format'].decode(),\n"
                      "      f.attrs['format_version'], f['metadata'].attrs['note'].decode())\n");
  const std::string command = python + " " + script + " " + path;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[512] = {};
  const size_t got = fread(buffer, 1, sizeof(buffer) - 1, pipe);
  ASSERT_EQ(pclose(pipe), 0) << std::string(buffer, got);
  const float sample = recording.streams[0].samples(12345, 1);
  char expected_sample[64];
  std::snprintf(expected_sample, sizeof(expected_sample), "%.1f", static_cast<double>(sample));
  EXPECT_EQ(std::string(buffer, got), "3 20000 float32 alpha,beta,gamma N,N, 100.0 " +
                                          std::string(expected_sample) +
                                          " tactile-workbench 2 ünïcödé\n");
}

}  // namespace
}  // namespace tactile

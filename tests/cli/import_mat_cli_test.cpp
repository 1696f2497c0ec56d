// `tactile import FILE.mat` end to end: the Octave fixtures (tests/data/interop) written as a
// recording whose samples are the MATLAB matrix's, at the rate of the file's own variable,
// with its classes as ground truth; `tactile verify` passes on what was written; bad flags
// and damaged files are refused with the flag or the file and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "test_paths.h"

namespace tactile {
namespace {

using test::run_program;

const std::string kInterop = tactile::test::test_data_dir() + "/interop/";

class ImportMat : public ::testing::Test {
 protected:
  test::CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder);
  }
  test::TempFolder folder{"tactile-import-mat"};
};

TEST_F(ImportMat, SamplesRateAndClassesOfAnOctaveFileBecomeARecordingAndItsGroundTruth) {
  for (const std::string file : {"tactile_v6.mat", "tactile_v7.mat"}) {
    SCOPED_TRACE(file);
    const std::string out = folder.file("mat.h5");
    const std::string labels = folder.file("labels.db");
    const auto result = tactile("import " + kInterop + file +
                                " --layout grid:2x2 --dataset samples --rate-variable rate"
                                " --class-array classes --out " +
                                out + " --labels " + labels);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("6 samples x 4 channels at 250 Hz, 2 labels"), std::string::npos)
        << result.out;
    const Recording recording = read_recording(out);
    const Stream& stream = recording.streams.front();
    ASSERT_EQ(stream.sample_count(), 6);
    ASSERT_EQ(stream.channel_count(), 4);
    EXPECT_EQ(stream.rate_hz, 250);
    for (int t = 1; t <= 6; ++t)
      for (int c = 1; c <= 4; ++c) EXPECT_EQ(stream.samples(t - 1, c - 1), 100 * t + c);
    LabelStore store(labels);
    LabelFilter filter;
    filter.recording = "mat";
    const std::vector<Label> stored = store.list(filter);
    ASSERT_EQ(stored.size(), 2u) << "importing again replaces the ground truth";
    EXPECT_EQ(stored[0].class_name, "Punch");
    EXPECT_DOUBLE_EQ(stored[0].t0, 0.0);
    EXPECT_DOUBLE_EQ(stored[0].t1, 2 / 250.0);
    EXPECT_EQ(stored[1].class_name, "Stroke");
    EXPECT_DOUBLE_EQ(stored[1].t0, 3 / 250.0);
    const auto verified = tactile("verify " + out);
    EXPECT_EQ(verified.exit_code, 0) << verified.out << verified.err;
    std::filesystem::remove(out);
  }
}

TEST_F(ImportMat, TheOneArrayOfAFileNeedsNoName) {
  const std::string out = folder.file("one.h5");
  const auto result = tactile("import " + kInterop +
                              "one_array.mat --layout grid:2x2 --rate-variable fs --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(read_recording(out).streams.front().samples(5, 3), 604);
}

TEST_F(ImportMat, AMatlab4FileBecomesARecording) {
  // x = reshape(1:24, 6, 4) + 100 * (1:6)' ...: samples(t, c) = 100 t + c, and fs = 250, as
  // MATLAB's save('x4.mat', 'samples', 'fs', '-v4') lays them out: per variable a 20-byte
  // header (type 0: IEEE little-endian doubles, a numeric matrix; rows; columns; no imaginary
  // part; the name's length with its NUL), the name, the values column-major. No file header.
  std::string bytes;
  auto variable = [&](const std::string& name, int32_t rows, int32_t columns,
                      const std::vector<double>& values) {
    for (const int32_t field : {0, rows, columns, 0, static_cast<int32_t>(name.size() + 1)})
      bytes.append(reinterpret_cast<const char*>(&field), 4);
    bytes.append(name.c_str(), name.size() + 1);
    for (const double value : values) bytes.append(reinterpret_cast<const char*>(&value), 8);
  };
  std::vector<double> samples;
  for (int c = 1; c <= 4; ++c)
    for (int t = 1; t <= 6; ++t) samples.push_back(100 * t + c);
  variable("samples", 6, 4, samples);
  variable("fs", 1, 1, {250});
  const std::string path = folder.file("x4.mat");
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string out = folder.file("x4.h5");
  const auto result =
      tactile("import " + path + " --layout grid:2x2 --rate-variable fs --out " + out);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Recording recording = read_recording(out);
  const Stream& stream = recording.streams.front();
  EXPECT_EQ(stream.rate_hz, 250);
  ASSERT_EQ(stream.sample_count(), 6);
  EXPECT_EQ(stream.samples(4, 2), 503);
}

TEST_F(ImportMat, BadFlagsAndDamagedFilesAreRefusedAndWriteNothing) {
  // A file cut in its second variable.
  const std::string cut = folder.file("cut.mat");
  {
    std::ifstream in(kInterop + "tactile_v6.mat", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, 400);
  }
  const std::string v6 = kInterop + "tactile_v6.mat --layout grid:2x2 ";
  const std::vector<test::RefusedImport> cases = {
      {v6 + "--dataset samples --rate 10 --rate-variable rate",
       "--rate-variable: or --rate, not both"},
      {v6 + "--dataset samples", "--rate"},
      {v6 + "--rate 10", "--dataset: " + kInterop + "tactile_v6.mat holds 2 numeric arrays"},
      {v6 + "--rate 10", "s.pressure 6x2x2 single"},
      {v6 + "--rate 10 --dataset force", "no variable force"},
      {v6 + "--rate 10 --dataset waves", "waves 1x2 complex double is not read"},
      {v6 + "--dataset samples --rate-variable names", "is not one positive number"},
      {v6 + "--dataset samples --rate 10 --class-array counts", "3 classes for 6 frames"},
      {tactile::test::test_data_dir() + "/io/long_strip3.csv --layout strip:3 --rate-variable rate",
       "--rate-variable: is not an option of CSV files"},
      {cut + " --layout grid:2x2 --rate 10 --dataset samples",
       cut + ": byte 384: a data element declares 56 bytes, 8 are left"},
  };
  const std::string out = folder.file("never.h5");
  test::expect_imports_refused(cases, out, folder);
}

}  // namespace
}  // namespace tactile

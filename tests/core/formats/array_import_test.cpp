// Other programs' arrays: files written by numpy and h5py (tests/data/import) read back to
// the same numbers in every format, classes per frame and per capture as labels, and every
// malformed or truncated file refused with its place, never read as other numbers, never
// a crash, never an allocation larger than the file.
#include <gtest/gtest.h>
#include <hdf5/serial/hdf5.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/array_files.h"
#include "tactile/formats/csv_files.h"
#include "tactile/io/hdf5_file.h"
#include "test_paths.h"

namespace tactile {
namespace {

using testing::refusal_of;

const std::string kData = tactile::test::test_data_dir() + "/import/";

std::vector<uint8_t> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A .npy file: version 1 header padded to 64 bytes, then `data`.
std::vector<uint8_t> npy(const std::string& header_dict, const std::vector<uint8_t>& data) {
  std::string header = header_dict;
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::vector<uint8_t> bytes = {0x93,
                                'N',
                                'U',
                                'M',
                                'P',
                                'Y',
                                1,
                                0,
                                static_cast<uint8_t>(header.size() & 0xFF),
                                static_cast<uint8_t>(header.size() >> 8)};
  bytes.insert(bytes.end(), header.begin(), header.end());
  bytes.insert(bytes.end(), data.begin(), data.end());
  return bytes;
}

TEST(ArrayImport, EveryFormatGivesTheSameFrames) {
  const ImportedArray reference = read_npy(kData + "frames.npy");
  ASSERT_EQ(reference.shape, (std::vector<int64_t>{50, 4, 4}));
  const ImportedArray fortran = read_npy(kData + "fortran.npy");
  EXPECT_EQ(fortran.shape, (std::vector<int64_t>{50, 16}));
  EXPECT_EQ(fortran.values, reference.values);
  EXPECT_EQ(read_npz(kData + "frames.npz", "pressure").values, reference.values);  // deflated
  EXPECT_EQ(read_npz(kData + "plain.npz", "pressure").values,
            reference.values);  // big-endian f8, stored
  EXPECT_EQ(npz_names(kData + "frames.npz"), (std::vector<std::string>{"pressure", "gesture"}));
  const ImportedArray json = read_json_array(kData + "frames.json", "data.frames");
  EXPECT_EQ(json.shape, reference.shape);
  for (size_t k = 0; k < json.values.size(); ++k)
    ASSERT_FLOAT_EQ(static_cast<float>(json.values[k]), static_cast<float>(reference.values[k]));
  EXPECT_EQ(read_hdf5_dataset(kData + "foreign.h5", "/sensors/pressure").values, reference.values);
  // Classes as unicode (npz), text (JSON) and bytes (HDF5).
  const ImportedArray gesture = read_npz(kData + "frames.npz", "gesture");
  ASSERT_TRUE(gesture.text);
  EXPECT_EQ(gesture.strings[10], "pat");
  EXPECT_EQ(read_json_array(kData + "frames.json", "data.gesture").strings, gesture.strings);
  EXPECT_EQ(read_hdf5_dataset(kData + "foreign.h5", "/sensors/gesture").strings, gesture.strings);
}

TEST(ArrayImport, FramesOfAGridAndTheirClassesBecomeARecordingWithLabels) {
  ArrayRecordingOptions options;
  options.rate_hz = 100;
  options.classes = read_npz(kData + "frames.npz", "gesture").strings;
  const ImportedRecording imported = recording_from_array(
      read_npy(kData + "frames.npy"), load_layout("grid:4x4"), options, "frames.npy");
  const Stream& stream = imported.recording.streams.front();
  EXPECT_EQ(stream.sample_count(), 50);
  EXPECT_EQ(stream.channel_count(), 16);
  ASSERT_EQ(imported.labels.size(), 2u);  // none and "" are no touch
  EXPECT_EQ(imported.labels[0].class_name, "pat");
  EXPECT_DOUBLE_EQ(imported.labels[0].t0, 0.10);
  EXPECT_DOUBLE_EQ(imported.labels[0].t1, 0.25);
  EXPECT_EQ(imported.labels[1].class_name, "stroke");
  EXPECT_DOUBLE_EQ(imported.labels[1].t0, 0.30);
}

TEST(ArrayImport, CapturesLieEndToEndWithOneLabelEach) {
  ArrayRecordingOptions options;
  options.rate_hz = 100;
  options.captures = true;
  options.classes = {"a", "b", "c", "a", "b", "c"};
  const ImportedArray captures = read_npz(kData + "caps.npz", "x");
  const ImportedRecording imported =
      recording_from_array(captures, load_layout("grid:4x4"), options, "caps");
  const Stream& stream = imported.recording.streams.front();
  ASSERT_EQ(stream.sample_count(), 180);
  // Capture 2, channel 5, sample 7 is row 2 * 30 + 7.
  EXPECT_FLOAT_EQ(stream.samples(67, 5),
                  static_cast<float>(captures.values[(2 * 16 + 5) * 30 + 7]));
  ASSERT_EQ(imported.labels.size(), 6u);
  EXPECT_DOUBLE_EQ(imported.labels[2].t0, 0.6);
  EXPECT_EQ(imported.labels[2].class_name, "c");
}

TEST(ArrayImport, ShapesThatDoNotFitAreRefusedWithTheLayout) {
  ArrayRecordingOptions options;
  options.rate_hz = 10;
  const ImportedArray frames = read_npy(kData + "frames.npy");
  EXPECT_NE(refusal_of([&] {
              recording_from_array(frames, load_layout("grid:4x5"), options, "f");
            }).find("does not fit grid:4x5"),
            std::string::npos);
  options.classes = {"a", "b"};
  EXPECT_NE(refusal_of([&] {
              recording_from_array(frames, load_layout("grid:4x4"), options, "f");
            }).find("2 classes for 50 frames"),
            std::string::npos);
  ImportedArray nan = frames;
  nan.values[3 * 16 + 2 * 4 + 1] = NAN;
  options.classes.clear();
  EXPECT_NE(refusal_of([&] {
              recording_from_array(nan, load_layout("grid:4x4"), options, "f");
            }).find("f index [3][2][1]"),
            std::string::npos);
}

TEST(ArrayImport, EveryTruncationOfANpyOrNpzIsRefused) {
  for (const std::string name : {"frames.npy", "frames.npz", "plain.npz"}) {
    const std::vector<uint8_t> whole = file_bytes(kData + name);
    testing::TemporaryDirectory directory;
    const std::string path = directory.file(name);
    for (size_t length = 0; length < whole.size(); length += (length < 200 ? 1 : 97)) {
      {
        std::ofstream(path, std::ios::binary)
            .write(reinterpret_cast<const char*>(whole.data()),
                   static_cast<std::streamsize>(length));
      }
      const std::string why = refusal_of([&] {
        if (name.ends_with(".npy"))
          read_npy(path);
        else
          read_npz(path, "pressure");
      });
      ASSERT_FALSE(why.empty()) << name << " cut at " << length << " bytes was read";
    }
  }
}

TEST(ArrayImport, ADamagedDeflateStreamIsRefused) {
  std::vector<uint8_t> bytes = file_bytes(kData + "frames.npz");
  bytes[200] ^= 0xFF;  // inside the deflated pressure array
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("bad.npz");
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  EXPECT_FALSE(refusal_of([&] { read_npz(path, "pressure"); }).empty());
}

TEST(ArrayImport, HeadersThatLieAreRefusedBeforeAnyAllocation) {
  const std::vector<uint8_t> eight(8, 0);
  // 2^40 elements declared over 8 bytes of data: refused by the shape, not by running out of
  // memory.
  EXPECT_NE(refusal_of([&] {
              parse_npy(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1099511627776,), }",
                            eight),
                        "x.npy");
            }).find("more than"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              parse_npy(
                  npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1000, 1000), }", eight),
                  "x.npy");
            }).find("truncated"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              parse_npy(
                  npy("{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (1,), }", eight),
                  "x.npy");
            }).find("descr"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              parse_npy(npy("{'descr': '<c16', 'fortran_order': False, 'shape': (1,), }", eight),
                        "x.npy");
            }).find("only bool, integer, float and string"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              parse_npy(npy("{'descr': '<f8', 'fortran_order': maybe, 'shape': (1,), }", eight),
                        "x.npy");
            }).find("fortran_order"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] {
              parse_npy(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", eight),
                        "x.npy");
            }).find("truncated"),
            std::string::npos);
  // Found by the fuzzer (tests/fuzz/regressions/arrays): a header that ends right after the
  // key read past its end instead of being refused.
  const std::string cut = "{'descr': '>i2', 'fortran_order'";
  std::vector<uint8_t> ends_at_key = {
      0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<uint8_t>(cut.size()), 0};
  ends_at_key.insert(ends_at_key.end(), cut.begin(), cut.end());
  EXPECT_NE(
      refusal_of([&] { parse_npy(ends_at_key, "x.npy"); }).find("'fortran_order' has no value"),
      std::string::npos);
  std::vector<uint8_t> not_npy = {'P', 'K', 3, 4, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_NE(refusal_of([&] { parse_npy(not_npy, "x.npy"); }).find("x.npy byte 0"),
            std::string::npos);
  // A small valid one reads.
  std::vector<uint8_t> two(16);
  const double values[2] = {1.5, -2.0};
  std::memcpy(two.data(), values, 16);
  EXPECT_EQ(
      parse_npy(npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }", two), "x.npy")
          .values,
      (std::vector<double>{1.5, -2.0}));
}

TEST(ArrayImport, JsonThatIsNotRegularFramesIsRefusedWithItsIndex) {
  testing::TemporaryDirectory directory;
  const auto write = [&](const std::string& text) {
    const std::string path = directory.file("f.json");
    std::ofstream(path) << text;
    return path;
  };
  EXPECT_NE(refusal_of([&] { read_json_array(write("[[1,2],[3]]"), ""); }).find("[1]"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] { read_json_array(write("[[1,2],[3,\"x\"]]"), ""); }).find("[1][1]"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] { read_json_array(write("{\"a\": [1]}"), "b"); }).find("no key 'b'"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] { read_json_array(write("[[1,2],[3,4]"), ""); }).find("not JSON"),
            std::string::npos);
  // Found by the fuzzer (tests/fuzz/regressions/arrays): a number too large for a double
  // escaped as nlohmann's out_of_range instead of naming the file.
  EXPECT_NE(refusal_of([&] { read_json_array(write("[[1,2],[3,2e342]]"), ""); }).find("f.json"),
            std::string::npos);
  EXPECT_EQ(read_json_array(write("{\"a\": {\"b\": [[1,2],[3,4]]}}"), "a.b").shape,
            (std::vector<int64_t>{2, 2}));
}

// Another program's small float32 dataset (h5py's default for np.float32), stored without
// compression: the file holds 4 bytes a value, which the size check must count, not the 8 of
// the doubles it is read into.
TEST(ArrayImport, ASmallFloat32DatasetOfAnotherProgramIsRead) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "tactile-float32-grid.h5").string();
  const hsize_t shape[3] = {300, 4, 5};
  std::vector<float> values(300 * 4 * 5);
  for (size_t k = 0; k < values.size(); ++k) values[k] = static_cast<float>(k % 97) * 0.25f;
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t group = H5Gcreate2(file, "/sensors", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t space = H5Screate_simple(3, shape, nullptr);
  const hid_t dataset =
      H5Dcreate2(group, "grid", H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(H5Dwrite(dataset, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(dataset);
  H5Sclose(space);
  H5Gclose(group);
  H5Fclose(file);
  ASSERT_LT(std::filesystem::file_size(path), 8 * values.size());  // the old check's premise

  const ImportedArray array = read_hdf5_dataset(path, "/sensors/grid");
  EXPECT_EQ(array.shape, (std::vector<int64_t>{300, 4, 5}));
  ASSERT_EQ(array.values.size(), values.size());
  for (size_t k = 0; k < values.size(); k += 37) EXPECT_EQ(array.values[k], values[k]) << k;
  std::filesystem::remove(path);
}

TEST(ArrayImport, HdfDatasetsNameWhatIsMissing) {
  EXPECT_NE(refusal_of([&] {
              read_hdf5_dataset(kData + "foreign.h5", "/sensors/force");
            }).find("no such dataset"),
            std::string::npos);
  EXPECT_NE(
      refusal_of([&] { read_hdf5_dataset(kData + "frames.npy", "/x"); }).find("not an HDF5 file"),
      std::string::npos);
}

//---- other programs' .h5 files, walked as MATLAB v7.3 files are

std::string listed_hdf5(const std::string& path) {
  std::string listed;
  for (const Hdf5Dataset& dataset : hdf5_datasets(path))
    listed += (listed.empty() ? "" : ", ") + dataset.described;
  return listed;
}

TEST(ArrayImport, AnHdf5FileIsWalkedAndItsDatasetsListedBeforeLibhdf5ReadsThem) {
  // foreign.h5: what h5py writes by default (superblock 0, groups of symbol tables).
  EXPECT_EQ(listed_hdf5(kData + "foreign.h5"),
            "/sensors/gesture 50 string, /sensors/pressure 50x4x4 float32");
  const std::string missing =
      refusal_of([&] { read_hdf5_dataset(kData + "foreign.h5", "/pressure"); });
  EXPECT_NE(missing.find("/pressure: no such dataset (the file holds /sensors/gesture 50 string, "
                         "/sensors/pressure 50x4x4 float32)"),
            std::string::npos)
      << missing;
  // A compound dataset (a table of records) is walked, and refused by name before libhdf5 reads.
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("table.h5");
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t record = H5Tcreate(H5T_COMPOUND, 16);
  H5Tinsert(record, "time", 0, H5T_IEEE_F64LE);
  H5Tinsert(record, "force", 8, H5T_IEEE_F64LE);
  const hsize_t rows[1] = {3};
  const hid_t space = H5Screate_simple(1, rows, nullptr);
  const hid_t table =
      H5Dcreate2(file, "/table", record, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t counts =
      H5Dcreate2(file, "/counts", H5T_STD_I16LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const int16_t values[3] = {-3, 7, 300};
  ASSERT_GE(H5Dwrite(counts, H5T_NATIVE_INT16, H5S_ALL, H5S_ALL, H5P_DEFAULT, values), 0);
  for (hid_t id : {table, counts}) H5Dclose(id);
  H5Sclose(space);
  H5Tclose(record);
  H5Fclose(file);
  EXPECT_EQ(listed_hdf5(path), "/counts 3 int16");
  const std::string compound = refusal_of([&] { read_hdf5_dataset(path, "table"); });
  EXPECT_NE(
      compound.find("the dataset /table 3 compound is not read: only numbers and strings are"),
      std::string::npos)
      << compound;
  EXPECT_EQ(read_hdf5_dataset(path, "counts").values, (std::vector<double>{-3, 7, 300}));
}

TEST(ArrayImport, ADamagedHdf5FileIsRefusedByTheWalkNamingItsByte) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("damaged.h5");
  std::ifstream in(kData + "foreign.h5", std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  // The root group's B-tree: its first child (a symbol-table node) pointed past the end.
  const uint8_t tree[] = {'T', 'R', 'E', 'E'};
  const auto found = std::search(bytes.begin(), bytes.end(), std::begin(tree), std::end(tree));
  ASSERT_NE(found, bytes.end());
  const size_t child_at = static_cast<size_t>(found - bytes.begin()) + 24 + 8;
  std::memset(bytes.data() + child_at, 0xff, 8);
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  }
  const std::string expected = "byte " + std::to_string(child_at) + ": an address";
  EXPECT_NE(refusal_of([&] { hdf5_datasets(path); }).find(expected), std::string::npos);
  const std::string refusal = refusal_of([&] { read_hdf5_dataset(path, "/sensors/pressure"); });
  EXPECT_NE(refusal.find(path + ": " + expected), std::string::npos) << refusal;
}

TEST(ArrayImport, ADriverInformationBlockPastTheEndIsRefusedBeforeLibhdf5AllocatesIt) {
  // The fuzzer's finding: a superblock naming a driver information block at byte 255, whose
  // declared size libhdf5 1.10.8 allocated (4 GB) before reading it.
  const std::string path =
      tactile::test::test_data_dir() +
      "/../fuzz/regressions/hdf5/driver-info-size-makes-libhdf5-allocate-4-gb.h5";
  const std::string walked = refusal_of([&] { hdf5_datasets(path); });
  EXPECT_NE(walked.find("byte 259: an address 271"), std::string::npos) << walked;
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> image((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  const std::string recording = refusal_of([&] { RecordingFile::from_image(image, "image.h5"); });
  EXPECT_NE(recording.find("image.h5: byte 48: a driver information block past the end"),
            std::string::npos)
      << recording;
  // The same file on disk, as `tactile info` or the workbench open it.
  const std::string on_disk = refusal_of([&] { RecordingFile{path}; });
  EXPECT_NE(on_disk.find("byte 48: a driver information block past the end"), std::string::npos)
      << on_disk;
}

TEST(CsvTable, AClassColumnAndGroupColumnsMakeRecordingsWithLabels) {
  CsvTableOptions options;
  options.class_column = "gesture";
  options.group_columns = {"subject", "capture"};
  const std::vector<ImportedRecording> groups =
      import_csv_table(kData + "table.csv", load_layout("strip:4"), options);
  ASSERT_EQ(groups.size(), 4u);
  EXPECT_EQ(groups[2].recording.id, "table-s2-1");
  EXPECT_EQ(groups[2].recording.metadata.at("subject"), "s2");
  EXPECT_EQ(groups[2].recording.streams.front().sample_count(), 20);
  EXPECT_DOUBLE_EQ(groups[2].recording.streams.front().rate_hz, 100.0);
  ASSERT_EQ(groups[2].labels.size(), 1u);
  EXPECT_EQ(groups[2].labels[0].class_name, "tap");
  EXPECT_NEAR(groups[2].labels[0].t0, 0.05, 1e-12);
  EXPECT_NEAR(groups[2].labels[0].t1, 0.12, 1e-12);
  options.class_column = "gest";
  EXPECT_NE(refusal_of([&] {
              import_csv_table(kData + "table.csv", load_layout("strip:4"), options);
            }).find("no column 'gest'"),
            std::string::npos);
}

}  // namespace
}  // namespace tactile

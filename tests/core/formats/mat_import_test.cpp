// MATLAB .mat files: the fixtures Octave wrote (tests/data/interop/make_mat_fixtures.m, v5
// uncompressed and compressed) and a v7.3 file libmatio writes here, read value by value in
// C order (samples(t, c) = 100 t + c, so a transposed read shows); names, classes and the rate
// through the import; and files whose structure lies refused with their place before libmatio
// is given them.
#include <gtest/gtest.h>
#include <matio.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/import.h"
#include "tactile/formats/mat_files.h"
#include "test_paths.h"

namespace tactile {
namespace {

using testing::refusal_of;

const std::string kInterop = tactile::test::test_data_dir() + "/interop/";
const std::string kV6 = kInterop + "tactile_v6.mat";
const std::string kV7 = kInterop + "tactile_v7.mat";

std::vector<uint8_t> mat_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_mat_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

// samples(t, c) = 100 t + c for t = 1..6, c = 1..4, in C order.
void expect_samples(const ImportedArray& array) {
  ASSERT_EQ(array.shape, (std::vector<int64_t>{6, 4}));
  ASSERT_EQ(array.values.size(), 24u);
  for (int t = 1; t <= 6; ++t)
    for (int c = 1; c <= 4; ++c)
      EXPECT_EQ(array.values[static_cast<size_t>((t - 1) * 4 + (c - 1))], 100 * t + c)
          << "t " << t << " c " << c;
}

// A v7.3 file (HDF5 inside) written by libmatio: Octave cannot write one.
void write_mat73(const std::string& path) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT73);
  ASSERT_NE(mat, nullptr);
  std::vector<double> samples(24);  // column-major, as MATLAB holds it
  for (int t = 1; t <= 6; ++t)
    for (int c = 1; c <= 4; ++c) samples[static_cast<size_t>((t - 1) + 6 * (c - 1))] = 100 * t + c;
  size_t dims[2] = {6, 4};
  matvar_t* variable =
      Mat_VarCreate("samples", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, samples.data(), 0);
  ASSERT_EQ(Mat_VarWrite(mat, variable, MAT_COMPRESSION_NONE), 0);
  Mat_VarFree(variable);
  double rate = 250;
  size_t scalar[2] = {1, 1};
  variable = Mat_VarCreate("rate", MAT_C_DOUBLE, MAT_T_DOUBLE, 2, scalar, &rate, 0);
  ASSERT_EQ(Mat_VarWrite(mat, variable, MAT_COMPRESSION_NONE), 0);
  Mat_VarFree(variable);
  // names = ['Punch '; 'Stroke'], column-major.
  const char rows[2][7] = {"Punch ", "Stroke"};
  std::vector<uint8_t> names(12);
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 6; ++column)
      names[static_cast<size_t>(row + 2 * column)] = static_cast<uint8_t>(rows[row][column]);
  size_t name_dims[2] = {2, 6};
  variable = Mat_VarCreate("names", MAT_C_CHAR, MAT_T_UINT8, 2, name_dims, names.data(), 0);
  ASSERT_EQ(Mat_VarWrite(mat, variable, MAT_COMPRESSION_NONE), 0);
  Mat_VarFree(variable);
  Mat_Close(mat);
}

TEST(MatImport, OctaveV5FilesReadEveryValueInCOrder) {
  for (const std::string& path : {kV6, kV7}) {
    SCOPED_TRACE(path);
    expect_samples(read_mat_variable(path, "samples"));
    const ImportedArray rate = read_mat_variable(path, "rate");
    EXPECT_EQ(rate.values, std::vector<double>{250});
    const ImportedArray index = read_mat_variable(path, "class_index");
    EXPECT_EQ(index.values, (std::vector<double>{1, 1, 0, 2, 2, 0}));
    const ImportedArray counts = read_mat_variable(path, "counts");
    EXPECT_EQ(counts.shape, (std::vector<int64_t>{1, 3}));
    EXPECT_EQ(counts.values, (std::vector<double>{-3, 7, 300}));
    EXPECT_EQ(read_mat_variable(path, "touched").values, (std::vector<double>{1, 0, 1}));
  }
}

TEST(MatImport, AThreeDimensionalStructFieldKeepsEachSubscript) {
  for (const std::string& path : {kV6, kV7}) {
    SCOPED_TRACE(path);
    const ImportedArray pressure = read_mat_variable(path, "s.pressure");
    ASSERT_EQ(pressure.shape, (std::vector<int64_t>{6, 2, 2}));
    for (int t = 1; t <= 6; ++t)
      for (int r = 1; r <= 2; ++r)
        for (int c = 1; c <= 2; ++c)
          EXPECT_EQ(pressure.values[static_cast<size_t>(((t - 1) * 2 + (r - 1)) * 2 + (c - 1))],
                    100 * t + 10 * r + c);
    EXPECT_EQ(read_mat_variable(path, "s.rate").values, std::vector<double>{50});
  }
}

TEST(MatImport, NamesComeFromACellArrayOrACharMatrix) {
  for (const std::string& path : {kV6, kV7}) {
    SCOPED_TRACE(path);
    const ImportedArray classes = read_mat_variable(path, "classes");
    ASSERT_TRUE(classes.text);
    EXPECT_EQ(classes.strings,
              (std::vector<std::string>{"Punch", "Punch", "none", "Stroke", "Stroke", ""}));
    const ImportedArray names = read_mat_variable(path, "names");
    EXPECT_EQ(names.strings, (std::vector<std::string>{"Punch", "Stroke"}));
  }
}

TEST(MatImport, VariablesAreListedWithTheirSizesAndClasses) {
  std::vector<std::string> lines;
  for (const MatVariable& variable : mat_variables(kV7))
    lines.push_back(mat_variable_line(variable));
  EXPECT_EQ(lines,
            (std::vector<std::string>{"samples 6x4 double", "rate 1x1 double", "classes 6x1 cell",
                                      "class_index 6x1 int32", "names 2x6 char", "s 1x1 struct",
                                      "s.pressure 6x2x2 single", "s.rate 1x1 double",
                                      "counts 1x3 int16", "touched 1x3 logical",
                                      "waves 1x2 complex double", "sparse_map 2x2 sparse"}));
  EXPECT_EQ(mat_variable_names(kV6), mat_variable_names(kV7));
}

TEST(MatImport, ComplexSparseAndMissingVariablesAreRefusedByName) {
  EXPECT_NE(refusal_of([] { read_mat_variable(kV7, "waves"); }).find("waves 1x2 complex double"),
            std::string::npos);
  EXPECT_NE(refusal_of([] { read_mat_variable(kV6, "sparse_map"); }).find("sparse_map 2x2 sparse"),
            std::string::npos);
  const std::string missing = refusal_of([] { read_mat_variable(kV7, "pressure"); });
  EXPECT_NE(missing.find("no variable pressure"), std::string::npos) << missing;
  EXPECT_NE(missing.find("s.pressure 6x2x2 single"), std::string::npos) << missing;
  EXPECT_NE(refusal_of([] { read_mat_variable(kV7, "s.force"); }).find("fields: pressure, rate"),
            std::string::npos);
  EXPECT_NE(refusal_of([] { read_mat_variable(kV7, "rate.x"); }).find("not a struct"),
            std::string::npos);
}

TEST(MatImport, AV73FileWrittenByLibmatioReadsTheSameValues) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("v73.mat");
  write_mat73(path);
  expect_samples(read_mat_variable(path, "samples"));
  EXPECT_EQ(read_mat_variable(path, "rate").values, std::vector<double>{250});
  EXPECT_EQ(read_mat_variable(path, "names").strings,
            (std::vector<std::string>{"Punch", "Stroke"}));
}

TEST(MatImport, AV73AttributeWhoseDataspaceLiesIsRefusedBeforeLibhdf5DecodesIt) {
  // The fuzzer's finding: libhdf5 1.10.8 read past a heap buffer decoding this attribute of a
  // variable's object header (libmatio asks for MATLAB_class while it lists the variables).
  const std::string path = tactile::test::test_data_dir() +
                           "/../fuzz/regressions/mat/v73-attribute-dataspace-past-its-message.mat";
  const std::string refusal = refusal_of([&] { mat_variables(path); });
  EXPECT_NE(refusal.find("byte 1336: a dataspace of more than 2^40 elements"), std::string::npos)
      << refusal;
  // An attribute whose name claims more bytes than its message holds.
  testing::TemporaryDirectory directory;
  const std::string named = directory.file("named73.mat");
  write_mat73(named);
  std::vector<uint8_t> changed = mat_bytes(named);
  const auto name = std::search(changed.begin(), changed.end(), std::begin("MATLAB_class"),
                                std::end("MATLAB_class") - 1);
  ASSERT_NE(name, changed.end());
  const size_t message = static_cast<size_t>(name - changed.begin()) - 8;  // version 1 header
  ASSERT_EQ(changed[message], 1);
  changed[message + 2] = 0xff;  // name size 255: past the message
  const std::string lying = directory.file("lying73.mat");
  write_mat_bytes(lying, changed);
  const std::string too_long = refusal_of([&] { mat_variables(lying); });
  EXPECT_NE(too_long.find("an attribute whose name (255)"), std::string::npos) << too_long;
}

TEST(MatImport, AV73GroupNodePastTheEndIsRefusedBeforeLibhdf5FollowsIt) {
  // The fuzzer's finding: libhdf5 copied from a null pointer following the root group's
  // B-tree (its bytes shifted: the heap the superblock names is not where it points).
  const std::string path = tactile::test::test_data_dir() +
                           "/../fuzz/regressions/mat/v73-group-btree-child-past-the-end.mat";
  const std::string refusal = refusal_of([&] { read_mat_variable(path, "samples"); });
  EXPECT_NE(refusal.find("byte 1192: no local heap signature"), std::string::npos) << refusal;
  // A child address past the end of file.
  testing::TemporaryDirectory directory;
  const std::string child = directory.file("child73.mat");
  write_mat73(child);
  std::vector<uint8_t> changed = mat_bytes(child);
  const auto tree =
      std::search(changed.begin(), changed.end(), std::begin("TREE"), std::end("TREE") - 1);
  ASSERT_NE(tree, changed.end());
  const size_t child_at = static_cast<size_t>(tree - changed.begin()) + 24 + 8;
  std::memset(changed.data() + child_at, 0xff, 8);
  write_mat_bytes(child, changed);
  EXPECT_NE(refusal_of([&] {
              read_mat_variable(child, "samples");
            }).find("byte " + std::to_string(child_at) + ": an address"),
            std::string::npos);
  const std::string cut = directory.file("cut73.mat");
  write_mat73(cut);
  std::vector<uint8_t> bytes = mat_bytes(cut);
  bytes.resize(bytes.size() - 100);
  write_mat_bytes(cut, bytes);
  EXPECT_NE(refusal_of([&] { read_mat_variable(cut, "samples"); }).find("end of file at"),
            std::string::npos);
}

TEST(MatImport, EveryTruncationOfAV5FileIsRefusedOrReadWhole) {
  for (const std::string& path : {kV6, kV7}) {
    const std::vector<uint8_t> bytes = mat_bytes(path);
    testing::TemporaryDirectory directory;
    const std::string cut = directory.file("cut.mat");
    // Every third length (a step prime to the elements' 8-byte alignment), and the last.
    for (size_t size = 0; size < bytes.size();
         size = size + 3 < bytes.size() ? size + 3 : size + 1) {
      write_mat_bytes(cut, std::vector<uint8_t>(bytes.begin(), bytes.begin() + size));
      // Cut at a variable's end, the variables before it are whole; anywhere else refused.
      try {
        const ImportedArray samples = read_mat_variable(cut, "samples");
        expect_samples(samples);
      } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find(cut), std::string::npos);
      }
    }
  }
}

// The byte offset of samples' dimensions in the uncompressed file: after the header (128),
// the element tag (8), the array flags (16) and the dimensions' tag (8).
constexpr size_t kSamplesDims = 128 + 8 + 16 + 8;

TEST(MatImport, DimensionsThatLieAreRefusedBeforeLibmatioReads) {
  const std::vector<uint8_t> bytes = mat_bytes(kV6);
  int32_t rows = 0;
  std::memcpy(&rows, bytes.data() + kSamplesDims, 4);
  ASSERT_EQ(rows, 6);  // the fixture is as this test reads it
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("lie.mat");
  for (int32_t lie : {7, 5, 1 << 30, -6}) {
    std::vector<uint8_t> changed = bytes;
    std::memcpy(changed.data() + kSamplesDims, &lie, 4);
    write_mat_bytes(path, changed);
    const std::string refusal = refusal_of([&] { read_mat_variable(path, "samples"); });
    EXPECT_NE(refusal.find("variable samples, byte "), std::string::npos) << lie << refusal;
  }
  // A struct's field-name length of 0 (libmatio divides by it).
  std::vector<uint8_t> changed = bytes;
  const std::string field_names = "pressure";
  const auto at =
      std::search(changed.begin(), changed.end(), field_names.begin(), field_names.end());
  ASSERT_NE(at, changed.end());
  // The length is a small element just before the names' tag: 4 bytes of value, 8 before.
  const size_t length_value = static_cast<size_t>(at - changed.begin()) - 8 - 4;
  int32_t length = 0;
  std::memcpy(&length, changed.data() + length_value, 4);
  ASSERT_GE(length, 9);
  const int32_t zero = 0;
  std::memcpy(changed.data() + length_value, &zero, 4);
  write_mat_bytes(path, changed);
  EXPECT_NE(refusal_of([&] { read_mat_variable(path, "rate"); }).find("field-name length of 0"),
            std::string::npos);
}

TEST(MatImport, FilesThatAreNotMatlab4V5OrV73AreRefused) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("no.mat");
  testing::write_text(path, "short");
  const std::string short_refusal = refusal_of([&] { read_mat_variable(path, "x"); });
  EXPECT_NE(short_refusal.find("128-byte header (5 bytes), and its first bytes are no MATLAB 4 "
                               "variable header"),
            std::string::npos)
      << short_refusal;
  std::vector<uint8_t> bytes = mat_bytes(kV6);
  bytes[126] = 'X';
  write_mat_bytes(path, bytes);
  EXPECT_NE(refusal_of([&] { read_mat_variable(path, "samples"); }).find("nor a MATLAB 4 file"),
            std::string::npos);
  bytes = mat_bytes(kV7);
  bytes[125] = 3;
  write_mat_bytes(path, bytes);
  EXPECT_NE(refusal_of([&] { read_mat_variable(path, "samples"); }).find("byte 124"),
            std::string::npos);
}

//---- through the import

FileImportOptions mat_options(const std::string& file) {
  FileImportOptions options;
  options.file = file;
  options.layout = "grid:2x2";
  return options;
}

TEST(MatImport, TheImportReadsSamplesRateAndClassesByName) {
  testing::TemporaryDirectory directory;
  FileImportOptions options = mat_options(kV7);
  options.values.set("--dataset", "samples");
  options.values.set("--rate-variable", "rate");
  options.values.set("--class-array", "classes");
  const ImportPreview preview = preview_import(options, 6);
  ASSERT_EQ(preview.refusal, "");
  EXPECT_EQ(preview.format, ".mat array");
  EXPECT_EQ(preview.rate_hz, 250);
  ASSERT_EQ(preview.frames.size(), 6u);
  EXPECT_EQ(preview.frames[1], (std::vector<double>{201, 202, 203, 204}));
  EXPECT_EQ(preview.frame_classes,
            (std::vector<std::string>{"Punch", "Punch", "", "Stroke", "Stroke", ""}));
  EXPECT_EQ(preview.labels, 2u);
  // The 3-D field, as frames of the 2 x 2 grid, with the struct's own rate.
  options.values.set("--dataset", "s.pressure");
  options.values.set("--rate-variable", "s.rate");
  options.values.erase("--class-array");
  const ImportPreview grid = preview_import(options, 2);
  ASSERT_EQ(grid.refusal, "");
  EXPECT_EQ(grid.rate_hz, 50);
  EXPECT_EQ(grid.frames[0], (std::vector<double>{111, 112, 121, 122}));
}

TEST(MatImport, TheOneArrayOfAFileIsReadWithoutItsName) {
  FileImportOptions options = mat_options(kInterop + "one_array.mat");
  options.values.set("--rate-variable", "fs");
  const ImportPreview preview = preview_import(options, 1);
  ASSERT_EQ(preview.refusal, "");
  EXPECT_EQ(preview.rate_hz, 100);
  EXPECT_EQ(preview.frames[0], (std::vector<double>{101, 102, 103, 104}));
  // Two candidates: refused listing every variable with its size and class.
  options = mat_options(kV6);
  options.values.set("--rate", "10");
  const std::string refusal = preview_import(options).refusal;
  EXPECT_NE(refusal.find("--dataset"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("s.pressure 6x2x2 single"), std::string::npos) << refusal;
}

TEST(MatImport, TheRateVariableIsOneNumberAndNotWithRate) {
  FileImportOptions options = mat_options(kV6);
  options.values.set("--dataset", "samples");
  options.values.set("--rate-variable", "rate");
  options.values.set("--rate", "100");
  EXPECT_NE(preview_import(options).refusal.find("--rate-variable: or --rate, not both"),
            std::string::npos);
  options.values.erase("--rate");
  options.values.set("--rate-variable", "counts");
  EXPECT_NE(preview_import(options).refusal.find("is not one positive number"), std::string::npos);
  options = mat_options(tactile::test::test_data_dir() + "/io/long_strip3.csv");
  options.values.set("--rate-variable", "rate");
  EXPECT_NE(preview_import(options).refusal.find("--rate-variable: is not an option of CSV files"),
            std::string::npos)
      << preview_import(options).refusal;
}

TEST(MatImport, ClassIndicesNameTheLayoutsClasses) {
  FileImportOptions options = mat_options(kV6);
  options.layout = "grid:2x2";
  options.values.set("--dataset", "samples");
  options.values.set("--rate-variable", "rate");
  options.values.set("--class-array", "class_index");
  const ImportPreview preview = preview_import(options, 6);
  ASSERT_EQ(preview.refusal, "");
  // grid:RxC has no vocabulary of its own: indices stay numbers.
  EXPECT_EQ(preview.frame_classes[0], "1");
  EXPECT_EQ(preview.frame_classes[3], "2");
}

}  // namespace
}  // namespace tactile

// MATLAB files laid out as MATLAB itself writes them, where the first reader met a file of real
// MATLAB it had not seen (issue 44): a `string` saved by MATLAB 2017b+ (an opaque MCOS object
// in a v5 file), a v7.3 struct holding a sparse field beside a dense one, and MATLAB 4 (Level
// 4) files, which have no 128-byte header and may be shorter than it.
#include <gtest/gtest.h>
#include <matio.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/formats/import.h"
#include "tactile/formats/mat_files.h"

namespace tactile {
namespace {

using testing::refusal_of;

//---- the bytes of a v5 file, element by element

using Bytes = std::vector<uint8_t>;

void append_word(Bytes& bytes, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<uint8_t>(value >> shift));
}

void append_bytes(Bytes& bytes, const void* data, size_t count) {
  const auto* first = static_cast<const uint8_t*>(data);
  bytes.insert(bytes.end(), first, first + count);
}

// A data element: its 8-byte tag (type, byte count), the bytes, padding to 8.
Bytes element(uint32_t type, const Bytes& data) {
  Bytes bytes;
  append_word(bytes, type);
  append_word(bytes, static_cast<uint32_t>(data.size()));
  append_bytes(bytes, data.data(), data.size());
  bytes.resize((bytes.size() + 7) / 8 * 8, 0);
  return bytes;
}

// A small data element (4 bytes or fewer): type and count in one word, the bytes in the next.
Bytes small_element(uint32_t type, const std::string& text) {
  Bytes bytes;
  append_word(bytes, static_cast<uint32_t>(text.size()) << 16 | type);
  append_bytes(bytes, text.data(), text.size());
  bytes.resize(8, 0);
  return bytes;
}

Bytes text_bytes(const std::string& text) { return Bytes(text.begin(), text.end()); }

Bytes joined(std::initializer_list<Bytes> parts) {
  Bytes bytes;
  for (const Bytes& part : parts) append_bytes(bytes, part.data(), part.size());
  return bytes;
}

constexpr uint32_t kMiInt8 = 1, kMiUint8 = 2, kMiInt32 = 5, kMiUint32 = 6, kMiDouble = 9,
                   kMiMatrix = 14;

Bytes array_flags(uint32_t array_class) {
  Bytes flags;
  append_word(flags, array_class);
  append_word(flags, 0);
  return element(kMiUint32, flags);
}

Bytes dimensions(std::initializer_list<int32_t> extents) {
  Bytes dims;
  for (int32_t extent : extents) append_word(dims, static_cast<uint32_t>(extent));
  return element(kMiInt32, dims);
}

// A 2 x 3 double matrix [1 2 3; 4 5 6] (stored column-major), named `name` ("" in a struct).
Bytes double_matrix(const std::string& name) {
  Bytes values;
  for (double value : {1.0, 4.0, 2.0, 5.0, 3.0, 6.0}) append_bytes(values, &value, 8);
  return element(kMiMatrix,
                 joined({array_flags(6), dimensions({2, 3}), element(kMiInt8, text_bytes(name)),
                         element(kMiDouble, values)}));
}

// A `string` as MATLAB 2017b+ saves it (save -v6, and inflated, save -v7): an miMATRIX whose
// array flags say class 17 (mxOPAQUE_CLASS), then no dimensions but the variable's name, the
// type system's name "MCOS" (a small element: 4 bytes), the class name "string", and the
// object's metadata: a 6x1 uint32 array [0xdd000000 2 1 1 object-id class-id] (the reference
// into the subsystem data: its marker, 2 dimensions of 1 x 1, the object and class numbers).
Bytes string_object(const std::string& name) {
  Bytes reference;
  for (uint32_t value : {0xdd000000u, 2u, 1u, 1u, 1u, 1u}) append_word(reference, value);
  const Bytes metadata =
      element(kMiMatrix, joined({array_flags(13), dimensions({6, 1}), element(kMiInt8, {}),
                                 element(kMiUint32, reference)}));
  return element(kMiMatrix, joined({array_flags(17), element(kMiInt8, text_bytes(name)),
                                    small_element(kMiInt8, "MCOS"),
                                    element(kMiInt8, text_bytes("string")), metadata}));
}

// The header: 116 bytes of text, the subsystem data's offset (8 bytes), version 0x0100, "IM".
Bytes v5_header(uint64_t subsystem_at) {
  Bytes header = text_bytes(
      "MATLAB 5.0 MAT-file, Platform: GLNXA64, Created on: Mon Mar  4 "
      "10:00:00 2024");
  header.resize(116, ' ');
  append_bytes(header, &subsystem_at, 8);
  header.push_back(0x00);
  header.push_back(0x01);
  header.push_back('I');
  header.push_back('M');
  return header;
}

// What MATLAB writes after the variables of a file holding objects: a nameless 1xN uint8
// variable at the header's subsystem offset. Its bytes are a MAT stream of their own (the MCOS
// FileWrapper__ holding the string's characters); nothing here reads them, so this one holds
// only that stream's 8-byte start (version 0x0100, "IM") and zeros.
Bytes subsystem_data() {
  Bytes stream = {0x00, 0x01, 'I', 'M', 0, 0, 0, 0};
  stream.resize(32, 0);
  return element(kMiMatrix, joined({array_flags(9), dimensions({1, 32}), element(kMiInt8, {}),
                                    element(kMiUint8, stream)}));
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

//---- MATLAB 2017b+ string objects (v5)

TEST(MatAsMatlabWrites, AStringObjectIsListedAndRefusedByItsNameAndClass) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("with_string.mat");
  // samples = [1 2 3; 4 5 6]; label = "Punch"; s.name = "Punch"; s.data = samples;
  // save('with_string.mat', 'samples', 'label', 's', '-v6')
  const Bytes samples = double_matrix("samples");
  const Bytes label = string_object("label");
  // The struct: its field-name length (a small miINT32: 8), the names padded to 8 bytes each,
  // then each field's miMATRIX, nameless.
  Bytes names = text_bytes("name");
  names.resize(8, 0);
  const Bytes data_name = text_bytes("data");
  names.insert(names.end(), data_name.begin(), data_name.end());
  names.resize(16, 0);
  Bytes field_length;
  append_word(field_length, 4u << 16 | kMiInt32);
  append_word(field_length, 8);
  const Bytes structure = element(
      kMiMatrix,
      joined({array_flags(2), dimensions({1, 1}), element(kMiInt8, text_bytes("s")), field_length,
              element(kMiInt8, names), string_object(""), double_matrix("")}));
  const uint64_t subsystem_at = 128 + samples.size() + label.size() + structure.size();
  write_bytes(path, joined({v5_header(subsystem_at), samples, label, structure, subsystem_data()}));

  std::vector<std::string> lines;
  for (const MatVariable& variable : mat_variables(path))
    lines.push_back(mat_variable_line(variable));
  EXPECT_EQ(lines,
            (std::vector<std::string>{"samples 2x3 double", "label string object", "s 1x1 struct",
                                      "s.name string object", "s.data 2x3 double"}));
  const ImportedArray read = read_mat_variable(path, "samples");
  EXPECT_EQ(read.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(read_mat_variable(path, "s.data").values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  const std::string refusal = refusal_of([&] { read_mat_variable(path, "label"); });
  EXPECT_NE(refusal.find("variable label (a MATLAB string object of the MCOS type system) is "
                         "not read"),
            std::string::npos)
      << refusal;
  EXPECT_NE(refusal.find("cellstr(label)"), std::string::npos) << refusal;
  const std::string field = refusal_of([&] { read_mat_variable(path, "s.name"); });
  EXPECT_NE(field.find("s.name string object is not read"), std::string::npos) << field;
}

TEST(MatAsMatlabWrites, AStringObjectInACompressedVariableIsListedByItsClass) {
  // save('with_string.mat', 'samples', 'label') (-v7, MATLAB's default): each variable's
  // miMATRIX deflated into an miCOMPRESSED element (type 15, not padded).
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("compressed_string.mat");
  const Bytes label = string_object("label");
  uLongf deflated_size = compressBound(label.size());
  Bytes deflated(deflated_size);
  ASSERT_EQ(compress(deflated.data(), &deflated_size, label.data(), label.size()), Z_OK);
  deflated.resize(deflated_size);
  Bytes compressed;
  append_word(compressed, 15);
  append_word(compressed, static_cast<uint32_t>(deflated.size()));
  append_bytes(compressed, deflated.data(), deflated.size());
  write_bytes(path, joined({v5_header(0), double_matrix("samples"), compressed}));
  EXPECT_EQ(mat_variable_names(path), (std::vector<std::string>{"samples", "label"}));
  EXPECT_EQ(read_mat_variable(path, "samples").values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_NE(refusal_of([&] {
              read_mat_variable(path, "label");
            }).find("a MATLAB string object of the MCOS type system"),
            std::string::npos);
}

//---- a v7.3 struct of a sparse and a dense field

TEST(MatAsMatlabWrites, AV73StructFieldIsReadBesideASparseField) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("struct73.mat");
  // data.sparse = sparse([1 3], [1 3], [5 7], 3, 3); data.dense = [1 2 3; 4 5 6];
  // save('struct73.mat', 'data', '-v7.3') writes a group "data" holding a sparse group (ir, jc,
  // data datasets and a MATLAB_sparse attribute) and a dataset; libmatio follows that layout.
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT73);
  ASSERT_NE(mat, nullptr);
  const char* fields[] = {"sparse", "dense"};
  size_t one[2] = {1, 1};
  matvar_t* data = Mat_VarCreateStruct("data", 2, one, fields, 2);
  mat_uint32_t rows[] = {0, 2}, columns[] = {0, 1, 1, 2};
  double nonzero[] = {5, 7};
  mat_sparse_t sparse{};
  sparse.nzmax = 2;
  sparse.ir = rows;
  sparse.nir = 2;
  sparse.jc = columns;
  sparse.njc = 4;
  sparse.ndata = 2;
  sparse.data = nonzero;
  size_t square[2] = {3, 3};
  Mat_VarSetStructFieldByName(
      data, "sparse", 0, Mat_VarCreate(nullptr, MAT_C_SPARSE, MAT_T_DOUBLE, 2, square, &sparse, 0));
  double dense[] = {1, 4, 2, 5, 3, 6};  // column-major
  size_t two_three[2] = {2, 3};
  Mat_VarSetStructFieldByName(
      data, "dense", 0, Mat_VarCreate(nullptr, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, two_three, dense, 0));
  ASSERT_EQ(Mat_VarWrite(mat, data, MAT_COMPRESSION_NONE), 0);
  Mat_VarFree(data);
  Mat_Close(mat);

  const ImportedArray read = read_mat_variable(path, "data.dense");
  EXPECT_EQ(read.shape, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(read.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_NE(refusal_of([&] {
              read_mat_variable(path, "data.sparse");
            }).find("data.sparse 3x3 sparse is not read"),
            std::string::npos);
  // Through the import: named, and unnamed as the file's one array (both were refused because
  // of the sparse field).
  FileImportOptions options;
  options.file = path;
  options.layout = "strip:3";
  options.values.set("--rate", "10");
  for (const std::string dataset : {"data.dense", ""}) {
    SCOPED_TRACE(dataset);
    if (!dataset.empty()) options.values.set("--dataset", dataset);
    const ImportPreview preview = preview_import(options, 2);
    ASSERT_EQ(preview.refusal, "");
    EXPECT_EQ(preview.frames[1], (std::vector<double>{4, 5, 6}));
    options.values.erase("--dataset");
  }
}

//---- MATLAB 4 (Level 4) files

// One Level 4 variable: type MOPT, rows, columns, imaginary flag, name length (int32 each, in
// the byte order of M), the NUL-terminated name, the values column-major.
Bytes v4_variable(int32_t type, int32_t rows, int32_t columns, const std::string& name,
                  const std::vector<double>& values, bool big_endian = false) {
  Bytes bytes;
  for (int32_t field : {type, rows, columns, 0, static_cast<int32_t>(name.size() + 1)}) {
    uint32_t word = static_cast<uint32_t>(field);
    if (big_endian) word = __builtin_bswap32(word);
    append_word(bytes, word);
  }
  append_bytes(bytes, name.c_str(), name.size() + 1);
  for (double value : values) {
    uint64_t raw;
    std::memcpy(&raw, &value, 8);
    if (big_endian) raw = __builtin_bswap64(raw);
    append_bytes(bytes, &raw, 8);
  }
  return bytes;
}

TEST(MatAsMatlabWrites, AMatlab4FileShorterThan128BytesIsRead) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("x4.mat");
  // x = [1 2 3; 4 5 6]; save('x4.mat', 'x', '-v4'): 20 + 2 + 48 = 70 bytes, no file header.
  const Bytes little = v4_variable(0, 2, 3, "x", {1, 4, 2, 5, 3, 6});
  ASSERT_EQ(little.size(), 70u);
  write_bytes(path, little);
  ASSERT_EQ(mat_variable_names(path), std::vector<std::string>{"x"});
  ImportedArray read = read_mat_variable(path, "x");
  EXPECT_EQ(read.shape, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(read.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  // MATLAB 4 on a big-endian machine (M = 1: type 1000), with a second variable.
  write_bytes(path, joined({v4_variable(1000, 2, 3, "x", {1, 4, 2, 5, 3, 6}, true),
                            v4_variable(1000, 1, 1, "fs", {250}, true)}));
  read = read_mat_variable(path, "x");
  EXPECT_EQ(read.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(read_mat_variable(path, "fs").values, std::vector<double>{250});
}

TEST(MatAsMatlabWrites, AMatlab4FileThatCannotBeReadIsRefusedAsMatlab4) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("bad4.mat");
  // Cut inside its values.
  Bytes cut = v4_variable(0, 2, 3, "x", {1, 4, 2, 5, 3, 6});
  cut.resize(cut.size() - 8);
  write_bytes(path, cut);
  std::string refusal = refusal_of([&] { read_mat_variable(path, "x"); });
  EXPECT_NE(refusal.find("MATLAB 4 file, byte 0, variable x: 2 x 3 values need 48 bytes, the "
                         "file has 40 left"),
            std::string::npos)
      << refusal;
  // A sparse matrix (T = 2), as MATLAB 4 saves one: refused naming it.
  write_bytes(path, joined({v4_variable(0, 1, 1, "fs", {250}),
                            v4_variable(2, 3, 3, "map", {1, 3, 3, 1, 3, 3, 5, 7, 0})}));
  refusal = refusal_of([&] { read_mat_variable(path, "fs"); });
  EXPECT_NE(refusal.find("MATLAB 4 file, byte 31, variable map: a MATLAB 4 sparse matrix is not "
                         "read"),
            std::string::npos)
      << refusal;
  // A VAX D-float file (M = 2).
  write_bytes(path, v4_variable(2000, 1, 1, "fs", {250}));
  refusal = refusal_of([&] { read_mat_variable(path, "fs"); });
  EXPECT_NE(refusal.find("number format M=2 (VAX or Cray) is not read"), std::string::npos)
      << refusal;
}

}  // namespace
}  // namespace tactile

// The structure of a MATLAB v5 file walked before libmatio reads it (mat_structure.h). The
// layout is MathWorks' "MAT-File Format" (v5): a 128-byte header, then data elements of an
// 8-byte tag (type, byte count; or a small element of type, count and up to 4 bytes in one 8)
// padded to 8 bytes. A variable is an miMATRIX element (array flags, dimensions, name, then
// its data, cells or fields) or an miCOMPRESSED element holding one miMATRIX deflated.
#include "mat_structure.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/array_import.h"

namespace tactile {

namespace {

// Element types (miINT8 ... miUTF32) and array classes (mxCELL_CLASS ...) of the format.
enum : uint32_t {
  kMiInt8 = 1,
  kMiUint8 = 2,
  kMiInt16 = 3,
  kMiUint16 = 4,
  kMiInt32 = 5,
  kMiUint32 = 6,
  kMiSingle = 7,
  kMiDouble = 9,
  kMiInt64 = 12,
  kMiUint64 = 13,
  kMiMatrix = 14,
  kMiCompressed = 15,
  kMiUtf8 = 16,
  kMiUtf16 = 17,
  kMiUtf32 = 18,
};
enum : uint32_t {
  kMxCell = 1,
  kMxStruct = 2,
  kMxChar = 4,
  kMxSparse = 5,
  kMxDouble = 6,
  kMxUint64 = 15,
  kMxLastClass = 17,
};

constexpr int kMatMaxDepth = 16;              // cells and structs nested deeper are refused
constexpr uint64_t kMatMaxNameBytes = 65536;  // a variable's name, a struct's field names
constexpr uint32_t kMatMaxRank = 32;

// Bytes of one element of a numeric or char data type; 0 for the others.
uint64_t mat_type_bytes(uint32_t type) {
  switch (type) {
    case kMiInt8:
    case kMiUint8:
    case kMiUtf8:
      return 1;
    case kMiInt16:
    case kMiUint16:
    case kMiUtf16:
      return 2;
    case kMiInt32:
    case kMiUint32:
    case kMiSingle:
    case kMiUtf32:
      return 4;
    case kMiDouble:
    case kMiInt64:
    case kMiUint64:
      return 8;
    default:
      return 0;
  }
}

// A forward reader over the file or over a compressed variable's inflated bytes.
class MatByteStream {
 public:
  virtual ~MatByteStream() = default;
  // False when the stream holds fewer bytes (or its deflated data is damaged).
  virtual bool read(uint8_t* out, uint64_t count) = 0;
  virtual bool skip(uint64_t count) = 0;
  uint64_t offset() const { return offset_; }
  // "byte N" of the file, or "inflated byte N of the variable at byte M".
  virtual std::string place(uint64_t at) const = 0;

 protected:
  uint64_t offset_ = 0;
};

class MatFileStream : public MatByteStream {
 public:
  MatFileStream(std::ifstream& in, uint64_t size) : in_(in), size_(size) {}
  void seek(uint64_t at) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    offset_ = at;
  }
  bool read(uint8_t* out, uint64_t count) override {
    if (count > size_ - offset_) return false;
    in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(count));
    if (!in_) return false;
    offset_ += count;
    return true;
  }
  bool skip(uint64_t count) override {
    if (count > size_ - offset_) return false;
    seek(offset_ + count);
    return true;
  }
  std::string place(uint64_t at) const override { return "byte " + std::to_string(at); }

 private:
  std::ifstream& in_;
  uint64_t size_;
};

// Inflates as it is read: at most one input and one scratch window are held, so a variable
// that would inflate to gigabytes is walked in constant memory (and in time bounded by
// zlib's largest ratio, about 1032:1, times the compressed bytes).
class MatInflateStream : public MatByteStream {
 public:
  MatInflateStream(std::ifstream& in, uint64_t compressed, uint64_t element_at)
      : in_(in), left_(compressed), element_at_(element_at) {
    if (inflateInit(&zlib_) != Z_OK) throw Error("zlib", "cannot start inflating");
  }
  ~MatInflateStream() override { inflateEnd(&zlib_); }
  MatInflateStream(const MatInflateStream&) = delete;
  MatInflateStream& operator=(const MatInflateStream&) = delete;

  bool read(uint8_t* out, uint64_t count) override {
    while (count > 0) {
      const auto chunk = static_cast<uInt>(std::min<uint64_t>(count, 1u << 30));
      const uInt made = produce(out, chunk);
      if (made == 0) return false;
      out += made;
      count -= made;
      offset_ += made;
    }
    return true;
  }
  bool skip(uint64_t count) override {
    while (count > 0) {
      const auto chunk = static_cast<uInt>(std::min<uint64_t>(count, scratch_.size()));
      const uInt made = produce(scratch_.data(), chunk);
      if (made == 0) return false;
      count -= made;
      offset_ += made;
    }
    return true;
  }
  std::string place(uint64_t at) const override {
    return "inflated byte " + std::to_string(at) + " of the compressed variable at byte " +
           std::to_string(element_at_);
  }

 private:
  // Up to `count` inflated bytes into `out`; 0 at the end of the data or on damage.
  uInt produce(uint8_t* out, uInt count) {
    zlib_.next_out = out;
    zlib_.avail_out = count;
    while (zlib_.avail_out == count && !ended_) {
      if (zlib_.avail_in == 0 && left_ > 0) {
        const auto take = static_cast<std::streamsize>(std::min<uint64_t>(left_, input_.size()));
        in_.read(reinterpret_cast<char*>(input_.data()), take);
        if (in_.gcount() != take) return 0;
        left_ -= static_cast<uint64_t>(take);
        zlib_.next_in = input_.data();
        zlib_.avail_in = static_cast<uInt>(take);
      }
      const bool input_left = zlib_.avail_in > 0;
      const int status = inflate(&zlib_, Z_NO_FLUSH);
      if (status == Z_STREAM_END) ended_ = true;
      if (status != Z_OK && status != Z_STREAM_END) return 0;
      if (zlib_.avail_out == count && !input_left && left_ == 0) return 0;
    }
    return count - zlib_.avail_out;
  }

  std::ifstream& in_;
  uint64_t left_;
  uint64_t element_at_;
  z_stream zlib_{};
  bool ended_ = false;
  std::array<uint8_t, 65536> input_{};
  std::array<uint8_t, 65536> scratch_{};
};

// One data element's tag: a small element carries its (up to 4) bytes in the tag.
struct MatTag {
  uint32_t type = 0;
  uint64_t bytes = 0;
  bool small = false;
  std::array<uint8_t, 4> small_data{};
  uint64_t at = 0;  // where the tag starts
};

class MatWalker {
 public:
  MatWalker(std::string path, bool swap) : path_(std::move(path)), swap_(swap) {}

  // The miMATRIX whose bytes run from the stream's offset to `end`; `name` is "" for a
  // top-level variable (its name is read here) or the cell's or field's path.
  void matrix(MatByteStream& stream, uint64_t end, const std::string& given_name, int depth) {
    if (depth > kMatMaxDepth)
      refuse(stream, stream.offset(), given_name,
             "cells or structs nested more than " + std::to_string(kMatMaxDepth) + " deep");
    const uint64_t start = stream.offset();
    if (start == end) {
      // An empty element: what MATLAB writes for an empty cell or field.
      if (given_name.empty()) refuse(stream, start, "", "a variable of no bytes");
      return;
    }
    MatTag flags_tag = tag(stream, end, given_name);
    if (flags_tag.type != kMiUint32 || flags_tag.bytes != 8 || flags_tag.small)
      refuse(stream, flags_tag.at, given_name, "the array flags are not 8 bytes of miUINT32");
    const std::vector<uint8_t> flags = payload(stream, flags_tag, end, given_name);
    const uint32_t array_class = word(flags.data()) & 0xff;
    const bool complex = (word(flags.data()) >> 8) & 0x08;
    MatTag dims_tag = tag(stream, end, given_name);
    if (dims_tag.type != kMiInt32 || dims_tag.small || dims_tag.bytes < 8 ||
        dims_tag.bytes % 4 != 0 || dims_tag.bytes / 4 > kMatMaxRank)
      refuse(stream, dims_tag.at, given_name,
             "the dimensions are not 2 to " + std::to_string(kMatMaxRank) + " miINT32 values");
    const std::vector<uint8_t> dims = payload(stream, dims_tag, end, given_name);
    MatTag name_tag = tag(stream, end, given_name);
    if (name_tag.type != kMiInt8 && name_tag.type != kMiUint8)
      refuse(stream, name_tag.at, given_name, "the array name is not miINT8 text");
    if (name_tag.bytes > kMatMaxNameBytes)
      refuse(stream, name_tag.at, given_name,
             "the array name declares " + std::to_string(name_tag.bytes) + " bytes");
    const std::vector<uint8_t> name_bytes = payload(stream, name_tag, end, given_name);
    const std::string name =
        given_name.empty() ? std::string(name_bytes.begin(), name_bytes.end()) : given_name;
    // The element count, each extent checked before the product (the bound of every reader).
    int64_t count = 1;
    for (size_t at = 0; at < dims.size(); at += 4) {
      const auto extent = static_cast<int32_t>(word(dims.data() + at));
      if (extent < 0)
        refuse(stream, dims_tag.at, name, "a negative extent " + std::to_string(extent));
      if (extent != 0 && count > kMaxImportedElements / extent)
        refuse(stream, dims_tag.at, name,
               "the dimensions declare more than " + std::to_string(kMaxImportedElements) +
                   " elements");
      count *= extent;
    }
    const auto elements = static_cast<uint64_t>(count);
    if (array_class == 0 || array_class > kMxLastClass)
      refuse(stream, flags_tag.at, name, "unknown array class " + std::to_string(array_class));
    // libmatio reads objects, function handles and opaque classes by rules of its own (a
    // function handle whose bytes lie made it ask for 1.6 GB: the fuzzer's
    // regressions/mat/function-handle-makes-libmatio-allocate-1.6-gb.mat), and they are no
    // recording: the file is refused rather than handed over.
    if (array_class == 3 || array_class >= 16)
      refuse(stream, flags_tag.at, name,
             "array class " + std::to_string(array_class) +
                 " (an object, function handle or opaque object) is not read");
    if (array_class == kMxCell) {
      for (uint64_t index = 0; index < elements; ++index)
        child(stream, end, name + "{" + std::to_string(index + 1) + "}", depth);
    } else if (array_class == kMxStruct) {
      structure(stream, end, name, elements, depth);
    } else if (array_class == kMxSparse) {
      // libmatio allocates the row indices and values by nzmax and the column starts by the
      // columns (the fuzzer's regressions/mat/sparse-nzmax-makes-libmatio-allocate-2.3-gb.mat):
      // each must fit in the bytes the array holds.
      const uint64_t nonzero_max = word(flags.data() + 4);
      const uint64_t columns = dims.size() >= 8 ? word(dims.data() + 4) : 0;
      const uint64_t left = end - stream.offset();
      if (nonzero_max > left / 4 || columns + 1 > left / 4)
        refuse(stream, flags_tag.at, name,
               "a sparse array of " + std::to_string(nonzero_max) + " non-zeros and " +
                   std::to_string(columns) + " columns in " + std::to_string(left) + " bytes");
    } else if (array_class == kMxChar || (array_class >= kMxDouble && array_class <= kMxUint64)) {
      data(stream, end, name, elements, array_class == kMxChar, "the data");
      if (complex) data(stream, end, name, elements, false, "the imaginary part");
    }
    // Sparse arrays are stepped over whole: mat_import.cpp refuses them by name when they are
    // asked for.
    if (!stream.skip(end - stream.offset()))
      refuse(stream, stream.offset(), name, "ends before its declared end");
  }

  // The top-level elements, from byte 128 to the end of the file.
  void file(std::ifstream& in, uint64_t size) {
    MatFileStream stream(in, size);
    stream.seek(128);
    while (stream.offset() < size) {
      const MatTag element = tag(stream, size, "");
      if (element.small) refuse(stream, element.at, "", "a variable in a small data element");
      const uint64_t end = stream.offset() + element.bytes;
      if (element.type == kMiMatrix) {
        matrix(stream, end, "", 0);
      } else if (element.type == kMiCompressed) {
        MatInflateStream inflated(in, element.bytes, element.at);
        const MatTag inner = tag(inflated, UINT64_MAX, "");
        if (inner.type != kMiMatrix || inner.small)
          refuse(inflated, inner.at, "", "the compressed element does not hold a miMATRIX");
        matrix(inflated, inflated.offset() + inner.bytes, "", 0);
        stream.seek(end);
      } else {
        refuse(stream, element.at, "",
               "an element of type " + std::to_string(element.type) +
                   " where a variable (miMATRIX or miCOMPRESSED) was expected");
      }
      // An miMATRIX is padded to 8 bytes (the last one's padding may be left out); a
      // compressed element is not padded.
      const uint64_t padding = element.type == kMiMatrix ? (8 - element.bytes % 8) % 8 : 0;
      stream.seek(std::min(size, end + padding));
    }
  }

 private:
  uint32_t word(const uint8_t* bytes) const {
    uint32_t value;
    std::memcpy(&value, bytes, 4);
    return swap_ ? __builtin_bswap32(value) : value;
  }

  [[noreturn]] void refuse(const MatByteStream& stream, uint64_t at, const std::string& name,
                           const std::string& what) const {
    throw Error(path_, (name.empty() ? std::string() : "variable " + name + ", ") +
                           stream.place(at) + ": " + what);
  }

  MatTag tag(MatByteStream& stream, uint64_t end, const std::string& name) {
    MatTag result;
    result.at = stream.offset();
    std::array<uint8_t, 8> bytes{};
    if (end - result.at < 8 || !stream.read(bytes.data(), 8))
      refuse(stream, result.at, name, "a data element's tag is cut short");
    const uint32_t first = word(bytes.data());
    if (first >> 16 != 0) {
      result.small = true;
      result.type = first & 0xffff;
      result.bytes = first >> 16;
      if (result.bytes > 4)
        refuse(stream, result.at, name,
               "a small data element declares " + std::to_string(result.bytes) + " bytes");
      std::memcpy(result.small_data.data(), bytes.data() + 4, 4);
      return result;
    }
    result.type = first;
    result.bytes = word(bytes.data() + 4);
    if (result.bytes > end - stream.offset())
      refuse(stream, result.at, name,
             "a data element declares " + std::to_string(result.bytes) + " bytes, " +
                 std::to_string(end - stream.offset()) + " are left before the end of " +
                 (name.empty() ? "the file or its variable" : "its array"));
    return result;
  }

  // The element's bytes (small, or read and its padding stepped over).
  std::vector<uint8_t> payload(MatByteStream& stream, const MatTag& element, uint64_t end,
                               const std::string& name) {
    if (element.small)
      return {element.small_data.begin(), element.small_data.begin() + element.bytes};
    std::vector<uint8_t> bytes(element.bytes);
    if (!stream.read(bytes.data(), element.bytes))
      refuse(stream, element.at, name, "a data element's bytes are cut short");
    step_padding(stream, element, end);
    return bytes;
  }

  void step_padding(MatByteStream& stream, const MatTag& element, uint64_t end) {
    if (element.small) return;
    const uint64_t padding = (8 - element.bytes % 8) % 8;
    stream.skip(std::min(padding, end - stream.offset()));
  }

  // A cell's or field's miMATRIX.
  void child(MatByteStream& stream, uint64_t end, const std::string& name, int depth) {
    const MatTag element = tag(stream, end, name);
    if (element.type != kMiMatrix || element.small)
      refuse(stream, element.at, name, "is not an miMATRIX element");
    const uint64_t child_end = stream.offset() + element.bytes;
    matrix(stream, child_end, name, depth + 1);
    step_padding(stream, element, end);
  }

  void structure(MatByteStream& stream, uint64_t end, const std::string& name, uint64_t elements,
                 int depth) {
    const MatTag length_tag = tag(stream, end, name);
    if (length_tag.type != kMiInt32 || length_tag.bytes != 4)
      refuse(stream, length_tag.at, name, "the field-name length is not one miINT32");
    const std::vector<uint8_t> length_bytes = payload(stream, length_tag, end, name);
    const auto length = static_cast<int32_t>(word(length_bytes.data()));
    // libmatio divides by this length: 0 would stop the program.
    if (length < 1 || static_cast<uint64_t>(length) > kMatMaxNameBytes)
      refuse(stream, length_tag.at, name,
             "a field-name length of " + std::to_string(length) + " bytes");
    const MatTag names_tag = tag(stream, end, name);
    if (names_tag.type != kMiInt8 && names_tag.type != kMiUint8)
      refuse(stream, names_tag.at, name, "the field names are not miINT8 text");
    if (names_tag.bytes % static_cast<uint64_t>(length) != 0 || names_tag.bytes > kMatMaxNameBytes)
      refuse(stream, names_tag.at, name,
             std::to_string(names_tag.bytes) + " bytes of field names are not whole names of " +
                 std::to_string(length) + " bytes");
    const std::vector<uint8_t> names = payload(stream, names_tag, end, name);
    const uint64_t fields = names.size() / static_cast<uint64_t>(length);
    std::vector<std::string> field_names;
    for (uint64_t field = 0; field < fields; ++field) {
      const auto* first = reinterpret_cast<const char*>(names.data()) + field * length;
      field_names.emplace_back(first, strnlen(first, static_cast<size_t>(length)));
      // MATLAB names every field; a nameless one led libmatio to ask for 2.3 GB (the fuzzer's
      // regressions/mat/struct-field-of-no-name-makes-libmatio-allocate-2.3-gb.mat).
      if (field_names.back().empty())
        refuse(stream, names_tag.at, name, "field " + std::to_string(field + 1) + " has no name");
    }
    if (fields != 0 && elements > static_cast<uint64_t>(kMaxImportedElements) / fields)
      refuse(stream, names_tag.at, name, "declares more fields than can be read");
    // A struct array of no fields holds no bytes however many elements it declares.
    if (field_names.empty()) return;
    for (uint64_t element = 0; element < elements; ++element)
      for (const std::string& field : field_names) {
        const std::string prefix =
            elements == 1 ? name : name + "(" + std::to_string(element + 1) + ")";
        child(stream, end, prefix + "." + field, depth);
      }
  }

  // A numeric or char data element: exactly `elements` values of its type.
  void data(MatByteStream& stream, uint64_t end, const std::string& name, uint64_t elements,
            bool text, const std::string& part) {
    const MatTag element = tag(stream, end, name);
    const uint64_t size = mat_type_bytes(element.type);
    const bool known = text ? size != 0 && element.type != kMiSingle && element.type != kMiDouble
                            : size != 0 && element.type < kMiUtf8;
    if (!known)
      refuse(stream, element.at, name,
             part + " is of element type " + std::to_string(element.type) + ", not " +
                 (text ? "characters" : "numbers"));
    if (element.bytes != elements * size)
      refuse(stream, element.at, name,
             part + " holds " + std::to_string(element.bytes) + " bytes where its dimensions ask " +
                 std::to_string(elements) + " x " + std::to_string(size));
    if (element.small) return;
    if (!stream.skip(element.bytes)) refuse(stream, element.at, name, part + " is cut short");
    step_padding(stream, element, end);
  }

  std::string path_;
  bool swap_;
};

// The header's version and byte-order fields (bytes 124-127).
struct MatHeader {
  uint16_t version = 0;
  bool swap = false;
  uint64_t size = 0;
};

MatHeader read_mat_header(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  const uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (!in || error) throw Error(path, "cannot open");
  std::array<uint8_t, 128> header{};
  if (size < header.size() || !in.read(reinterpret_cast<char*>(header.data()), header.size()))
    throw Error(
        path, "shorter than a MATLAB file's 128-byte header (" + std::to_string(size) + " bytes)");
  MatHeader result;
  result.size = size;
  if (header[126] == 'I' && header[127] == 'M') {
    result.version = static_cast<uint16_t>(header[124] | header[125] << 8);
  } else if (header[126] == 'M' && header[127] == 'I') {
    result.swap = true;
    result.version = static_cast<uint16_t>(header[124] << 8 | header[125]);
  } else {
    throw Error(path,
                "not a MATLAB v5 or v7.3 file (no IM/MI byte-order mark at byte 126; v4 files "
                "are not read: save them again with save -v7)");
  }
  return result;
}

//---- v7.3: the HDF5 groups libmatio and libhdf5 walk when the file is opened

// libhdf5 1.10 follows a group's B-tree and symbol-table node addresses without checking them
// against the file (a child address past the end made it copy from a null pointer under the
// fuzzer: tests/fuzz/regressions/mat/v73-group-btree-child-past-the-end.mat). So the root
// group's B-tree, its symbol-table nodes and its local heap are walked here first (HDF5 format
// specification, version 0/1 superblock, "Group B-tree nodes", "Symbol Table Node", "Local
// Heap"): every address within the end of file the superblock declares, every node whole,
// every count within the node's capacity. Superblocks of version 2 and 3 (new-style groups)
// are only checked for their end of file.
class MatHdf5Walker {
 public:
  MatHdf5Walker(std::string path, std::ifstream& in, uint64_t size)
      : path_(std::move(path)), in_(in), size_(size) {}

  void file() {
    constexpr uint64_t kSuperblock = 512;  // after MATLAB's 512-byte header block
    const std::vector<uint8_t> head = bytes(kSuperblock, 24, "the HDF5 superblock");
    static const uint8_t kSignature[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
    if (!std::equal(kSignature, kSignature + 8, head.begin()))
      fail(kSuperblock, "no HDF5 superblock where a v7.3 file has it");
    const uint8_t version = head[8];
    if (version > 3) fail(kSuperblock + 8, "superblock version " + std::to_string(version));
    if (version >= 2) {
      const std::vector<uint8_t> fields = bytes(kSuperblock + 12, 32, "the HDF5 superblock");
      if (head[9] != 8) fail(kSuperblock + 9, "offsets of " + std::to_string(head[9]) + " bytes");
      check_end(kSuperblock, number(fields, 0), number(fields, 16));
      return;
    }
    if (head[13] != 8 || head[14] != 8)
      fail(kSuperblock + 13, "offsets and lengths of other than 8 bytes");
    leaf_k_ = static_cast<uint64_t>(head[16] | head[17] << 8);
    internal_k_ = static_cast<uint64_t>(head[18] | head[19] << 8);
    if (leaf_k_ == 0 || internal_k_ == 0 || leaf_k_ > 4096 || internal_k_ > 4096)
      fail(kSuperblock + 16, "group node sizes K of " + std::to_string(leaf_k_) + " and " +
                                 std::to_string(internal_k_));
    const uint64_t fields_at = kSuperblock + (version == 0 ? 24 : 28);
    const std::vector<uint8_t> fields = bytes(fields_at, 32 + 40, "the HDF5 superblock");
    check_end(fields_at, number(fields, 0), number(fields, 16));
    // The root group's symbol-table entry: its object header, and the B-tree and heap it caches.
    const uint64_t root_header = address(number(fields, 40), fields_at + 40, 16);
    if (number(fields, 48) % (uint64_t{1} << 32) == 1)
      group(number(fields, 56), number(fields, 64), fields_at + 56);
    root_object_header(root_header);
  }

 private:
  [[noreturn]] void fail(uint64_t at, const std::string& what) const {
    throw Error(path_, "byte " + std::to_string(at) + ": " + what);
  }

  std::vector<uint8_t> bytes(uint64_t at, uint64_t count, const std::string& what) {
    if (at > size_ || count > size_ - at)
      fail(at, what + " (" + std::to_string(count) + " bytes) is past the end of the file");
    std::vector<uint8_t> read(count);
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    in_.read(reinterpret_cast<char*>(read.data()), static_cast<std::streamsize>(count));
    if (!in_) fail(at, "cannot read " + what);
    return read;
  }

  static uint64_t number(const std::vector<uint8_t>& bytes, size_t at, size_t size = 8) {
    uint64_t value = 0;
    for (size_t k = 0; k < size; ++k) value |= static_cast<uint64_t>(bytes[at + k]) << (8 * k);
    return value;
  }

  // The end of file as libmatio's files store it counts the 512-byte block before the
  // superblock; addresses are relative to the base (the superblock).
  void check_end(uint64_t at, uint64_t base, uint64_t end) {
    if (base > size_ || end > size_ || end < base)
      fail(at, "the superblock declares a base at " + std::to_string(base) +
                   " and an end of file at " + std::to_string(end) + ", the file has " +
                   std::to_string(size_) + " bytes");
    base_ = base;
    end_ = end;
  }

  // An address relative to the base, whose `count` bytes must lie within the declared end.
  uint64_t address(uint64_t relative, uint64_t named_at, uint64_t count) {
    if (relative > end_ - base_ || count > end_ - base_ - relative)
      fail(named_at, "an address " + std::to_string(relative) + " (" + std::to_string(count) +
                         " bytes) past the end of file");
    return base_ + relative;
  }

  void root_object_header(uint64_t at) {
    const std::vector<uint8_t> prefix = bytes(at, 16, "the root group's object header");
    if (prefix[0] != 1) return;  // version 2 ("OHDR"): new-style links, not walked here
    const uint64_t length = number(prefix, 8, 4);
    if (length > 65536) fail(at + 8, "an object header of " + std::to_string(length) + " bytes");
    address(at - base_ + 16, at, length);
    const std::vector<uint8_t> messages = bytes(at + 16, length, "the root group's messages");
    for (uint64_t offset = 0; offset + 8 <= length;) {
      const uint64_t type = number(messages, offset, 2);
      const uint64_t size = number(messages, offset + 2, 2);
      if (size > length - offset - 8) fail(at + 16 + offset, "a header message past its header");
      if (type == 0x11 && size >= 16)  // the symbol table message: B-tree and heap
        group(number(messages, offset + 8), number(messages, offset + 16), at + 16 + offset + 8);
      offset += 8 + size;
    }
  }

  void group(uint64_t btree, uint64_t heap, uint64_t named_at) {
    const uint64_t heap_at = address(heap, named_at + 8, 32);
    const std::vector<uint8_t> header = bytes(heap_at, 32, "a local heap");
    if (std::memcmp(header.data(), "HEAP", 4) != 0) fail(heap_at, "no local heap signature");
    heap_size_ = number(header, 8);
    address(number(header, 24), heap_at + 24, heap_size_);
    nodes_ = 0;
    btree_node(btree, named_at, UINT32_MAX);
  }

  void btree_node(uint64_t relative, uint64_t named_at, uint64_t level_above) {
    if (++nodes_ > 65536) fail(named_at, "more than 65536 group B-tree nodes (a cycle?)");
    const uint64_t node_bytes = 8 + 2 * 8 + (2 * internal_k_ + 1) * 8 + 2 * internal_k_ * 8;
    const uint64_t at = address(relative, named_at, node_bytes);
    const std::vector<uint8_t> node = bytes(at, node_bytes, "a group B-tree node");
    if (std::memcmp(node.data(), "TREE", 4) != 0 || node[4] != 0)
      fail(at, "not a group B-tree node");
    const uint64_t level = node[5];
    if (level >= level_above) fail(at + 5, "a B-tree level that does not descend");
    const uint64_t entries = number(node, 6, 2);
    if (entries > 2 * internal_k_)
      fail(at + 6,
           std::to_string(entries) + " entries in a node of " + std::to_string(2 * internal_k_));
    for (uint64_t entry = 0; entry < entries; ++entry) {
      const size_t child_at = 24 + 8 + static_cast<size_t>(entry) * 16;
      const uint64_t child = number(node, child_at);
      if (level > 0)
        btree_node(child, at + child_at, level);
      else
        symbol_node(child, at + child_at);
    }
  }

  void symbol_node(uint64_t relative, uint64_t named_at) {
    const uint64_t node_bytes = 8 + 2 * leaf_k_ * 40;
    const uint64_t at = address(relative, named_at, node_bytes);
    const std::vector<uint8_t> node = bytes(at, node_bytes, "a symbol table node");
    if (std::memcmp(node.data(), "SNOD", 4) != 0) fail(at, "not a symbol table node");
    const uint64_t symbols = number(node, 6, 2);
    if (symbols > 2 * leaf_k_)
      fail(at + 6,
           std::to_string(symbols) + " symbols in a node of " + std::to_string(2 * leaf_k_));
    for (uint64_t symbol = 0; symbol < symbols; ++symbol) {
      const size_t entry = 8 + static_cast<size_t>(symbol) * 40;
      if (number(node, entry) >= heap_size_) fail(at + entry, "a link name past its heap");
      const uint64_t header = address(number(node, entry + 8), at + entry + 8, 16);
      object_header(header);
    }
  }

  // A variable's (or a struct's group's) object header, version 1: every message within its
  // block, continuation blocks followed within the file, and the messages libhdf5 decodes
  // without checking their sizes against the message (attributes: MATLAB_class on every
  // variable; dataspaces; datatypes) checked here. A struct's group is walked in turn.
  void object_header(uint64_t at) {
    if (++headers_ > 65536) fail(at, "more than 65536 object headers (a cycle?)");
    const std::vector<uint8_t> prefix = bytes(at, 16, "an object header");
    if (std::memcmp(prefix.data(), "OHDR", 4) == 0)
      fail(at, "an object header of version 2, which is not read here");
    if (prefix[0] != 1) fail(at, "an object header of version " + std::to_string(prefix[0]));
    const uint64_t declared = number(prefix, 2, 2);
    const uint64_t length = number(prefix, 8, 4);
    std::vector<std::pair<uint64_t, uint64_t>> blocks = {{at + 16, length}};
    uint64_t messages = 0;
    std::optional<uint64_t> elements, element_bytes;
    for (size_t block = 0; block < blocks.size(); ++block) {
      if (block > 64) fail(at, "more than 64 continuation blocks");
      const auto [start, size] = blocks[block];
      if (size > (uint64_t{1} << 20))
        fail(start, "a header block of " + std::to_string(size) + " bytes");
      address(start - base_, start, size);
      const std::vector<uint8_t> data = bytes(start, size, "an object header block");
      for (uint64_t offset = 0; offset + 8 <= size;) {
        const uint64_t type = number(data, offset, 2);
        const uint64_t message = number(data, offset + 2, 2);
        const uint64_t body = start + offset + 8;
        if (message > size - offset - 8) fail(start + offset, "a header message past its block");
        if (++messages > declared + 64)
          fail(start + offset, "more messages than the header declares");
        const std::vector<uint8_t> content(
            data.begin() + static_cast<std::ptrdiff_t>(offset + 8),
            data.begin() + static_cast<std::ptrdiff_t>(offset + 8 + message));
        if (type == 0x0001) elements = dataspace(content, 0, message, body);
        if (type == 0x0003) element_bytes = datatype(content, 0, message, body);
        if (type == 0x000C) attribute(content, body);
        if (type == 0x0010) {
          if (message < 16)
            fail(body, "a continuation message of " + std::to_string(message) + " bytes");
          blocks.emplace_back(address(number(content, 0), body, number(content, 8)),
                              number(content, 8));
        }
        if (type == 0x0011) {
          if (message < 16)
            fail(body, "a symbol table message of " + std::to_string(message) + " bytes");
          if (++depth_ > 32) fail(body, "groups nested deeper than 32");
          const uint64_t saved_heap = heap_size_, saved_nodes = nodes_;
          group(number(content, 0), number(content, 8), body);
          heap_size_ = saved_heap;
          nodes_ = saved_nodes;
          --depth_;
        }
        offset += 8 + message;
      }
    }
    // A dataset's value: libhdf5 allocates elements x element size to read it (and to convert
    // it), whatever the file holds, so it must be what the file's bytes could hold even
    // deflated (1032:1).
    if (elements && element_bytes &&
        (*elements != 0 && *element_bytes > size_ / *elements * 1032 + 1032))
      fail(at, "a dataset of " + std::to_string(*elements) + " elements of " +
                   std::to_string(*element_bytes) + " bytes, more than the file's " +
                   std::to_string(size_) + " bytes could hold");
  }

  // Dataspace message (versions 1 and 2) at `from` of `content`, `limit` bytes long: its rank
  // and dimension sizes within those bytes. Returns the element count (1 for a scalar).
  uint64_t dataspace(const std::vector<uint8_t>& content, size_t from, uint64_t limit,
                     uint64_t at) {
    if (limit < 8) fail(at, "a dataspace of " + std::to_string(limit) + " bytes");
    const uint8_t version = content[from], rank = content[from + 1], flags = content[from + 2];
    if (version < 1 || version > 2) fail(at, "a dataspace of version " + std::to_string(version));
    if (rank > 32) fail(at + 1, "a dataspace of rank " + std::to_string(rank));
    const uint64_t header = version == 1 ? 8 : 4;
    const uint64_t needed = header + uint64_t{rank} * 8 * ((flags & 1) ? 2 : 1);
    if (needed > limit)
      fail(at, "a dataspace of rank " + std::to_string(rank) + " needs " + std::to_string(needed) +
                   " bytes, its message has " + std::to_string(limit));
    uint64_t elements = 1;
    for (uint64_t d = 0; d < rank; ++d) {
      const uint64_t extent = number(content, from + header + d * 8);
      if (extent != 0 && elements > (uint64_t{1} << 40) / extent)
        fail(at, "a dataspace of more than 2^40 elements");
      elements *= extent;
    }
    return elements;
  }

  // Datatype message: at least its 8-byte header within `limit`; returns the element size.
  uint64_t datatype(const std::vector<uint8_t>& content, size_t from, uint64_t limit, uint64_t at) {
    if (limit < 8) fail(at, "a datatype of " + std::to_string(limit) + " bytes");
    const uint64_t size = number(content, from + 4, 4);
    if (size == 0) fail(at + 4, "a datatype of 0 bytes");
    return size;
  }

  // Attribute message, versions 1 to 3: name, datatype and dataspace within the message, and
  // the value (elements x element size) within what is left.
  void attribute(const std::vector<uint8_t>& content, uint64_t at) {
    const uint64_t limit = content.size();
    if (limit < 8) fail(at, "an attribute of " + std::to_string(limit) + " bytes");
    const uint8_t version = content[0];
    if (version < 1 || version > 3) fail(at, "an attribute of version " + std::to_string(version));
    const uint64_t name = number(content, 2, 2), type = number(content, 4, 2),
                   space = number(content, 6, 2);
    auto padded = [version](uint64_t n) { return version == 1 ? (n + 7) / 8 * 8 : n; };
    const uint64_t header = version == 3 ? 9 : 8;
    const uint64_t type_at = header + padded(name), space_at = type_at + padded(type),
                   value_at = space_at + padded(space);
    if (name == 0 || value_at > limit)
      fail(at, "an attribute whose name (" + std::to_string(name) + "), datatype (" +
                   std::to_string(type) + ") and dataspace (" + std::to_string(space) +
                   " bytes) do not fit its " + std::to_string(limit) + " bytes");
    const uint64_t element = datatype(content, type_at, type, at + type_at);
    const uint64_t elements = dataspace(content, space_at, space, at + space_at);
    if (elements != 0 && element > (limit - value_at) / elements)
      fail(at, "an attribute value of " + std::to_string(elements) + " x " +
                   std::to_string(element) + " bytes past its message");
  }

  std::string path_;
  std::ifstream& in_;
  uint64_t size_;
  uint64_t base_ = 0, end_ = 0;
  uint64_t leaf_k_ = 0, internal_k_ = 0, heap_size_ = 0, nodes_ = 0, headers_ = 0, depth_ = 0;
};

}  // namespace

MatFileVersion mat_file_version(const std::string& path) {
  const MatHeader header = read_mat_header(path);
  if (header.version == 0x0100) return MatFileVersion::v5;
  if (header.version == 0x0200) return MatFileVersion::v73;
  throw Error(path, "byte 124: MAT-file version " + std::to_string(header.version) +
                        " (v5 is 256, v7.3 is 512)");
}

void check_mat_v73_structure(const std::string& path) {
  const MatHeader header = read_mat_header(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  MatHdf5Walker(path, in, header.size).file();
}

void check_mat_v5_structure(const std::string& path) {
  const MatHeader header = read_mat_header(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  MatWalker(path, header.swap).file(in, header.size);
}

}  // namespace tactile

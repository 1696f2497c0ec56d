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
#include "tactile/formats/array_files.h"

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
  kMxOpaque = 17,
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
    if (array_class == kMxOpaque) return opaque(stream, end, given_name, depth);
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
    // libmatio reads objects and function handles by rules of its own (a function handle
    // whose bytes lie made it ask for 1.6 GB: the fuzzer's
    // regressions/mat/function-handle-makes-libmatio-allocate-1.6-gb.mat), and they are no
    // recording: the file is refused rather than handed over. (Opaque objects, class 17, are
    // walked above: libmatio only steps over them.)
    if (array_class == 3 || array_class == 16)
      refuse(stream, flags_tag.at, name,
             "array class " + std::to_string(array_class) +
                 (array_class == 3 ? " (an object)" : " (a function handle)") + " is not read");
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
    // Sparse arrays are stepped over whole: mat_files.cpp refuses them by name when they are
    // asked for.
    if (!stream.skip(end - stream.offset()))
      refuse(stream, stream.offset(), name, "ends before its declared end");
  }

  // The top-level elements, from byte 128 to the end of the file.
  std::vector<MatOpaqueVariable> file(std::ifstream& in, uint64_t size) {
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
    return opaque_;
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

  // An opaque object, as MATLAB 2017b+ writes a `string` (and `table`, `datetime`, ...): after
  // the array flags come no dimensions but its name, the type system's name ("MCOS") and the
  // class name ("string"), each miINT8 text, then the object's metadata as one miMATRIX (for
  // MCOS a uint32 array referring into the subsystem data MATLAB writes as a last, nameless
  // variable). It holds no array to read: it is recorded, to be listed and refused by name.
  void opaque(MatByteStream& stream, uint64_t end, const std::string& given_name, int depth) {
    const std::string own_name = text(stream, end, given_name, "the array name");
    const std::string name = given_name.empty() ? own_name : given_name;
    MatOpaqueVariable object;
    object.name = name;
    object.type_system = printable(text(stream, end, name, "the type system name"));
    object.class_name = printable(text(stream, end, name, "the class name"));
    object.top_level = given_name.empty();
    if (object.class_name.empty())
      refuse(stream, stream.offset(), name, "an opaque object of no class name");
    child(stream, end, name, depth);
    opaque_.push_back(std::move(object));
    if (!stream.skip(end - stream.offset()))
      refuse(stream, stream.offset(), name, "ends before its declared end");
  }

  // An miINT8 (or miUINT8) text element of at most kMatMaxNameBytes, trailing NULs dropped.
  std::string text(MatByteStream& stream, uint64_t end, const std::string& name,
                   const std::string& what) {
    const MatTag text_tag = tag(stream, end, name);
    if (text_tag.type != kMiInt8 && text_tag.type != kMiUint8)
      refuse(stream, text_tag.at, name, what + " is not miINT8 text");
    if (text_tag.bytes > kMatMaxNameBytes)
      refuse(stream, text_tag.at, name,
             what + " declares " + std::to_string(text_tag.bytes) + " bytes");
    const std::vector<uint8_t> bytes = payload(stream, text_tag, end, name);
    std::string result(bytes.begin(), bytes.end());
    while (!result.empty() && result.back() == '\0') result.pop_back();
    return result;
  }

  // Names said in refusals: printable ASCII, anything else as '?'.
  static std::string printable(std::string text) {
    for (char& character : text)
      if (static_cast<uint8_t>(character) < 0x20 || static_cast<uint8_t>(character) >= 0x7f)
        character = '?';
    return text;
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
  std::vector<MatOpaqueVariable> opaque_;
};

}  // namespace

MatHeader read_mat_header(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  const uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (!in || error) throw Error(path, "cannot open");
  std::array<uint8_t, 128> header{};
  if (size < header.size() || !in.read(reinterpret_cast<char*>(header.data()), header.size()))
    throw Error(path, "shorter than a v5 or v7.3 file's 128-byte header (" + std::to_string(size) +
                          " bytes), and its first bytes are no MATLAB 4 variable header");
  MatHeader result;
  result.size = size;
  if (header[126] == 'I' && header[127] == 'M') {
    result.version = static_cast<uint16_t>(header[124] | header[125] << 8);
  } else if (header[126] == 'M' && header[127] == 'I') {
    result.swap = true;
    result.version = static_cast<uint16_t>(header[124] << 8 | header[125]);
  } else {
    throw Error(path,
                "not a MATLAB v5 or v7.3 file (no IM/MI byte-order mark at byte 126) nor a "
                "MATLAB 4 file (its first bytes are no Level 4 variable header)");
  }
  return result;
}

MatFileVersion mat_file_version(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw Error(path, "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  std::array<uint8_t, 128> first{};
  in.read(reinterpret_cast<char*>(first.data()), first.size());
  const auto read = static_cast<uint64_t>(in.gcount());
  // A v5 or v7.3 header's byte-order mark first: its text ("MATLAB 5.0 MAT-file") is no
  // Level 4 header in either byte order.
  const bool marked = read == first.size() && ((first[126] == 'I' && first[127] == 'M') ||
                                               (first[126] == 'M' && first[127] == 'I'));
  if (!marked && looks_like_mat_v4(first.data(), read)) return MatFileVersion::v4;
  const MatHeader header = read_mat_header(path);
  if (header.version == 0x0100) return MatFileVersion::v5;
  if (header.version == 0x0200) return MatFileVersion::v73;
  throw Error(path, "byte 124: MAT-file version " + std::to_string(header.version) +
                        " (v5 is 256, v7.3 is 512)");
}

std::vector<MatOpaqueVariable> check_mat_v5_structure(const std::string& path) {
  const MatHeader header = read_mat_header(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open");
  return MatWalker(path, header.swap).file(in, header.size);
}

}  // namespace tactile

// The structure of a MATLAB 4 (Level 4) file walked before libmatio reads it (mat_structure.h).
// MATLAB 4.x wrote these, and later MATLABs still do with `save -v4`. There is no file header:
// each variable is a 20-byte header of five int32 (type MOPT, rows, columns, imaginary flag,
// name length), its name (name length bytes, the last a NUL), then the real part (rows x
// columns values of the P type, column-major) and, when imaginary, as many values more.
// MOPT is the decimal number M*1000 + O*100 + P*10 + T: M the number format (0 IEEE little-
// endian, 1 IEEE big-endian, 2-4 VAX and Cray), O always 0, P the value type (0 double, 1
// single, 2 int32, 3 int16, 4 uint16, 5 uint8), T the matrix type (0 numeric, 1 text, 2 sparse).
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "mat_structure.h"
#include "tactile/error.h"
#include "tactile/formats/array_files.h"

namespace tactile {

namespace {

constexpr int32_t kMatV4MostNameBytes = 65536;

// One variable header as read (in the byte order its M digit declares).
struct MatV4Header {
  int32_t type = 0, rows = 0, columns = 0, imaginary = 0, name_bytes = 0;
  bool big_endian = false;
};

int32_t int32_at(const uint8_t* bytes, bool big_endian) {
  uint32_t value;
  std::memcpy(&value, bytes, 4);
  if (big_endian) value = __builtin_bswap32(value);
  return static_cast<int32_t>(value);
}

// The header in the byte order whose M digit agrees with it (0 little-endian, 1 big-endian);
// false when neither order gives a Level 4 header (VAX and Cray formats included, for the
// refusal to name them).
bool parse_v4_header(const uint8_t* bytes, MatV4Header& header) {
  for (const bool big_endian : {false, true}) {
    const int32_t type = int32_at(bytes, big_endian);
    if (type < 0 || type > 4052) continue;
    const int machine = type / 1000, zero = type / 100 % 10, precision = type / 10 % 10,
              matrix = type % 10;
    if (zero != 0 || precision > 5 || matrix > 2) continue;
    if (machine <= 1 && machine != (big_endian ? 1 : 0)) continue;
    header.type = type;
    header.rows = int32_at(bytes + 4, big_endian);
    header.columns = int32_at(bytes + 8, big_endian);
    header.imaginary = int32_at(bytes + 12, big_endian);
    header.name_bytes = int32_at(bytes + 16, big_endian);
    header.big_endian = big_endian;
    if (header.rows < 0 || header.columns < 0 || (header.imaginary != 0 && header.imaginary != 1) ||
        header.name_bytes < 1 || header.name_bytes > kMatV4MostNameBytes)
      continue;
    return true;
  }
  return false;
}

uint64_t v4_value_bytes(int precision) {
  static constexpr std::array<uint64_t, 6> kBytes = {8, 4, 4, 2, 2, 1};
  return kBytes[static_cast<size_t>(precision)];
}

}  // namespace

bool looks_like_mat_v4(const uint8_t* bytes, uint64_t size) {
  MatV4Header header;
  return size >= 20 && parse_v4_header(bytes, header);
}

void check_mat_v4_structure(const std::string& path) {
  std::error_code error;
  const uint64_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (!in || error) throw Error(path, "cannot open");
  uint64_t at = 0;
  while (at < size) {
    const std::string place = "MATLAB 4 file, byte " + std::to_string(at);
    std::array<uint8_t, 20> bytes{};
    in.seekg(static_cast<std::streamoff>(at));
    if (size - at < bytes.size() || !in.read(reinterpret_cast<char*>(bytes.data()), 20))
      throw Error(path, place + ": a variable header (20 bytes) is cut short");
    MatV4Header header;
    if (!parse_v4_header(bytes.data(), header))
      throw Error(path, place + ": not a MATLAB 4 variable header");
    if (size - at - 20 < static_cast<uint64_t>(header.name_bytes))
      throw Error(path, place + ": the name declares " + std::to_string(header.name_bytes) +
                            " bytes, the file has " + std::to_string(size - at - 20) + " left");
    std::string name(static_cast<size_t>(header.name_bytes), '\0');
    in.read(name.data(), header.name_bytes);
    if (!in || name.back() != '\0')
      throw Error(path, place + ": the variable's name does not end in a NUL");
    name.resize(std::strlen(name.c_str()));
    for (char& character : name)
      if (static_cast<uint8_t>(character) < 0x20 || static_cast<uint8_t>(character) >= 0x7f)
        character = '?';
    const std::string where = place + ", variable " + name;
    const int machine = header.type / 1000, precision = header.type / 10 % 10;
    if (machine > 1)
      throw Error(path, where + ": number format M=" + std::to_string(machine) +
                            " (VAX or Cray) is not read, only IEEE little- and big-endian");
    if (header.type % 10 == 2)
      throw Error(path, where + ": a MATLAB 4 sparse matrix is not read (save it full)");
    const auto rows = static_cast<uint64_t>(header.rows);
    const auto columns = static_cast<uint64_t>(header.columns);
    if (columns != 0 && rows > static_cast<uint64_t>(kMaxImportedElements) / columns)
      throw Error(path, where + ": " + std::to_string(rows) + " x " + std::to_string(columns) +
                            " declares more than " + std::to_string(kMaxImportedElements) +
                            " elements");
    const uint64_t data = rows * columns * v4_value_bytes(precision) * (header.imaginary ? 2 : 1);
    const uint64_t left = size - at - 20 - static_cast<uint64_t>(header.name_bytes);
    if (data > left)
      throw Error(path, where + ": " + std::to_string(rows) + " x " + std::to_string(columns) +
                            " values need " + std::to_string(data) + " bytes, the file has " +
                            std::to_string(left) + " left");
    at += 20 + static_cast<uint64_t>(header.name_bytes) + data;
  }
}

}  // namespace tactile

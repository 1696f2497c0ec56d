#include "row_checksum.h"

#include <zlib.h>

#include <cstring>

namespace tactile::row_checksum {

namespace {

constexpr size_t kDigits = 8;

uint32_t crc_bytes(uint32_t crc, const void* data, size_t size) {
  return static_cast<uint32_t>(
      crc32(crc, static_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

template <typename T>
uint32_t crc_value(uint32_t crc, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  return crc_bytes(crc, bytes, sizeof(T));
}

uint32_t field_crc(const std::string& table, int64_t row, const Field& field) {
  uint32_t crc = crc_bytes(0, table.data(), table.size() + 1);  // with its NUL: a separator
  crc = crc_value(crc, row);
  crc = crc_bytes(crc, field.name, std::strlen(field.name) + 1);
  const auto tag = static_cast<unsigned char>(field.value.index());
  crc = crc_bytes(crc, &tag, 1);
  if (const auto* integer = std::get_if<int64_t>(&field.value)) return crc_value(crc, *integer);
  if (const auto* real = std::get_if<double>(&field.value)) return crc_value(crc, *real);
  if (const auto* text = std::get_if<std::string>(&field.value))
    return crc_bytes(crc, text->data(), text->size());
  return crc;
}

std::string hex(uint32_t value) {
  static const char* const kDigitChars = "0123456789abcdef";
  std::string text(kDigits, '0');
  for (size_t index = 0; index < kDigits; ++index)
    text[kDigits - 1 - index] = kDigitChars[(value >> (4 * index)) & 0xf];
  return text;
}

}  // namespace

std::string compute(const std::string& table, int64_t row, const std::vector<Field>& fields) {
  std::string checksum;
  checksum.reserve(fields.size() * kDigits);
  for (const Field& field : fields) checksum += hex(field_crc(table, row, field));
  return checksum;
}

std::vector<std::string> mismatches(const std::string& table, int64_t row,
                                    const std::vector<Field>& fields, const std::string& stored) {
  std::vector<std::string> names;
  const bool malformed = stored.size() != fields.size() * kDigits;
  for (size_t index = 0; index < fields.size(); ++index)
    if (malformed ||
        stored.compare(index * kDigits, kDigits, hex(field_crc(table, row, fields[index]))) != 0)
      names.emplace_back(fields[index].name);
  return names;
}

uint64_t row_hash(int64_t row, const std::string& checksum) {
  // FNV-1a, 64 bits.
  uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](unsigned char byte) {
    hash ^= byte;
    hash *= 1099511628211ull;
  };
  for (size_t index = 0; index < sizeof(row); ++index)
    mix(static_cast<unsigned char>(static_cast<uint64_t>(row) >> (8 * index)));
  for (char c : checksum) mix(static_cast<unsigned char>(c));
  return hash;
}

}  // namespace tactile::row_checksum

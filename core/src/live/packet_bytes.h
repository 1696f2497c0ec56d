#pragma once
// Little-endian reads and writes for the packet codec. Callers check bounds first; these
// helpers only assemble bytes.

#include <bit>
#include <cstdint>
#include <vector>

namespace tactile::packet_detail {

inline void put_u8(std::vector<uint8_t>& out, uint8_t value) { out.push_back(value); }

inline void put_u16(std::vector<uint8_t>& out, uint16_t value) {
  out.push_back(static_cast<uint8_t>(value));
  out.push_back(static_cast<uint8_t>(value >> 8));
}

inline void put_u32(std::vector<uint8_t>& out, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<uint8_t>(value >> shift));
}

inline void put_f64(std::vector<uint8_t>& out, double value) {
  const uint64_t bits = std::bit_cast<uint64_t>(value);
  for (int shift = 0; shift < 64; shift += 8) out.push_back(static_cast<uint8_t>(bits >> shift));
}

inline void store_u32(uint8_t* at, uint32_t value) {
  for (int index = 0; index < 4; ++index) at[index] = static_cast<uint8_t>(value >> (8 * index));
}

inline uint16_t get_u16(const uint8_t* at) {
  return static_cast<uint16_t>(at[0] | (static_cast<uint16_t>(at[1]) << 8));
}

inline int16_t get_i16(const uint8_t* at) { return static_cast<int16_t>(get_u16(at)); }

inline uint32_t get_u32(const uint8_t* at) {
  uint32_t value = 0;
  for (int index = 3; index >= 0; --index) value = (value << 8) | at[index];
  return value;
}

inline double get_f64(const uint8_t* at) {
  uint64_t bits = 0;
  for (int index = 7; index >= 0; --index) bits = (bits << 8) | at[index];
  return std::bit_cast<double>(bits);
}

}  // namespace tactile::packet_detail

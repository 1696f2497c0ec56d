#pragma once
// The few pieces of a ZIP archive a .npz needs (array_files.cpp): its central directory
// (ZIP64 sizes and offsets included) and an entry's bytes, stored or deflated (zlib), each
// checked against the file's size before anything is allocated; and the little-endian reads
// both NumPy's header and ZIP's records are made of.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile::formats {

inline uint32_t little32(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
         static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}
inline uint16_t little16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | p[1] << 8); }
inline uint64_t little64(const uint8_t* p) {
  return little32(p) | static_cast<uint64_t>(little32(p + 4)) << 32;
}

struct ZipEntry {
  std::string name;
  uint16_t method = 0;  // 0 stored, 8 deflate
  uint64_t compressed = 0, size = 0, local = 0;
};

// The archive's entries from its central directory; `where` names the file in errors.
std::vector<ZipEntry> zip_entries(const std::vector<uint8_t>& bytes, const std::string& where);
// One entry's bytes, inflated when deflated; refused when damaged, truncated, or declaring
// more than deflate can give.
std::vector<uint8_t> zip_content(const std::vector<uint8_t>& bytes, const ZipEntry& entry,
                                 const std::string& where);

}  // namespace tactile::formats

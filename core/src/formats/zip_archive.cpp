#include "zip_archive.h"

#include <zlib.h>

#include <algorithm>

#include "tactile/error.h"
#include "tactile/formats/array_files.h"

namespace tactile::formats {

std::vector<ZipEntry> zip_entries(const std::vector<uint8_t>& bytes, const std::string& where) {
  // The end of central directory record: 22 bytes, then a comment of up to 65535.
  if (bytes.size() < 22) throw Error(where, "too short for a .npz (zip) file");
  size_t end = std::string::npos;
  for (size_t at = bytes.size() - 22 + 1; at-- > 0 && bytes.size() - at <= 22 + 65535;)
    if (little32(bytes.data() + at) == 0x06054b50) {
      end = at;
      break;
    }
  if (end == std::string::npos)
    throw Error(where, "no zip directory at the end (not a .npz, or truncated)");
  const uint16_t count = little16(bytes.data() + end + 10);
  const uint64_t directory = little32(bytes.data() + end + 16);
  std::vector<ZipEntry> entries;
  uint64_t at = directory;
  for (uint16_t k = 0; k < count; ++k) {
    const std::string place = where + " zip entry " + std::to_string(k);
    if (at + 46 > bytes.size() || little32(bytes.data() + at) != 0x02014b50)
      throw Error(place, "directory record missing or damaged at byte " + std::to_string(at));
    const uint8_t* record = bytes.data() + at;
    ZipEntry entry;
    entry.method = little16(record + 10);
    entry.compressed = little32(record + 20);
    entry.size = little32(record + 24);
    const uint16_t name_length = little16(record + 28), extra = little16(record + 30),
                   comment = little16(record + 32);
    entry.local = little32(record + 42);
    if (at + 46 + name_length + extra + comment > bytes.size())
      throw Error(place, "directory record runs past the end");
    entry.name.assign(reinterpret_cast<const char*>(record + 46), name_length);
    // ZIP64: sizes and offset in the extra field (id 1), in this order, for those marked.
    for (size_t x = 0; x + 4 <= extra;) {
      const uint8_t* field = record + 46 + name_length + x;
      const uint16_t id = little16(field), length = little16(field + 2);
      if (x + 4 + length > extra) throw Error(place, "extra field runs past its record");
      if (id == 1) {
        size_t y = 4;
        for (uint64_t* value : {&entry.size, &entry.compressed, &entry.local})
          if (*value == 0xFFFFFFFFu) {
            if (y + 8 > 4u + length) throw Error(place, "ZIP64 field too short");
            *value = little64(field + y);
            y += 8;
          }
      }
      x += 4 + length;
    }
    entries.push_back(std::move(entry));
    at += 46 + name_length + extra + comment;
  }
  return entries;
}

std::vector<uint8_t> zip_content(const std::vector<uint8_t>& bytes, const ZipEntry& entry,
                                 const std::string& where) {
  if (entry.local + 30 > bytes.size() || little32(bytes.data() + entry.local) != 0x04034b50)
    throw Error(where, "local header missing at byte " + std::to_string(entry.local));
  const uint64_t start = entry.local + 30 + little16(bytes.data() + entry.local + 26) +
                         little16(bytes.data() + entry.local + 28);
  if (start > bytes.size() || entry.compressed > bytes.size() - start)
    throw Error(where, "its " + std::to_string(entry.compressed) +
                           " bytes run past the end of the file (truncated?)");
  const uint8_t* data = bytes.data() + start;
  if (entry.method == 0) {
    if (entry.size != entry.compressed) throw Error(where, "stored entry whose sizes differ");
    return std::vector<uint8_t>(data, data + entry.compressed);
  }
  if (entry.method != 8)
    throw Error(where, "compression method " + std::to_string(entry.method) +
                           " (stored and deflate are read)");
  // Deflate expands at most 1032 times: a larger declared size is a lie, refused before allocating.
  if (entry.size > entry.compressed * 1032 + 1024 ||
      entry.size > static_cast<uint64_t>(kMaxImportedElements) * 8)
    throw Error(where, "declares " + std::to_string(entry.size) + " bytes from " +
                           std::to_string(entry.compressed) +
                           " compressed, more than deflate can give");
  std::vector<uint8_t> out(entry.size);
  z_stream stream{};
  if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) throw Error(where, "cannot start inflating");
  stream.next_in = const_cast<uint8_t*>(data);
  stream.avail_in = static_cast<uInt>(std::min<uint64_t>(entry.compressed, UINT32_MAX));
  stream.next_out = out.data();
  stream.avail_out = static_cast<uInt>(std::min<uint64_t>(entry.size, UINT32_MAX));
  const int status = inflate(&stream, Z_FINISH);
  const uint64_t produced = stream.total_out;
  inflateEnd(&stream);
  if (status != Z_STREAM_END || produced != entry.size)
    throw Error(where, "deflated data damaged or truncated (inflated " + std::to_string(produced) +
                           " of " + std::to_string(entry.size) + " bytes)");
  return out;
}

}  // namespace tactile::formats

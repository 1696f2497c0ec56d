// The live packet decoder and the serial framer in front of it. The first byte picks the
// skin's layout and whether the harness mends the payload CRC (so that mutations reach the
// payload checks instead of stopping at the checksum); the rest is one datagram, and then the
// same bytes fed to the framer in pieces.
#include <algorithm>
#include <vector>

#include "fuzz_support.h"
#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_input.h"
#include "tactile/live/packets.h"

using namespace tactile;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const std::vector<SkinLayout> layouts = [] {
    std::vector<SkinLayout> all;
    for (const std::string& skin : packet_skin_ids()) all.push_back(load_layout(skin));
    return all;
  }();
  const uint8_t mode = data[0];
  std::vector<uint8_t> datagram(data + 1, data + size);
  if ((mode & 0x80) && datagram.size() >= static_cast<size_t>(kPacketHeaderSize)) {
    const uint32_t crc = crc32(std::span<const uint8_t>(datagram).subspan(kPacketHeaderSize));
    for (int k = 0; k < 4; ++k) datagram[28 + k] = static_cast<uint8_t>(crc >> (8 * k));
  }
  const SkinLayout& layout = layouts[(mode & 0x7f) % layouts.size()];
  try {
    decode_packet_header(datagram);
  } catch (const Error&) {
  }
  try {
    decode_packet(datagram, layout);
  } catch (const Error&) {
  }
  // A serial line delivers the same bytes in arbitrary pieces.
  PacketFramer framer;
  std::vector<uint8_t> out;
  const size_t piece = 1 + (mode & 0x0f);
  for (size_t at = 0; at < datagram.size(); at += piece) {
    framer.feed(
        std::span<const uint8_t>(datagram).subspan(at, std::min(piece, datagram.size() - at)));
    while (framer.next(out)) {
      try {
        decode_packet(out, layout);
      } catch (const Error&) {
      }
    }
  }
  return 0;
}

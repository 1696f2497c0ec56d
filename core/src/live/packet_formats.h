#pragma once
// How a skin's packet format (its record's) maps wire values onto a layout, and the NAO cell
// record's per-modality scales (docs/PACKETS.md).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/skins/skin.h"

namespace tactile::packet_detail {

// The format of a skin's packets is its record's (skins/skin.h): PacketFormat, its
// CountScale and WireWord.
using SkinFormat = PacketFormat;

// NAO cell record: cell id u8, reserved u8 (0), ax ay az int16, f1 f2 f3 uint16, prox uint16,
// temp int16.
inline constexpr int kNaoCells = 32;
inline constexpr int kNaoSlots = 8;
inline constexpr int kNaoRecordBytes = 2 + 2 * kNaoSlots;
inline constexpr const char* kNaoModalities[kNaoSlots] = {"ax", "ay", "az",   "f1",
                                                          "f2", "f3", "prox", "temp"};
const CountScale& nao_scale(int slot);

const SkinFormat* find_format(const std::string& skin);  // nullptr when unknown
const SkinFormat* find_format(uint8_t code);             // nullptr when unknown
// Throws tactile::Error at `where` naming the skin when it has no format.
const SkinFormat& require_format(const std::string& skin, const std::string& where);
int payload_bytes_per_sample(const SkinFormat& format);
// Payload bytes for `samples` samples; 64-bit so that no header value can overflow it.
uint64_t payload_bytes(const SkinFormat& format, uint64_t samples);

// Where each wire value goes in a layout.
struct WirePlan {
  const SkinFormat* format = nullptr;
  std::vector<int> device_channels;       // layout channel indices sent by the device, layout order
  std::vector<int> wire_channels;         // layout channel index of each wire position
  std::vector<int> column_of_wire;        // column in device_channels of each wire position
  std::vector<int64_t> cell_ids;          // nao: taxel id of each cell record, in wire order
  std::vector<const CountScale*> scales;  // per wire position
};

// Throws tactile::Error naming the layout when it does not fit the skin's format.
WirePlan make_wire_plan(const SkinLayout& layout);

}  // namespace tactile::packet_detail

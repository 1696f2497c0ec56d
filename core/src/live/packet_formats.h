#pragma once
// Per-skin packet formats: how each device packs its samples and how its ADC counts map to
// the layout's units. The one place where counts and physical units meet (docs/PACKETS.md).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"

namespace tactile::packet_detail {

// Physical value = offset + count * step, for counts in [min_count, max_count]. Encoding
// rounds to the nearest count and saturates at the limits, as the device's ADC does.
struct CountScale {
  double offset = 0.0;
  double step = 1.0;
  int32_t min_count = 0;
  int32_t max_count = 0;

  // `value` must be finite; sets `saturated` when it was clamped.
  int32_t to_count(double value, bool& saturated) const;
  float to_value(int32_t count) const;
};

// How one sample's values sit in the payload.
enum class WireWord {
  kInt16,     // one little-endian int16 per value
  kUint16,    // one little-endian uint16 per value
  kPacked12,  // two 12-bit values in 3 bytes
  kNaoCells,  // one 18-byte record per cell (see kNaoRecordBytes)
};

struct SkinFormat {
  const char* skin;
  uint8_t code;
  double rate_hz;
  int samples_per_datagram;
  int wire_channels;
  WireWord word;
  CountScale scale;  // for every value, except nao (per modality, nao_scale)
};

// NAO cell record: cell id u8, reserved u8 (0), ax ay az int16, f1 f2 f3 uint16, prox uint16,
// temp int16.
inline constexpr int kNaoCells = 32;
inline constexpr int kNaoSlots = 8;
inline constexpr int kNaoRecordBytes = 2 + 2 * kNaoSlots;
inline constexpr const char* kNaoModalities[kNaoSlots] = {"ax", "ay", "az",   "f1",
                                                          "f2", "f3", "prox", "temp"};
const CountScale& nao_scale(int slot);

const std::vector<SkinFormat>& skin_formats();
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

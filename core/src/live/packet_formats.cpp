#include "packet_formats.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "tactile/error.h"
#include "tactile/live/packets.h"
#include "tactile/text.h"

namespace tactile::packet_detail {

//---- NAO cells (the other skins' ranges are in their records) -------------------------------

namespace {

// NAO cellular skin, paper 000 Table 2. Accelerometer: +-2 g on a signed 10-bit ADC, so
// 512 counts per 2 g. Force: 0-3 N on 12 bits. Proximity: 1-200 mm on the full 16 bits.
// Temperature: 0.01 degC per count over the sensor's -40..150 degC (finer than its 14 bits).
const CountScale kNaoScales[kNaoSlots] = {
    {0.0, 2.0 / 512.0, -512, 511},    {0.0, 2.0 / 512.0, -512, 511}, {0.0, 2.0 / 512.0, -512, 511},
    {0.0, 3.0 / 4095.0, 0, 4095},     {0.0, 3.0 / 4095.0, 0, 4095},  {0.0, 3.0 / 4095.0, 0, 4095},
    {1.0, 199.0 / 65535.0, 0, 65535}, {0.0, 0.01, -4000, 15000},
};

}  // namespace

const CountScale& nao_scale(int slot) { return kNaoScales[slot]; }

const SkinFormat* find_format(const std::string& skin) {
  const SkinRecord* record = find_skin(skin);
  return record && record->packet ? &*record->packet : nullptr;
}

const SkinFormat* find_format(uint8_t code) {
  const SkinRecord* record = find_skin_by_packet_code(code);
  return record ? &*record->packet : nullptr;
}

int payload_bytes_per_sample(const SkinFormat& format) {
  switch (format.word) {
    case WireWord::kInt16:
    case WireWord::kUint16:
      return 2 * format.wire_channels;
    case WireWord::kPacked12:
      return (3 * format.wire_channels + 1) / 2;
    case WireWord::kNaoCells:
      return kNaoCells * kNaoRecordBytes;
  }
  return 0;
}

uint64_t payload_bytes(const SkinFormat& format, uint64_t samples) {
  return samples * static_cast<uint64_t>(payload_bytes_per_sample(format));
}

//---- Layout -> wire positions ----------------------------------------------------------

namespace {

std::vector<int> owned_channels(const SkinLayout& layout) {
  std::vector<int> channels;
  for (const Taxel& taxel : layout.taxels)
    for (int channel : taxel.channels)
      if (channel >= 0) channels.push_back(channel);
  std::sort(channels.begin(), channels.end());
  channels.erase(std::unique(channels.begin(), channels.end()), channels.end());
  return channels;
}

void plan_nao_cells(const SkinLayout& layout, WirePlan& plan) {
  const std::string where = "layout " + layout.id;
  int slot_modality[kNaoSlots];
  for (int slot = 0; slot < kNaoSlots; ++slot) {
    slot_modality[slot] = layout.modality_index(kNaoModalities[slot]);
    if (slot_modality[slot] < 0)
      throw Error(where, std::string("no modality \"") + kNaoModalities[slot] +
                             "\" for the nao cell packet");
  }
  std::vector<const Taxel*> cells;
  for (const Taxel& taxel : layout.taxels) cells.push_back(&taxel);
  std::sort(cells.begin(), cells.end(),
            [](const Taxel* a, const Taxel* b) { return a->id < b->id; });
  if (static_cast<int>(cells.size()) != kNaoCells)
    throw Error(where, "has " + std::to_string(cells.size()) + " cells, the nao packet carries " +
                           std::to_string(kNaoCells));
  for (const Taxel* cell : cells) {
    if (cell->id < 1 || cell->id > 255)
      throw Error(where, "cell id " + std::to_string(cell->id) + " does not fit the u8 cell id");
    plan.cell_ids.push_back(cell->id);
    for (int slot = 0; slot < kNaoSlots; ++slot) {
      const size_t modality = static_cast<size_t>(slot_modality[slot]);
      const int channel = modality < cell->channels.size() ? cell->channels[modality] : -1;
      if (channel < 0)
        throw Error(where, "cell " + std::to_string(cell->id) + " lacks its " +
                               kNaoModalities[slot] + " channel");
      plan.wire_channels.push_back(channel);
      plan.scales.push_back(&kNaoScales[slot]);
    }
  }
}

}  // namespace

const SkinFormat& require_format(const std::string& skin, const std::string& where) {
  const SkinFormat* format = find_format(skin);
  if (!format)
    throw Error(where, "no packet format for skin \"" + skin + "\" (have " +
                           joined(packet_skin_ids()) + ")");
  return *format;
}

WirePlan make_wire_plan(const SkinLayout& layout) {
  WirePlan plan;
  plan.format = &require_format(layout.id, "layout " + layout.id);
  plan.device_channels = owned_channels(layout);
  if (static_cast<int>(plan.device_channels.size()) != plan.format->wire_channels)
    throw Error("layout " + layout.id, "has " + std::to_string(plan.device_channels.size()) +
                                           " device channels, the packet format carries " +
                                           std::to_string(plan.format->wire_channels));
  if (plan.format->word == WireWord::kNaoCells) {
    plan_nao_cells(layout, plan);
  } else {
    plan.wire_channels = plan.device_channels;
    plan.scales.assign(plan.wire_channels.size(), &plan.format->scale);
  }
  std::map<int, int> column_of_channel;
  for (size_t column = 0; column < plan.device_channels.size(); ++column)
    column_of_channel[plan.device_channels[column]] = static_cast<int>(column);
  for (int channel : plan.wire_channels) plan.column_of_wire.push_back(column_of_channel[channel]);
  return plan;
}

}  // namespace tactile::packet_detail

namespace tactile {

PacketFormatInfo packet_format_info(const std::string& skin) {
  const packet_detail::SkinFormat& format = packet_detail::require_format(skin, "skin " + skin);
  PacketFormatInfo info;
  info.skin = format.skin;
  info.sample_rate_hz = format.rate_hz;
  info.samples_per_datagram = format.samples_per_datagram;
  info.wire_channels = format.wire_channels;
  info.payload_bytes_per_sample = packet_detail::payload_bytes_per_sample(format);
  return info;
}

std::vector<int> device_channels(const SkinLayout& layout) {
  return packet_detail::make_wire_plan(layout).device_channels;
}

uint8_t packet_skin_code(const std::string& skin) {
  return packet_detail::require_format(skin, "skin " + skin).code;
}

std::string packet_skin_name(uint8_t code) {
  const packet_detail::SkinFormat* format = packet_detail::find_format(code);
  return format ? format->skin : "";
}

}  // namespace tactile

// Encoding streams into datagrams and decoding them back (header byte map in
// docs/PACKETS.md). Every read of a datagram is preceded by a length check.
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "packet_bytes.h"
#include "packet_formats.h"
#include "tactile/error.h"
#include "tactile/live/packets.h"

namespace tactile {

using namespace packet_detail;

namespace {

// Byte offsets of the header fields.
constexpr size_t kOffsetVersion = 4;
constexpr size_t kOffsetSkin = 5;
constexpr size_t kOffsetFlags = 6;
constexpr size_t kOffsetHeaderLength = 7;
constexpr size_t kOffsetSequence = 8;
constexpr size_t kOffsetTime = 12;
constexpr size_t kOffsetSampleCount = 20;
constexpr size_t kOffsetChannelCount = 22;
constexpr size_t kOffsetPayloadLength = 24;
constexpr size_t kOffsetCrc = 28;

Error packet_error(size_t offset, const std::string& message) {
  return Error("packet byte " + std::to_string(offset), message);
}

std::string hex32(uint32_t value) {
  std::ostringstream out;
  out << "0x" << std::hex << value;
  return out.str();
}

std::array<uint32_t, 256> make_crc_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t index = 0; index < 256; ++index) {
    uint32_t value = index;
    for (int bit = 0; bit < 8; ++bit) value = (value & 1) ? (value >> 1) ^ 0xEDB88320u : value >> 1;
    table[index] = value;
  }
  return table;
}

}  // namespace

uint32_t crc32(std::span<const uint8_t> bytes) {
  static const std::array<uint32_t, 256> table = make_crc_table();
  uint32_t crc = 0xFFFFFFFFu;
  for (uint8_t byte : bytes) crc = table[(crc ^ byte) & 0xFF] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

//---- Encoding --------------------------------------------------------------------------

PacketEncoder::PacketEncoder(const SkinLayout& layout, const Stream& stream)
    : plan_(std::make_shared<WirePlan>(make_wire_plan(layout))),
      stream_(&stream),
      format_(packet_format_info(layout.id)) {
  const std::string where = "stream " + stream.name;
  if (static_cast<size_t>(stream.samples.cols()) != stream.channels.size())
    throw Error(where, "has " + std::to_string(stream.channels.size()) + " channel names for " +
                           std::to_string(stream.samples.cols()) + " columns");
  if (!(std::abs(stream.rate_hz - format_.sample_rate_hz) <= 1e-9 * format_.sample_rate_hz))
    throw Error(where, "rate " + std::to_string(stream.rate_hz) + " Hz is not the " + format_.skin +
                           " device's " + std::to_string(format_.sample_rate_hz) + " Hz");
  // Stream column of each layout channel; channels the device does not send (flux's virtual
  // sums) may be present and are left out.
  std::vector<int> column_of_channel(layout.channels.size(), -1);
  for (size_t column = 0; column < stream.channels.size(); ++column) {
    const int channel = layout.channel_index(stream.channels[column]);
    if (channel < 0)
      throw Error(where,
                  "channel \"" + stream.channels[column] + "\" is not in layout " + layout.id);
    if (column_of_channel[static_cast<size_t>(channel)] >= 0)
      throw Error(where, "channel \"" + stream.channels[column] + "\" appears twice");
    column_of_channel[static_cast<size_t>(channel)] = static_cast<int>(column);
  }
  for (int channel : plan_->wire_channels) {
    const int column = column_of_channel[static_cast<size_t>(channel)];
    if (column < 0)
      throw Error(where, "lacks channel \"" + layout.channels[static_cast<size_t>(channel)].name +
                             "\" that the " + layout.id + " device sends");
    stream_columns_.push_back(column);
  }
}

std::vector<std::vector<uint8_t>> PacketEncoder::encode(int64_t first, int64_t count,
                                                        uint32_t& sequence) const {
  const Stream& stream = *stream_;
  if (first < 0 || count < 0 || first + count > stream.sample_count())
    throw Error("stream " + stream.name, "samples [" + std::to_string(first) + ", " +
                                             std::to_string(first + count) + ") outside its " +
                                             std::to_string(stream.sample_count()) + " samples");
  const SkinFormat& format = *plan_->format;
  const size_t wire_count = plan_->wire_channels.size();
  std::vector<int32_t> counts(wire_count);
  std::vector<std::vector<uint8_t>> datagrams;
  for (int64_t start = first; start < first + count; start += format.samples_per_datagram) {
    const int64_t rows = std::min<int64_t>(format.samples_per_datagram, first + count - start);
    std::vector<uint8_t> payload;
    payload.reserve(payload_bytes(format, static_cast<uint64_t>(rows)));
    bool saturated = false;
    for (int64_t row = start; row < start + rows; ++row) {
      for (size_t wire = 0; wire < wire_count; ++wire) {
        const double value = stream.samples(row, stream_columns_[wire]);
        if (!std::isfinite(value))
          throw Error("stream " + stream.name + " channel " +
                          stream.channels[static_cast<size_t>(stream_columns_[wire])] + " sample " +
                          std::to_string(row),
                      "value is " + std::to_string(value) + "; the device format has no NaN");
        counts[wire] = plan_->scales[wire]->to_count(value, saturated);
      }
      switch (format.word) {
        case WireWord::kInt16:
        case WireWord::kUint16:
          // Two's complement carries the int16 counts; their range fits by construction.
          for (int32_t value : counts) put_u16(payload, static_cast<uint16_t>(value));
          break;
        case WireWord::kPacked12:
          // Value a in the low 12 bits, value b in the high 12 bits of 3 little-endian bytes.
          for (size_t wire = 0; wire < wire_count; wire += 2) {
            const uint32_t a = static_cast<uint32_t>(counts[wire]);
            const uint32_t b = wire + 1 < wire_count ? static_cast<uint32_t>(counts[wire + 1]) : 0;
            payload.push_back(static_cast<uint8_t>(a));
            payload.push_back(static_cast<uint8_t>((a >> 8) | (b << 4)));
            if (wire + 1 < wire_count) payload.push_back(static_cast<uint8_t>(b >> 4));
          }
          break;
        case WireWord::kNaoCells:
          for (size_t cell = 0; cell < plan_->cell_ids.size(); ++cell) {
            put_u8(payload, static_cast<uint8_t>(plan_->cell_ids[cell]));
            put_u8(payload, 0);
            for (int slot = 0; slot < kNaoSlots; ++slot)
              put_u16(payload, static_cast<uint16_t>(counts[cell * kNaoSlots + slot]));
          }
          break;
      }
    }
    std::vector<uint8_t> datagram;
    datagram.reserve(kPacketHeaderSize + payload.size());
    datagram.insert(datagram.end(), kPacketMagic, kPacketMagic + 4);
    put_u8(datagram, kPacketVersion);
    put_u8(datagram, format.code);
    put_u8(datagram, saturated ? kPacketFlagSaturated : 0);
    put_u8(datagram, kPacketHeaderSize);
    put_u32(datagram, sequence++);
    put_f64(datagram, stream.time_of(start));
    put_u16(datagram, static_cast<uint16_t>(rows));
    put_u16(datagram, static_cast<uint16_t>(wire_count));
    put_u32(datagram, static_cast<uint32_t>(payload.size()));
    put_u32(datagram, crc32(payload));
    datagram.insert(datagram.end(), payload.begin(), payload.end());
    datagrams.push_back(std::move(datagram));
  }
  return datagrams;
}

std::vector<std::vector<uint8_t>> encode_packets(const std::string& skin, const Stream& stream,
                                                 int64_t first, int64_t count, uint32_t& sequence) {
  return PacketEncoder(load_layout(skin), stream).encode(first, count, sequence);
}

//---- Decoding --------------------------------------------------------------------------

PacketHeader decode_packet_header(std::span<const uint8_t> datagram) {
  const size_t size = datagram.size();
  if (size < static_cast<size_t>(kPacketHeaderSize))
    throw packet_error(
        size, "datagram of " + std::to_string(size) + " bytes ends inside the 32-byte header");
  const uint8_t* bytes = datagram.data();
  if (!std::equal(kPacketMagic, kPacketMagic + 4, bytes))
    throw packet_error(0, "magic is not \"TWPK\"");
  PacketHeader header;
  header.version = bytes[kOffsetVersion];
  header.skin_code = bytes[kOffsetSkin];
  header.flags = bytes[kOffsetFlags];
  header.header_length = bytes[kOffsetHeaderLength];
  header.sequence = get_u32(bytes + kOffsetSequence);
  header.time = get_f64(bytes + kOffsetTime);
  header.sample_count = get_u16(bytes + kOffsetSampleCount);
  header.channel_count = get_u16(bytes + kOffsetChannelCount);
  header.payload_length = get_u32(bytes + kOffsetPayloadLength);
  header.payload_crc = get_u32(bytes + kOffsetCrc);
  if (header.version != kPacketVersion)
    throw packet_error(kOffsetVersion, "version " + std::to_string(header.version) +
                                           " is not supported (this reader knows version " +
                                           std::to_string(kPacketVersion) + ")");
  if (header.flags & ~kPacketFlagSaturated)
    throw packet_error(kOffsetFlags,
                       "reserved flag bits are set (flags " + std::to_string(header.flags) + ")");
  // A longer header is allowed: a later version may append fields that this reader skips.
  if (header.header_length < kPacketHeaderSize || header.header_length > size)
    throw packet_error(kOffsetHeaderLength, "header length " +
                                                std::to_string(header.header_length) +
                                                " is not between 32 and the datagram's " +
                                                std::to_string(size) + " bytes");
  if (header.payload_length != size - header.header_length)
    throw packet_error(kOffsetPayloadLength,
                       "payload length " + std::to_string(header.payload_length) +
                           " does not match the " + std::to_string(size - header.header_length) +
                           " bytes after the header");
  if (!std::isfinite(header.time))
    throw packet_error(kOffsetTime, "time stamp is not a finite number");
  if (header.sample_count == 0) throw packet_error(kOffsetSampleCount, "sample count is 0");
  return header;
}

namespace {

// Reads one value of a flat payload and checks it against the ADC range.
int32_t checked_count(int32_t value, const CountScale& scale, size_t offset) {
  if (value < scale.min_count || value > scale.max_count)
    throw packet_error(offset, "value " + std::to_string(value) + " is outside the ADC range " +
                                   std::to_string(scale.min_count) + ".." +
                                   std::to_string(scale.max_count));
  return value;
}

void decode_nao_sample(const uint8_t* bytes, size_t offset, int64_t row, const WirePlan& plan,
                       PacketBatch& batch) {
  std::array<int, 256> cell_of_id;
  cell_of_id.fill(-1);
  for (size_t cell = 0; cell < plan.cell_ids.size(); ++cell)
    cell_of_id[static_cast<size_t>(plan.cell_ids[cell])] = static_cast<int>(cell);
  std::array<bool, kNaoCells> seen{};
  for (int record = 0; record < kNaoCells; ++record) {
    const size_t at = offset + static_cast<size_t>(record) * kNaoRecordBytes;
    const uint8_t id = bytes[at];
    const int cell = cell_of_id[id];
    if (cell < 0) throw packet_error(at, "cell id " + std::to_string(id) + " is not in the layout");
    if (seen[static_cast<size_t>(cell)])
      throw packet_error(
          at, "cell " + std::to_string(id) + " appears twice in sample " + std::to_string(row));
    seen[static_cast<size_t>(cell)] = true;
    if (bytes[at + 1] != 0) throw packet_error(at + 1, "reserved byte of a cell record is not 0");
    for (int slot = 0; slot < kNaoSlots; ++slot) {
      const size_t value_at = at + 2 + 2 * static_cast<size_t>(slot);
      const CountScale& scale = nao_scale(slot);
      const int32_t raw =
          scale.min_count < 0 ? get_i16(bytes + value_at) : get_u16(bytes + value_at);
      const size_t wire = static_cast<size_t>(cell) * kNaoSlots + static_cast<size_t>(slot);
      batch.samples(row, plan.column_of_wire[wire]) =
          scale.to_value(checked_count(raw, scale, value_at));
    }
  }
}

void decode_flat_sample(const uint8_t* bytes, size_t offset, int64_t row, const WirePlan& plan,
                        PacketBatch& batch) {
  const SkinFormat& format = *plan.format;
  const size_t count = plan.wire_channels.size();
  for (size_t wire = 0; wire < count; ++wire) {
    int32_t raw = 0;
    size_t at = 0;
    switch (format.word) {
      case WireWord::kInt16:
        at = offset + 2 * wire;
        raw = get_i16(bytes + at);
        break;
      case WireWord::kUint16:
        at = offset + 2 * wire;
        raw = get_u16(bytes + at);
        break;
      case WireWord::kPacked12: {
        at = offset + 3 * (wire / 2);
        raw = (wire % 2 == 0) ? (bytes[at] | ((bytes[at + 1] & 0x0F) << 8))
                              : ((bytes[at + 1] >> 4) | (bytes[at + 2] << 4));
        break;
      }
      case WireWord::kNaoCells:
        break;
    }
    batch.samples(row, plan.column_of_wire[wire]) =
        format.scale.to_value(checked_count(raw, format.scale, at));
  }
}

}  // namespace

PacketBatch decode_packet(std::span<const uint8_t> datagram, const SkinLayout& layout) {
  const PacketHeader header = decode_packet_header(datagram);
  const SkinFormat* format = find_format(header.skin_code);
  if (!format)
    throw packet_error(kOffsetSkin, "unknown skin code " + std::to_string(header.skin_code));
  if (layout.id != format->skin)
    throw packet_error(kOffsetSkin, std::string("packet is from skin ") + format->skin +
                                        " but the layout is " + layout.id);
  const WirePlan plan = make_wire_plan(layout);
  if (header.channel_count != plan.device_channels.size())
    throw packet_error(kOffsetChannelCount,
                       "channel count " + std::to_string(header.channel_count) +
                           " does not match the layout's " +
                           std::to_string(plan.device_channels.size()) + " device channels");
  const uint64_t expected = payload_bytes(*format, header.sample_count);
  if (header.payload_length != expected)
    throw packet_error(kOffsetPayloadLength,
                       "payload length " + std::to_string(header.payload_length) + " is not the " +
                           std::to_string(expected) + " bytes of " +
                           std::to_string(header.sample_count) + " " + format->skin + " samples");
  const std::span<const uint8_t> payload = datagram.subspan(header.header_length);
  const uint32_t crc = crc32(payload);
  if (crc != header.payload_crc)
    throw packet_error(kOffsetCrc, "CRC-32 of the payload is " + hex32(crc) + ", the header says " +
                                       hex32(header.payload_crc));

  PacketBatch batch;
  batch.skin = format->skin;
  batch.sequence = header.sequence;
  batch.time = header.time;
  batch.saturated = (header.flags & kPacketFlagSaturated) != 0;
  batch.channels = plan.device_channels;
  batch.samples.resize(header.sample_count, static_cast<Eigen::Index>(plan.device_channels.size()));
  const size_t stride = static_cast<size_t>(payload_bytes_per_sample(*format));
  for (int64_t row = 0; row < header.sample_count; ++row) {
    const size_t offset = header.header_length + static_cast<size_t>(row) * stride;
    if (format->word == WireWord::kNaoCells)
      decode_nao_sample(datagram.data(), offset, row, plan, batch);
    else
      decode_flat_sample(datagram.data(), offset, row, plan, batch);
  }
  return batch;
}

}  // namespace tactile

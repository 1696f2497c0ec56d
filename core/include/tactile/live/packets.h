#pragma once
// The live packet format of the five skins (docs/PACKETS.md): one 32-byte header shared by
// all skins, then each device's own payload of raw ADC counts. Encoding turns a Stream in
// physical units into datagrams; decoding turns a datagram back into samples, and refuses
// anything malformed with a tactile::Error naming the byte offset. No sockets here.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/skins/skin.h"

namespace tactile {

namespace packet_detail {
struct WirePlan;
}

//---- Header ----------------------------------------------------------------------------

inline constexpr char kPacketMagic[4] = {'T', 'W', 'P', 'K'};
inline constexpr uint8_t kPacketVersion = 1;
inline constexpr int kPacketHeaderSize = 32;
// Header flag bit 0: at least one value of this datagram was out of the device's range and
// was clamped to its ADC limit when encoded. Other bits are reserved and must be zero.
inline constexpr uint8_t kPacketFlagSaturated = 0x01;

struct PacketHeader {
  uint8_t version = kPacketVersion;
  uint8_t skin_code = 0;
  uint8_t flags = 0;
  uint8_t header_length = kPacketHeaderSize;
  uint32_t sequence = 0;
  double time = 0.0;  // device time stamp of the first sample (s)
  uint16_t sample_count = 0;
  uint16_t channel_count = 0;  // wire channels per sample
  uint32_t payload_length = 0;
  uint32_t payload_crc = 0;
};

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as zlib's crc32).
uint32_t crc32(std::span<const uint8_t> bytes);

// Skin code on the wire (its record's: nao 1, tsa 2, fur 3, robovie 4, flux 5). Throws
// tactile::Error naming the skin when it has no packet format.
uint8_t packet_skin_code(const std::string& skin);
// "" for an unknown code.
std::string packet_skin_name(uint8_t code);

//---- Device formats --------------------------------------------------------------------

// How a skin's device groups samples into datagrams and what one datagram costs.
struct PacketFormatInfo {
  std::string skin;
  double sample_rate_hz = 0.0;   // the device's native rate
  int samples_per_datagram = 1;  // what the encoder packs: flux 10, the others 1
  int wire_channels = 0;         // values per sample on the wire
  int payload_bytes_per_sample = 0;
  double datagrams_per_second() const { return sample_rate_hz / samples_per_datagram; }
};
PacketFormatInfo packet_format_info(const std::string& skin);

// The layout channels a device sends, in layout order: every channel owned by a taxel (flux's
// virtual sums x_sum and y_sum are computed by preprocessing and never sent). Throws
// tactile::Error when the layout does not fit the skin's packet format.
std::vector<int> device_channels(const SkinLayout& layout);

//---- Encoding --------------------------------------------------------------------------

// Maps a Stream's columns onto a skin's wire channels once, then encodes sample ranges.
class PacketEncoder {
 public:
  // Throws tactile::Error when the stream lacks a device channel, has a channel the layout
  // does not know, or its rate is not the device's. The encoder reads `stream` when encoding:
  // the stream must outlive it.
  PacketEncoder(const SkinLayout& layout, const Stream& stream);

  // Datagrams for samples [first, first + count), `samples_per_datagram` samples each (the
  // last may hold fewer); `sequence` is the number of the first and is advanced by one per
  // datagram. Values are converted to counts and clamped to the ADC range; NaN or infinite
  // values throw tactile::Error naming the channel and sample.
  std::vector<std::vector<uint8_t>> encode(int64_t first, int64_t count, uint32_t& sequence) const;

  const PacketFormatInfo& format() const { return format_; }

 private:
  std::shared_ptr<const packet_detail::WirePlan> plan_;
  const Stream* stream_;
  PacketFormatInfo format_;
  std::vector<int> stream_columns_;  // per wire position, the stream column holding it
};

// One-shot convenience: loads the skin's layout and encodes. Prefer PacketEncoder in loops.
std::vector<std::vector<uint8_t>> encode_packets(const std::string& skin, const Stream& stream,
                                                 int64_t first, int64_t count, uint32_t& sequence);

//---- Decoding --------------------------------------------------------------------------

struct PacketBatch {
  std::string skin;
  uint32_t sequence = 0;
  double time = 0.0;  // device time of the first row (s)
  bool saturated = false;
  // Rows = samples, columns = the layout's device channels (`channels`, in layout order) in
  // the layout's units.
  SampleMatrix samples;
  std::vector<int> channels;  // layout channel index of each column
};

// Reads the header alone; throws tactile::Error (where "packet byte N") when the datagram is
// shorter than a header, the magic, version, header length or flags are wrong, or the length
// does not match.
PacketHeader decode_packet_header(std::span<const uint8_t> datagram);

// Checks everything (header, skin against the layout, CRC, channel count, payload length,
// values within the ADC range, finite time) and converts counts to units. Throws
// tactile::Error naming the problem and its byte offset; never reads out of bounds.
PacketBatch decode_packet(std::span<const uint8_t> datagram, const SkinLayout& layout);

//---- Sequence tracking -----------------------------------------------------------------

// Counts lost, duplicated and reordered datagrams from their sequence numbers (u32, wrapping).
// A number ahead of the next expected one marks the gap as lost; when a missing number arrives
// later it is counted as reordered and no longer as lost. A number already seen within the
// last kWindow numbers is a duplicate. A number more than `restart_behind` (at most kWindow)
// behind cannot be a late datagram on any real network: the sender restarted its count, and
// tracking starts over (LiveTimeline sets it to a second of datagrams).
class SequenceTracker {
 public:
  static constexpr uint32_t kWindow = 4096;

  explicit SequenceTracker(uint32_t restart_behind = kWindow);

  // Returns true when the datagram is new (deliver it), false for a duplicate (drop it).
  bool accept(uint32_t sequence);
  // The sender started over (its device was unplugged, it was restarted): counts a restart
  // and accepts `sequence` as the first number of the new count.
  void restart_at(uint32_t sequence);
  // True once a number was accepted; next() is one past the highest accepted number.
  bool started() const { return started_; }
  uint32_t next() const { return next_; }

  int64_t received() const { return received_; }  // accepted datagrams
  int64_t lost() const { return lost_; }          // skipped and still missing
  int64_t duplicated() const { return duplicated_; }
  int64_t reordered() const { return reordered_; }  // arrived after a later number
  int64_t restarts() const { return restarts_; }

 private:
  void start_at(uint32_t sequence);

  uint32_t restart_behind_;
  bool started_ = false;
  uint32_t first_ = 0;  // lowest number accepted since the (re)start
  uint32_t next_ = 0;   // one past the highest number accepted
  std::vector<bool> seen_ = std::vector<bool>(kWindow, false);  // by sequence % kWindow
  int64_t received_ = 0;
  int64_t lost_ = 0;
  int64_t duplicated_ = 0;
  int64_t reordered_ = 0;
  int64_t restarts_ = 0;
};

}  // namespace tactile

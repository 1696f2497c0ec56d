// Broken datagrams: every refusal names its problem and byte offset; no length of a cut
// datagram and no flipped byte crashes the decoder.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "packet_test_support.h"
#include "tactile/error.h"
#include "tactile/live/packets.h"

namespace tactile {
namespace {

std::vector<uint8_t> valid_datagram(const SkinLayout& layout, int64_t samples = 1) {
  const Stream stream = test::grid_stream(layout, samples, 7);
  uint32_t sequence = 100;
  return PacketEncoder(layout, stream).encode(0, samples, sequence).front();
}

void put_u16_at(std::vector<uint8_t>& datagram, size_t at, uint16_t value) {
  datagram[at] = static_cast<uint8_t>(value);
  datagram[at + 1] = static_cast<uint8_t>(value >> 8);
}

// After editing a payload, the broken value should be what is reported, not the CRC.
void reseal(std::vector<uint8_t>& datagram) {
  const uint32_t crc = crc32(std::span<const uint8_t>(datagram).subspan(kPacketHeaderSize));
  for (int index = 0; index < 4; ++index)
    datagram[28 + index] = static_cast<uint8_t>(crc >> (8 * index));
}

void expect_refusal(const std::vector<uint8_t>& datagram, const SkinLayout& layout, int offset,
                    const std::string& words) {
  try {
    decode_packet(datagram, layout);
    ADD_FAILURE() << "decoded a datagram that should be refused for: " << words;
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "packet byte " + std::to_string(offset)) << error.what();
    EXPECT_NE(error.message().find(words), std::string::npos) << error.what();
  }
}

TEST(BrokenPacket, ShortDatagramNamesWhereItEnds) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram.resize(12);
  expect_refusal(datagram, layout, 12, "ends inside the 32-byte header");
}

TEST(BrokenPacket, WrongMagicIsRefusedAtByteZero) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[1] = 'X';
  expect_refusal(datagram, layout, 0, "magic");
}

TEST(BrokenPacket, UnknownVersionIsRefusedAtByteFour) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[4] = 2;
  expect_refusal(datagram, layout, 4, "version 2");
}

TEST(BrokenPacket, UnknownSkinCodeAndForeignSkinAreRefusedAtByteFive) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[5] = 9;
  expect_refusal(datagram, layout, 5, "unknown skin code 9");
  expect_refusal(valid_datagram(load_layout("flux")), layout, 5,
                 "from skin flux but the layout is fur");
}

TEST(BrokenPacket, ReservedFlagsAreRefusedAtByteSix) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[6] = 0x80;
  expect_refusal(datagram, layout, 6, "reserved flag");
}

TEST(BrokenPacket, HeaderLengthOutsideTheDatagramIsRefusedAtByteSeven) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[7] = 16;
  expect_refusal(datagram, layout, 7, "header length 16");
}

TEST(BrokenPacket, NanTimeStampIsRefusedAtByteTwelve) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(datagram.data() + 12, &nan, 8);  // the test machine is little-endian, as the format
  expect_refusal(datagram, layout, 12, "not a finite number");
}

TEST(BrokenPacket, ZeroSamplesAreRefusedAtByteTwenty) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  put_u16_at(datagram, 20, 0);
  expect_refusal(datagram, layout, 20, "sample count is 0");
}

TEST(BrokenPacket, ChannelCountNotMatchingTheLayoutIsRefusedAtByte22) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  put_u16_at(datagram, 22, 159);
  expect_refusal(datagram, layout, 22, "channel count 159 does not match the layout's 160");
}

TEST(BrokenPacket, LengthMismatchesAreRefusedAtByte24) {
  const SkinLayout layout = load_layout("fur");
  std::vector<uint8_t> longer = valid_datagram(layout);
  longer.push_back(0);
  expect_refusal(longer, layout, 24, "does not match the 321 bytes after the header");
  // Consistent lengths, but two samples' worth of header for one sample's payload.
  std::vector<uint8_t> datagram = valid_datagram(layout);
  put_u16_at(datagram, 20, 2);
  expect_refusal(datagram, layout, 24, "is not the 640 bytes of 2 fur samples");
}

TEST(BrokenPacket, CorruptPayloadIsRefusedByItsCrcAtByte28) {
  const SkinLayout layout = load_layout("tsa");
  std::vector<uint8_t> datagram = valid_datagram(layout);
  datagram[500] ^= 0x10;
  expect_refusal(datagram, layout, 28, "CRC-32");
}

TEST(BrokenPacket, ValueOutsideTheAdcRangeNamesItsByte) {
  const SkinLayout fur = load_layout("fur");
  std::vector<uint8_t> datagram = valid_datagram(fur);
  put_u16_at(datagram, 32 + 2 * 40, 2000);  // channel 40: 2000 does not fit 10 bits
  reseal(datagram);
  expect_refusal(datagram, fur, 32 + 80, "value 2000 is outside the ADC range 0..1023");

  const SkinLayout nao = load_layout("nao");
  std::vector<uint8_t> cells = valid_datagram(nao);
  put_u16_at(cells, 32 + 18 * 3 + 2, 600);  // cell record 3, ax: a 10-bit accelerometer
  reseal(cells);
  expect_refusal(cells, nao, 32 + 18 * 3 + 2, "value 600 is outside the ADC range -512..511");
}

TEST(BrokenPacket, NaoCellIdsMustBeKnownAndAppearOnce) {
  const SkinLayout layout = load_layout("nao");
  std::vector<uint8_t> unknown = valid_datagram(layout);
  unknown[32 + 18 * 4] = 40;
  reseal(unknown);
  expect_refusal(unknown, layout, 32 + 18 * 4, "cell id 40 is not in the layout");
  std::vector<uint8_t> twice = valid_datagram(layout);
  twice[32 + 18 * 4] = 2;  // record 4 claims to be cell 2, already sent in record 1
  reseal(twice);
  expect_refusal(twice, layout, 32 + 18 * 4, "cell 2 appears twice");
}

TEST(BrokenPacket, EveryTruncationOfEverySkinIsRefusedWithoutACrash) {
  for (const std::string& skin : packet_skin_ids()) {
    const SkinLayout layout = load_layout(skin);
    const std::vector<uint8_t> datagram =
        valid_datagram(layout, packet_format_info(skin).samples_per_datagram);
    ASSERT_NO_THROW(decode_packet(datagram, layout)) << skin;
    for (size_t length = 0; length < datagram.size(); ++length) {
      // A copy of exactly `length` bytes, so a read past it would be a read past the heap block.
      const std::vector<uint8_t> cut(datagram.begin(), datagram.begin() + length);
      EXPECT_THROW(decode_packet(cut, layout), Error) << skin << " cut at " << length;
    }
  }
}

TEST(BrokenPacket, RandomByteFlipsDecodeOrThrowButNeverCrash) {
  std::mt19937_64 engine(2024);
  for (const std::string& skin : packet_skin_ids()) {
    const SkinLayout layout = load_layout(skin);
    const std::vector<uint8_t> datagram = valid_datagram(layout);
    std::uniform_int_distribution<size_t> position(0, datagram.size() - 1);
    std::uniform_int_distribution<int> bit(0, 7);
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<uint8_t> flipped = datagram;
      const size_t at = position(engine);
      flipped[at] ^= static_cast<uint8_t>(1 << bit(engine));
      const bool in_payload = at >= static_cast<size_t>(kPacketHeaderSize);
      const bool sealed = trial % 2 == 1 && in_payload;  // reach the value checks
      if (sealed) reseal(flipped);
      bool refused = false;
      try {
        decode_packet(flipped, layout);
      } catch (const Error&) {
        refused = true;
      }
      // CRC-32 catches every single-bit error of the payload.
      if (in_payload && !sealed) {
        EXPECT_TRUE(refused) << skin << " byte " << at;
      }
    }
  }
}

}  // namespace
}  // namespace tactile

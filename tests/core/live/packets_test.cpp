#include "tactile/live/packets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "packet_test_support.h"
#include "tactile/error.h"

namespace tactile {
namespace {

using test::documented_range;
using test::grid_stream;

std::span<const uint8_t> span_of(const std::string& text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

//---- CRC and header --------------------------------------------------------------------

TEST(PacketCrc, CheckStringGivesTheStandardCrc32) {
  EXPECT_EQ(crc32(span_of("123456789")), 0xCBF43926u);
  EXPECT_EQ(crc32(span_of("")), 0u);
}

TEST(PacketHeader, IsLaidOutByteByByteAsDocumented) {
  const SkinLayout layout = load_layout("robovie");
  Stream stream = grid_stream(layout, 1, 3);
  uint32_t sequence = 0x01020304;
  const auto datagrams = PacketEncoder(layout, stream).encode(0, 1, sequence);
  ASSERT_EQ(datagrams.size(), 1u);
  const std::vector<uint8_t>& d = datagrams[0];
  ASSERT_EQ(d.size(), 32u + 274 * 2);
  EXPECT_EQ(std::string(d.begin(), d.begin() + 4), "TWPK");
  EXPECT_EQ(d[4], 1);     // version
  EXPECT_EQ(d[5], 4);     // robovie
  EXPECT_EQ(d[6], 0);     // flags: nothing clamped
  EXPECT_EQ(d[7], 32);    // header length
  EXPECT_EQ(d[8], 0x04);  // sequence, little-endian
  EXPECT_EQ(d[11], 0x01);
  // 12.5 s as an IEEE-754 double is 0x4029000000000000.
  EXPECT_EQ(d[19], 0x40);
  EXPECT_EQ(d[18], 0x29);
  EXPECT_EQ(d[12], 0x00);
  EXPECT_EQ(d[20] | (d[21] << 8), 1);    // samples
  EXPECT_EQ(d[22] | (d[23] << 8), 274);  // channels
  EXPECT_EQ(d[24] | (d[25] << 8), 548);  // payload bytes
  EXPECT_EQ(sequence, 0x01020305u);
  // Row 0 holds each channel's minimum: int16 -32768 = 0x8000 little-endian.
  EXPECT_EQ(d[32], 0x00);
  EXPECT_EQ(d[33], 0x80);
}

TEST(PacketHeader, TheWorkedExampleOfTheDocsDecodes) {
  // docs/PACKETS.md, "Worked example": one flux sample.
  const std::vector<uint8_t> datagram = {0x54, 0x57, 0x50, 0x4b, 0x01, 0x05, 0x00, 0x20, 0x07, 0x00,
                                         0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd0, 0x3f,
                                         0x01, 0x00, 0x08, 0x00, 0x10, 0x00, 0x00, 0x00, 0x49, 0x23,
                                         0xe5, 0x7c, 0x00, 0x02, 0x12, 0x02, 0xf2, 0x01, 0xff, 0x03,
                                         0x00, 0x00, 0x64, 0x00, 0xc8, 0x00, 0x2c, 0x01};
  const PacketBatch batch = decode_packet(datagram, load_layout("flux"));
  EXPECT_EQ(batch.sequence, 7u);
  EXPECT_EQ(batch.time, 0.25);
  ASSERT_EQ(batch.samples.rows(), 1);
  ASSERT_EQ(batch.samples.cols(), 8);
  const std::vector<float> expected = {512, 530, 498, 1023, 0, 100, 200, 300};
  for (int column = 0; column < 8; ++column)
    EXPECT_EQ(batch.samples(0, column), expected[static_cast<size_t>(column)]) << column;
}

//---- Round trips -----------------------------------------------------------------------

class PacketRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(PacketRoundTrip, GridValuesComeBackExactlyWithTheirTimeStamps) {
  const SkinLayout layout = load_layout(GetParam());
  const PacketFormatInfo info = packet_format_info(layout.id);
  // Flux packs 10 samples a datagram, so its last one is short; the others send one each.
  const int64_t samples = 2 * info.samples_per_datagram + 3;
  const int64_t expected_datagrams = info.samples_per_datagram == 1 ? 5 : 3;
  const Stream stream = grid_stream(layout, samples, 11);
  const PacketEncoder encoder(layout, stream);
  uint32_t sequence = 40;
  const auto datagrams = encoder.encode(0, samples, sequence);
  ASSERT_EQ(static_cast<int64_t>(datagrams.size()), expected_datagrams);
  EXPECT_EQ(sequence, 40u + expected_datagrams);

  int64_t row = 0;
  for (size_t index = 0; index < datagrams.size(); ++index) {
    const PacketBatch batch = decode_packet(datagrams[index], layout);
    EXPECT_EQ(batch.skin, layout.id);
    EXPECT_EQ(batch.sequence, 40 + index);
    EXPECT_DOUBLE_EQ(batch.time, stream.time_of(row));
    EXPECT_FALSE(batch.saturated);
    ASSERT_EQ(batch.samples.cols(), info.wire_channels);
    for (int64_t r = 0; r < batch.samples.rows(); ++r)
      for (Eigen::Index column = 0; column < batch.samples.cols(); ++column) {
        const int channel = batch.channels[static_cast<size_t>(column)];
        const int stream_column = layout.channel_index(layout.channels[channel].name);
        ASSERT_EQ(batch.samples(r, column), stream.samples(row + r, stream_column))
            << layout.channels[channel].name << " sample " << row + r;
      }
    row += batch.samples.rows();
  }
  EXPECT_EQ(row, samples);
}

TEST_P(PacketRoundTrip, OffGridValuesComeBackWithinHalfAnAdcStep) {
  const SkinLayout layout = load_layout(GetParam());
  Stream stream = grid_stream(layout, 4, 5);
  std::mt19937_64 engine(9);
  std::uniform_real_distribution<double> fraction(-0.49, 0.49);
  SampleMatrix original = stream.samples;
  for (Eigen::Index column = 0; column < stream.samples.cols(); ++column) {
    const auto range = documented_range(layout.id, layout.channels[column].modality);
    for (Eigen::Index row = 2; row < 4; ++row) {  // rows 0 and 1 sit on the range limits
      original(row, column) += static_cast<float>(fraction(engine) * range.step);
      stream.samples(row, column) = original(row, column);
    }
  }
  uint32_t sequence = 0;
  const PacketEncoder encoder(layout, stream);
  for (const auto& datagram : encoder.encode(2, 2, sequence)) {
    const PacketBatch batch = decode_packet(datagram, layout);
    const int64_t first = stream.index_at(batch.time + 1e-9);
    for (int64_t r = 0; r < batch.samples.rows(); ++r)
      for (Eigen::Index column = 0; column < batch.samples.cols(); ++column) {
        const int channel = batch.channels[static_cast<size_t>(column)];
        const auto range = documented_range(layout.id, layout.channels[channel].modality);
        EXPECT_NEAR(batch.samples(r, column), original(first + r, channel),
                    0.5 * range.step + 1e-4);
      }
  }
}

INSTANTIATE_TEST_SUITE_P(FiveSkins, PacketRoundTrip,
                         ::testing::Values("nao", "tsa", "fur", "robovie", "flux"));

TEST(PacketFormat, FluxSendsItsEightSerpentinesAndNotTheVirtualSums) {
  const SkinLayout layout = load_layout("flux");
  const std::vector<int> channels = device_channels(layout);
  std::vector<std::string> names;
  for (int channel : channels) names.push_back(layout.channels[channel].name);
  EXPECT_EQ(names, (std::vector<std::string>{"x1", "x2", "x3", "x4", "y1", "y2", "y3", "y4"}));
  EXPECT_EQ(packet_format_info("flux").datagrams_per_second(), 100.0);
  // A stream of only the real channels (as the simulator writes) encodes too.
  Stream stream = grid_stream(layout, 10, 1);
  Stream real = stream;
  real.channels.clear();
  real.units.clear();
  real.samples.resize(10, 8);
  for (size_t k = 0; k < channels.size(); ++k) {
    real.channels.push_back(layout.channels[channels[k]].name);
    real.units.push_back("counts");
    real.samples.col(static_cast<Eigen::Index>(k)) = stream.samples.col(channels[k]);
  }
  uint32_t sequence = 0;
  const auto datagrams = PacketEncoder(layout, real).encode(0, 10, sequence);
  ASSERT_EQ(datagrams.size(), 1u);
  EXPECT_EQ(datagrams[0].size(), 32u + 10 * 8 * 2);
  EXPECT_TRUE(decode_packet(datagrams[0], layout).samples.isApprox(real.samples, 0.0f));
}

TEST(PacketFormat, TsaPacksTwelveBitPairsInThreeBytes) {
  const SkinLayout layout = load_layout("tsa");
  Stream stream = grid_stream(layout, 1, 2);
  stream.samples(0, 0) = 0xABC;
  stream.samples(0, 1) = 0x123;
  uint32_t sequence = 0;
  const auto datagrams = PacketEncoder(layout, stream).encode(0, 1, sequence);
  ASSERT_EQ(datagrams[0].size(), 32u + 1008);
  EXPECT_EQ(datagrams[0][32], 0xBC);
  EXPECT_EQ(datagrams[0][33], 0x3A);
  EXPECT_EQ(datagrams[0][34], 0x12);
}

TEST(PacketFormat, NaoSendsOneEighteenByteRecordPerCellInCellIdOrder) {
  const SkinLayout layout = load_layout("nao");
  Stream stream = grid_stream(layout, 1, 2);
  const auto column = [&](const std::string& name) { return layout.channel_index(name); };
  stream.samples(0, column("c01.ax")) = -1.0f;     // -256 counts
  stream.samples(0, column("c01.f1")) = 1.2f;      // 1638 counts
  stream.samples(0, column("c01.prox")) = 200.0f;  // 65535 counts
  stream.samples(0, column("c01.temp")) = 21.37f;  // 2137 counts
  uint32_t sequence = 0;
  const auto d = PacketEncoder(layout, stream).encode(0, 1, sequence)[0];
  ASSERT_EQ(d.size(), 32u + 32 * 18);
  EXPECT_EQ(d[32], 1);  // cell id
  EXPECT_EQ(d[33], 0);  // reserved
  EXPECT_EQ(static_cast<int16_t>(d[34] | (d[35] << 8)), -256);
  EXPECT_EQ(d[40] | (d[41] << 8), 1638);
  EXPECT_EQ(d[46] | (d[47] << 8), 65535);
  EXPECT_EQ(static_cast<int16_t>(d[48] | (d[49] << 8)), 2137);
  EXPECT_EQ(d[32 + 18], 2);  // next record: cell 2
}

TEST(PacketFormat, OutOfRangeValuesSaturateAtTheAdcLimitsAndFlagTheDatagram) {
  const SkinLayout layout = load_layout("nao");
  Stream stream = grid_stream(layout, 1, 2);
  const auto column = [&](const std::string& name) { return layout.channel_index(name); };
  stream.samples(0, column("c05.az")) = 3.5f;      // over +2 g
  stream.samples(0, column("c05.f2")) = -0.4f;     // under 0 N
  stream.samples(0, column("c05.prox")) = 0.0f;    // under 1 mm
  stream.samples(0, column("c05.temp")) = 300.0f;  // over 150 degC
  uint32_t sequence = 0;
  const auto datagrams = PacketEncoder(layout, stream).encode(0, 1, sequence);
  EXPECT_EQ(datagrams[0][6], kPacketFlagSaturated);
  const PacketBatch batch = decode_packet(datagrams[0], layout);
  EXPECT_TRUE(batch.saturated);
  const auto value = [&](const std::string& name) {
    const int channel = column(name);
    for (size_t k = 0; k < batch.channels.size(); ++k)
      if (batch.channels[k] == channel) return batch.samples(0, static_cast<Eigen::Index>(k));
    return std::numeric_limits<float>::quiet_NaN();
  };
  EXPECT_FLOAT_EQ(value("c05.az"), 511.0f / 256.0f);
  EXPECT_FLOAT_EQ(value("c05.f2"), 0.0f);
  EXPECT_FLOAT_EQ(value("c05.prox"), 1.0f);
  EXPECT_FLOAT_EQ(value("c05.temp"), 150.0f);

  const SkinLayout robovie = load_layout("robovie");
  Stream piezo = grid_stream(robovie, 1, 2);
  piezo.samples(0, 7) = 1e6f;
  sequence = 0;
  const auto piezo_datagram = PacketEncoder(robovie, piezo).encode(0, 1, sequence)[0];
  EXPECT_FLOAT_EQ(decode_packet(piezo_datagram, robovie).samples(0, 7), 32767.0f);
}

//---- Refusals when encoding ------------------------------------------------------------

TEST(PacketEncoder, NanNamesTheChannelAndSample) {
  const SkinLayout layout = load_layout("fur");
  Stream stream = grid_stream(layout, 3, 2);
  stream.samples(2, 17) = std::numeric_limits<float>::quiet_NaN();
  uint32_t sequence = 0;
  const PacketEncoder encoder(layout, stream);
  try {
    encoder.encode(0, 3, sequence);
    FAIL() << "NaN was encoded";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "stream skin channel f017 sample 2");
  }
}

TEST(PacketEncoder, RefusesAStreamLackingADeviceChannelOrAtTheWrongRate) {
  const SkinLayout layout = load_layout("fur");
  Stream stream = grid_stream(layout, 2, 2);
  stream.channels[3] = "not-a-channel";
  EXPECT_THROW(PacketEncoder(layout, stream), Error);
  stream = grid_stream(layout, 2, 2);
  stream.rate_hz = 30.0;
  try {
    PacketEncoder encoder(layout, stream);
    FAIL() << "a 30 Hz stream was accepted for the 15 Hz fur";
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("15"), std::string::npos) << error.what();
  }
  EXPECT_THROW(packet_format_info("grid:4x4"), Error);
}

}  // namespace
}  // namespace tactile

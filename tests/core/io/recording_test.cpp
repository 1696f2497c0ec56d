#include "tactile/io/recording.h"

#include <gtest/gtest.h>

namespace tactile {
namespace {

TEST(Stream, RegularStreamMapsTimesToSampleIndices) {
  Stream stream;
  stream.rate_hz = 100.0;
  stream.samples = SampleMatrix::Zero(250, 2);
  EXPECT_DOUBLE_EQ(stream.duration(), 2.5);
  EXPECT_DOUBLE_EQ(stream.time_of(10), 0.1);
  EXPECT_EQ(stream.index_at(0.1), 10);
  EXPECT_EQ(stream.index_at(-1.0), 0);
  EXPECT_EQ(stream.index_at(99.0), 249);
}

TEST(Stream, IrregularStreamUsesItsTimestamps) {
  Stream stream;
  stream.rate_hz = 10.0;
  stream.samples = SampleMatrix::Zero(3, 1);
  stream.timestamps = {0.0, 0.5, 2.0};
  EXPECT_EQ(stream.index_at(1.9), 1);
  EXPECT_EQ(stream.index_at(2.0), 2);
  EXPECT_DOUBLE_EQ(stream.time_of(2), 2.0);
}

}  // namespace
}  // namespace tactile

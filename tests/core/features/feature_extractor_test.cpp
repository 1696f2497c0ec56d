#include "tactile/features/feature_extractor.h"

#include <gtest/gtest.h>

namespace tactile {
namespace {

TEST(SampleRange, CoversTheSamplesWhoseTimesFallInsideTheHalfOpenSpan) {
  Stream stream;
  stream.rate_hz = 10.0;
  stream.samples = SampleMatrix::Zero(50, 1);
  // Samples at 0.0, 0.1, ...: [0.1, 0.3) holds samples 1 and 2.
  EXPECT_EQ(sample_range(stream, 0.1, 0.3), (std::pair<int64_t, int64_t>{1, 3}));
  EXPECT_EQ(sample_range(stream, 0.15, 0.3), (std::pair<int64_t, int64_t>{2, 3}));
  EXPECT_EQ(sample_range(stream, -1.0, 100.0), (std::pair<int64_t, int64_t>{0, 50}));
  EXPECT_EQ(sample_range(stream, 2.0, 1.0), (std::pair<int64_t, int64_t>{0, 0}));
}

TEST(SampleRange, UsesTimestampsOfIrregularStreams) {
  Stream stream;
  stream.rate_hz = 1.0;
  stream.samples = SampleMatrix::Zero(4, 1);
  stream.timestamps = {0.0, 0.5, 2.0, 2.1};
  EXPECT_EQ(sample_range(stream, 0.5, 2.1), (std::pair<int64_t, int64_t>{1, 3}));
}

}  // namespace
}  // namespace tactile

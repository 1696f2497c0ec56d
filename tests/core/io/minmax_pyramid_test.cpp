#include "tactile/io/minmax_pyramid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tactile/error.h"

namespace tactile {
namespace {

std::vector<float> random_samples(int64_t count, uint32_t seed, double nan_fraction = 0.0) {
  std::mt19937 generator(seed);
  std::normal_distribution<float> value(0.0f, 10.0f);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  std::vector<float> samples(count);
  for (float& sample : samples) {
    sample =
        coin(generator) < nan_fraction ? std::numeric_limits<float>::quiet_NaN() : value(generator);
  }
  return samples;
}

MinMax brute_force(const std::vector<float>& samples, int64_t first, int64_t last) {
  MinMax result;
  for (int64_t index = std::max<int64_t>(first, 0); index < std::min<int64_t>(last, samples.size());
       ++index) {
    if (std::isnan(samples[index])) continue;
    result.min = std::min(result.min, samples[index]);
    result.max = std::max(result.max, samples[index]);
  }
  return result;
}

// The overview a recording file would store: per-block min/max of 256 samples.
void make_overview(const std::vector<float>& samples, std::vector<float>& low,
                   std::vector<float>& high) {
  const int64_t count = static_cast<int64_t>(samples.size());
  const int64_t block = MinMaxPyramid::kOverviewBlock;
  for (int64_t first = 0; first < count; first += block) {
    const MinMax range = brute_force(samples, first, first + block);
    low.push_back(range.empty() ? std::numeric_limits<float>::quiet_NaN() : range.min);
    high.push_back(range.empty() ? std::numeric_limits<float>::quiet_NaN() : range.max);
  }
}

struct OverviewPyramid {
  std::vector<float> samples, low, high;
  MinMaxPyramid pyramid;
  explicit OverviewPyramid(std::vector<float> data) : samples(std::move(data)) {
    make_overview(samples, low, high);
    pyramid = MinMaxPyramid(
        static_cast<int64_t>(samples.size()), low, high,
        [this](int64_t first, std::span<float> out) {
          ASSERT_GE(first, 0);
          ASSERT_LE(first + static_cast<int64_t>(out.size()), static_cast<int64_t>(samples.size()));
          std::copy_n(samples.begin() + first, out.size(), out.begin());
        },
        "test.h5");
  }
  // The reader points at this object's samples.
  OverviewPyramid(const OverviewPyramid&) = delete;
};

void expect_random_queries_match(const MinMaxPyramid& pyramid, const std::vector<float>& samples,
                                 uint32_t seed, int queries) {
  const int64_t count = static_cast<int64_t>(samples.size());
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int64_t> position(-50, count + 50);
  std::uniform_int_distribution<int> column_count(1, 300);
  for (int query = 0; query < queries; ++query) {
    int64_t first = position(generator);
    int64_t last = position(generator);
    if (first > last) std::swap(first, last);
    const int columns = column_count(generator);
    const std::vector<MinMax> result = pyramid.query(first, last, columns);
    ASSERT_EQ(result.size(), static_cast<size_t>(columns));
    for (int column = 0; column < columns; ++column) {
      const int64_t begin = first + (last - first) * column / columns;
      const int64_t end = first + (last - first) * (column + 1) / columns;
      const MinMax expected = brute_force(samples, begin, end);
      ASSERT_EQ(result[column].empty(), expected.empty())
          << "query " << query << " column " << column << " [" << begin << ", " << end << ")";
      if (!expected.empty()) {
        ASSERT_EQ(result[column].min, expected.min) << "query " << query << " column " << column;
        ASSERT_EQ(result[column].max, expected.max) << "query " << query << " column " << column;
      }
    }
  }
}

TEST(MinMaxPyramid, RandomQueriesEqualBruteForce) {
  for (int64_t count : {1, 15, 16, 17, 255, 1000, 4096, 100003}) {
    const std::vector<float> samples = random_samples(count, static_cast<uint32_t>(count));
    const MinMaxPyramid pyramid(samples);
    expect_random_queries_match(pyramid, samples, 7, 200);
  }
}

TEST(MinMaxPyramid, RandomQueriesFromOverviewEqualBruteForce) {
  for (int64_t count : {1, 255, 256, 257, 5000, 100003}) {
    const OverviewPyramid overview(random_samples(count, static_cast<uint32_t>(count) + 1));
    expect_random_queries_match(overview.pyramid, overview.samples, 11, 200);
  }
}

TEST(MinMaxPyramid, NaNSamplesAreSkipped) {
  const std::vector<float> samples = random_samples(50000, 3, 0.3);
  const MinMaxPyramid pyramid(samples);
  expect_random_queries_match(pyramid, samples, 5, 200);
  const OverviewPyramid overview(samples);
  expect_random_queries_match(overview.pyramid, samples, 6, 200);
}

TEST(MinMaxPyramid, AllNaNColumnIsAGapNotNaN) {
  std::vector<float> samples = random_samples(4000, 9);
  // Samples 1000..2999 are missing: columns 1 and 2 of four over [0, 4000).
  std::fill(samples.begin() + 1000, samples.begin() + 3000,
            std::numeric_limits<float>::quiet_NaN());
  const MinMaxPyramid in_memory(samples);
  const OverviewPyramid overview(samples);
  for (const MinMaxPyramid* pyramid : {&in_memory, &overview.pyramid}) {
    const std::vector<MinMax> columns = pyramid->query(0, 4000, 4);
    EXPECT_FALSE(columns[0].empty());
    EXPECT_TRUE(columns[1].empty());
    EXPECT_TRUE(columns[2].empty());
    EXPECT_FALSE(columns[3].empty());
    EXPECT_FALSE(std::isnan(columns[1].min));
    EXPECT_FALSE(std::isnan(columns[1].max));
    EXPECT_EQ(columns[0].min, brute_force(samples, 0, 1000).min);
    EXPECT_EQ(columns[3].max, brute_force(samples, 3000, 4000).max);
  }
}

TEST(MinMaxPyramid, EmptyRangesAreGaps) {
  const std::vector<float> samples = random_samples(1000, 13);
  const MinMaxPyramid pyramid(samples);
  EXPECT_TRUE(pyramid.range(500, 500).empty());
  EXPECT_TRUE(pyramid.range(600, 500).empty());
  EXPECT_TRUE(pyramid.range(-100, 0).empty());
  EXPECT_TRUE(pyramid.range(1000, 2000).empty());
  EXPECT_TRUE(pyramid.query(10, 20, 0).empty());
  // More columns than samples: the columns between samples hold nothing.
  const std::vector<MinMax> sparse = pyramid.query(0, 2, 4);
  EXPECT_TRUE(sparse[0].empty());
  EXPECT_EQ(sparse[1].min, samples[0]);
  EXPECT_TRUE(sparse[2].empty());
  EXPECT_EQ(sparse[3].max, samples[1]);
  const MinMaxPyramid nothing(std::span<const float>{});
  EXPECT_TRUE(nothing.range(0, 10).empty());
  EXPECT_EQ(nothing.query(0, 10, 3).size(), 3u);
}

TEST(MinMaxPyramid, LevelsTakeLessThanAThirdOfTheRawData) {
  const std::vector<float> samples = random_samples(1 << 20, 17);
  const MinMaxPyramid pyramid(samples);
  const int64_t raw_bytes = static_cast<int64_t>(samples.size() * sizeof(float));
  EXPECT_LE(pyramid.memory_bytes(), raw_bytes / 3);
  EXPECT_GT(pyramid.memory_bytes(), raw_bytes / 8);  // the levels are really there
}

TEST(MinMaxPyramid, WideColumnsReadFewRawSamples) {
  const int64_t count = 2'000'000;
  const OverviewPyramid overview(random_samples(count, 19));
  const int columns = 1000;
  overview.pyramid.query(123, count - 77, columns);
  // At most two partial blocks per column, whatever the length of the data.
  EXPECT_LE(overview.pyramid.raw_samples_read(), 2 * 255 * columns);

  // Column edges on block boundaries need the overview only.
  const int64_t before = overview.pyramid.raw_samples_read();
  std::vector<int64_t> edges;
  for (int column = 0; column <= columns; ++column) edges.push_back(column * 7 * 256);
  std::vector<MinMax> out(columns);
  overview.pyramid.query_edges(edges, out);
  EXPECT_EQ(overview.pyramid.raw_samples_read(), before);
  EXPECT_EQ(out[5].max, brute_force(overview.samples, 5 * 7 * 256, 6 * 7 * 256).max);
}

TEST(MinMaxPyramid, ZoomedInReadsOnlyTheVisibleSamples) {
  const int64_t count = 1'000'000;
  const OverviewPyramid overview(random_samples(count, 23));
  const std::vector<MinMax> out = overview.pyramid.query(500'000, 510'000, 800);
  EXPECT_EQ(overview.pyramid.raw_samples_read(), 10'000);
  EXPECT_EQ(out[0].min, brute_force(overview.samples, 500'000, 500'012).min);
}

TEST(MinMaxPyramid, OverviewOfWrongLengthNamesTheFile) {
  const std::vector<float> low(3, 0.0f), high(3, 1.0f);
  try {
    MinMaxPyramid pyramid(
        1000, low, high, [](int64_t, std::span<float>) {}, "rec.h5");
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "rec.h5");
    EXPECT_NE(error.message().find("expected 4 blocks"), std::string::npos) << error.what();
  }
}

TEST(MinMaxPyramid, OverviewBlockWithMinAboveMaxNamesTheBlock) {
  std::vector<float> low(4, 0.0f), high(4, 1.0f);
  low[2] = 5.0f;
  try {
    MinMaxPyramid pyramid(
        1000, low, high, [](int64_t, std::span<float>) {}, "rec.h5");
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), "rec.h5 overview block 2");
  }
  low[2] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(MinMaxPyramid(
                   1000, low, high, [](int64_t, std::span<float>) {}, "rec.h5"),
               Error);
}

TEST(MinMaxPyramid, DecreasingColumnEdgesAreRejected) {
  const std::vector<float> samples = random_samples(100, 29);
  const MinMaxPyramid pyramid(samples);
  const std::vector<int64_t> edges = {0, 50, 40};
  std::vector<MinMax> out(2);
  EXPECT_THROW(pyramid.query_edges(edges, out), Error);
}

}  // namespace
}  // namespace tactile

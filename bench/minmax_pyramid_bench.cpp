// A plot frame asks for the min/max of 1000 pixel columns. Through the pyramid the
// cost must stay flat from a thousand samples to a hundred million; a brute-force
// scan of the visible samples, measured in the same run, grows with them.

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "tactile/io/minmax_pyramid.h"

namespace {

constexpr int kColumns = 1000;

const std::vector<float>& samples_of(int64_t count) {
  // One buffer for the largest size, shared by every size: building 1e8 random
  // samples per benchmark would dominate the run.
  static std::vector<float> samples;
  if (static_cast<int64_t>(samples.size()) < count) {
    std::mt19937 generator(42);
    std::normal_distribution<float> value(0.0f, 1.0f);
    samples.resize(count);
    for (float& sample : samples) sample = value(generator);
  }
  return samples;
}

void PyramidQuery(benchmark::State& state) {
  const int64_t count = state.range(0);
  const std::span<const float> samples(samples_of(count).data(), count);
  const tactile::MinMaxPyramid pyramid(samples);
  // An unaligned range over almost everything, as a fitted view would ask.
  const int64_t first = count / 1000 + 3;
  const int64_t last = count - count / 1000 - 1;
  for (auto _ : state) {
    std::vector<tactile::MinMax> columns = pyramid.query(first, last, kColumns);
    benchmark::DoNotOptimize(columns.data());
  }
  state.counters["samples"] = static_cast<double>(count);
  state.counters["pyramid_MB"] = static_cast<double>(pyramid.memory_bytes()) / 1e6;
}

// The plot's way when a column spans more than the finest bucket: edges rounded to
// bucket boundaries (less than a pixel off), so no raw sample is touched.
void PyramidQueryAlignedEdges(benchmark::State& state) {
  const int64_t count = state.range(0);
  const std::span<const float> samples(samples_of(count).data(), count);
  const tactile::MinMaxPyramid pyramid(samples);
  const int64_t first = count / 1000 + 3;
  const int64_t last = count - count / 1000 - 1;
  const int64_t bucket = pyramid.finest_bucket();
  std::vector<int64_t> edges(kColumns + 1);
  std::vector<tactile::MinMax> columns(kColumns);
  for (auto _ : state) {
    for (int column = 0; column <= kColumns; ++column) {
      const int64_t edge = first + (last - first) * column / kColumns;
      edges[column] = (last - first) / kColumns >= bucket ? edge / bucket * bucket : edge;
    }
    pyramid.query_edges(edges, columns);
    benchmark::DoNotOptimize(columns.data());
  }
}

void BruteForceScan(benchmark::State& state) {
  const int64_t count = state.range(0);
  const std::vector<float>& samples = samples_of(count);
  const int64_t first = count / 1000 + 3;
  const int64_t last = count - count / 1000 - 1;
  for (auto _ : state) {
    std::vector<tactile::MinMax> columns(kColumns);
    for (int column = 0; column < kColumns; ++column) {
      const int64_t begin = first + (last - first) * column / kColumns;
      const int64_t end = first + (last - first) * (column + 1) / kColumns;
      for (int64_t index = begin; index < end; ++index) columns[column].add(samples[index]);
    }
    benchmark::DoNotOptimize(columns.data());
  }
  state.counters["samples"] = static_cast<double>(count);
}

BENCHMARK(PyramidQuery)
    ->RangeMultiplier(10)
    ->Range(1000, 100'000'000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(PyramidQueryAlignedEdges)
    ->RangeMultiplier(10)
    ->Range(1000, 100'000'000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BruteForceScan)
    ->RangeMultiplier(10)
    ->Range(1000, 100'000'000)
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

// The SampleSource seam: a file read chunk by chunk answers exactly as the same samples
// held in memory, within its cache limit, and reads only the chunks a query needs.
#include "tactile/signal/sample_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/signal/display_scale.h"

namespace tactile {
namespace {

constexpr double kSourceRate = 100.0;

// A noisy rest level per channel with a few touches (bumps), some NaN gaps.
Recording noisy_recording(int64_t samples, int channels, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = kSourceRate;
  stream.start_time = 2.0;
  for (int channel = 0; channel < channels; ++channel)
    stream.channels.push_back(std::string(1, 'c').append(std::to_string(channel)));
  stream.samples.resize(samples, channels);
  for (int channel = 0; channel < channels; ++channel)
    for (int64_t index = 0; index < samples; ++index) {
      const bool touched = (index / 1000) % 7 == 3 && channel % 2 == 0;
      stream.samples(index, channel) = 100.0f * channel + noise(random) + (touched ? 40.0f : 0.0f);
    }
  stream.samples(777, 1) = std::numeric_limits<float>::quiet_NaN();
  Recording recording;
  recording.id = "noisy";
  recording.layout_id = "strip:" + std::to_string(channels);
  recording.streams = {stream};
  return recording;
}

struct SourcePair : ::testing::Test {
  testing::TemporaryDirectory directory;
  Recording recording = noisy_recording(50'000, 5, 11);
  std::string path = directory.file("noisy.h5");
  void SetUp() override { write_recording(path, recording); }
};

TEST_F(SourcePair, FileAndMemoryAnswerTheSameMinMaxPerColumn) {
  const FileSampleSource file(path);
  const MemorySampleSource memory(recording, recording.streams.front());
  EXPECT_EQ(file.sample_count(), memory.sample_count());
  EXPECT_DOUBLE_EQ(file.end_time(), memory.end_time());
  // Zoomed in (raw samples) and out (overview): exact wherever edges fall on samples
  // the overview covers, and zoomed out (half a block a column or more) the file's edges
  // snap to the nearest of its 256-sample blocks.
  for (const auto& [t0, t1, columns] : {std::tuple{2.0, 3.0, 400}, std::tuple{5.5, 40.0, 300},
                                        std::tuple{2.0, 402.0, 200}, std::tuple{2.0, 502.0, 50}}) {
    for (int channel = 0; channel < 5; ++channel) {
      const auto from_file = file.minmax_over_time(channel, t0, t1, columns);
      const auto from_memory = memory.minmax_over_time(channel, t0, t1, columns);
      ASSERT_EQ(from_file.size(), from_memory.size());
      const double samples_per_column = (t1 - t0) / columns * kSourceRate;
      for (size_t c = 0; c < from_file.size(); ++c) {
        if (samples_per_column < 128) {
          EXPECT_EQ(from_file[c], from_memory[c]) << "channel " << channel << " column " << c;
        } else {
          // Snapped edges move a column by less than a block: its range overlaps.
          EXPECT_LE(from_file[c].min, from_memory[c].max + 5.0f);
          EXPECT_GE(from_file[c].max, from_memory[c].min - 5.0f);
        }
      }
    }
  }
}

// Half a block a column or more is answered from the overview alone, however long the
// recording: no raw sample is read (an hour across 1600 columns read every chunk before).
TEST_F(SourcePair, HalfABlockAColumnReadsNoRawSample) {
  const FileSampleSource file(path);
  const int64_t before = file.chunks_read();
  file.minmax_over_time(0, file.start_time(), file.end_time(),
                        static_cast<int>(file.sample_count() / 200));  // 200 samples a column
  EXPECT_EQ(file.chunks_read(), before);
  file.minmax_over_time(0, file.start_time(), file.end_time(),
                        static_cast<int>(file.sample_count() / 100));  // 100: raw edges
  EXPECT_GT(file.chunks_read(), before);
}

TEST_F(SourcePair, ValuesAtAnInstantAndSampleRangesMatchTheRecording) {
  const FileSampleSource file(path);
  const Stream& stream = recording.streams.front();
  for (int64_t index : {int64_t{0}, int64_t{8191}, int64_t{8192}, int64_t{49'999}}) {
    const std::vector<float> values = file.values_at(index);
    for (int channel = 0; channel < 5; ++channel)
      EXPECT_EQ(values[channel], stream.samples(index, channel)) << index;
  }
  EXPECT_TRUE(std::isnan(file.values_at(50'000)[0]));  // beyond the data: no value
  EXPECT_EQ(file.index_at(2.0 + 123.456), 12345);
  const int channels[] = {4, 1};
  const SampleMatrix range = file.read(channels, 8000, 500);  // straddles a chunk edge
  EXPECT_EQ(range.col(0), stream.samples.col(4).segment(8000, 500));
  EXPECT_TRUE(std::isnan(file.read(channels, 777, 1)(0, 1)));
  EXPECT_THROW(file.read(channels, 49'900, 200), Error);
}

TEST_F(SourcePair, ZoomedOutViewsReadNoRawSamplesAndZoomedInReadOnlyTheirChunks) {
  const FileSampleSource file(path);
  EXPECT_EQ(file.chunk_samples(), 8192);
  file.minmax_over_time(0, file.start_time(), file.end_time(), 100);  // 500 samples a column
  for (int channel = 0; channel < 5; ++channel) file.channel_extent(channel);
  EXPECT_EQ(file.chunks_read(), 0);
  file.minmax_over_time(2, 100.0, 101.0, 800);  // 100 samples inside one chunk
  EXPECT_EQ(file.chunks_read(), 1);
  file.values_at(100);  // one chunk row of every channel
  EXPECT_EQ(file.chunks_read(), 1 + 5);
}

TEST_F(SourcePair, TheChunkCacheStaysWithinItsLimit) {
  FileSourceOptions options;
  options.cache_bytes = 6 * 8192 * 4;  // six chunks
  const FileSampleSource file(path, options);
  for (int64_t index = 0; index < 50'000; index += 4000) file.values_at(index);
  const int64_t pyramids = FileSampleSource(path).memory_bytes();
  EXPECT_LE(file.memory_bytes() - pyramids, options.cache_bytes);
  // Evicted chunks are read again and still give the same values.
  EXPECT_EQ(file.values_at(10)[3], recording.streams.front().samples(10, 3));
}

TEST_F(SourcePair, AChunkRowOverPartlyCachedChannelsKeepsTheCacheConsistent) {
  FileSourceOptions options;
  options.cache_bytes = 8 * 8192 * 4;
  const FileSampleSource file(path, options);
  const int some[] = {0, 1};
  file.read(some, 100, 10);  // channels 0 and 1 of chunk 0 cached
  file.values_at(200);       // the chunk row of all five: 0 and 1 again
  const int64_t pyramids = FileSampleSource(path).memory_bytes();
  EXPECT_EQ(file.memory_bytes() - pyramids, 5 * 8192 * 4);
  for (int64_t index = 0; index < 50'000; index += 3000) file.values_at(index);  // evicts
  EXPECT_LE(file.memory_bytes() - pyramids, options.cache_bytes);
  EXPECT_EQ(file.values_at(200)[1], recording.streams.front().samples(200, 1));
}

TEST_F(SourcePair, RestScaleOfALongSourceComesFromBucketsNearTheExactOne) {
  const FileSampleSource file(path);
  const std::vector<int> columns = {0, 1, 2, -1};
  const RestScale approximate = rest_scale(file, columns);
  const RestScale exact = rest_scale(recording.streams.front(), columns);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(approximate.rest[k], exact.rest[k], 0.5f) << k;
    // Unit noise: the exact band is 3 sigma; half the range of 256 samples is ~2.8 sigma.
    EXPECT_NEAR(approximate.noise_band[k], exact.noise_band[k], 1.0f) << k;
  }
  EXPECT_TRUE(std::isnan(approximate.rest[3]));
  EXPECT_NEAR(approximate.max_change, 40.0, 8.0);  // the bumps
  EXPECT_EQ(file.chunks_read(), 0);                // from the overview alone
}

TEST(SampleSource, AnUnreadableFileIsNamed) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("broken.h5");
  std::ofstream(path) << "not an HDF5 file";
  try {
    FileSampleSource source(path);
    FAIL() << "opened a broken file";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("broken.h5"), std::string::npos) << error.what();
  }
}

TEST(SampleSource, MemorySourceTimeHelpersFollowTheRate) {
  Stream stream;
  stream.name = "s";
  stream.rate_hz = 10.0;
  stream.start_time = 1.0;
  stream.channels = {"a"};
  stream.samples = SampleMatrix::Constant(20, 1, 3.0f);
  const MemorySampleSource source(std::move(stream));
  EXPECT_DOUBLE_EQ(source.duration(), 2.0);
  EXPECT_EQ(source.index_at(1.25), 2);
  EXPECT_EQ(source.first_index_at_or_after(1.25), 3);
  EXPECT_EQ(source.index_at(-5.0), 0);
  EXPECT_EQ(source.index_at(99.0), 19);
  EXPECT_DOUBLE_EQ(source.time_of(3), 1.3);
}

}  // namespace
}  // namespace tactile

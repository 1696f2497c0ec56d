// A recording file that goes away while it is open (a network share that hangs, a USB stick
// pulled: reads fail with EIO, the file moved): the source answers from what it holds, with
// gaps for the rest, says why, never holds its caller past its budget, and reopens the file
// when it is back. Faults are injected where a failing disk would put them: in the read.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <thread>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/signal/sample_source.h"

namespace tactile {
namespace {

std::string write_away_recording(const testing::TemporaryDirectory& directory) {
  Recording recording;
  recording.id = "away";
  recording.layout_id = "grid:2x2";
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = 1000.0;
  stream.channels = {"a", "b", "c", "d"};
  stream.units = {"V", "V", "V", "V"};
  stream.samples = SampleMatrix(100000, 4);
  for (Eigen::Index row = 0; row < stream.samples.rows(); ++row)
    for (Eigen::Index column = 0; column < 4; ++column)
      stream.samples(row, column) = static_cast<float>(row * 4 + column);
  recording.streams.push_back(stream);
  const std::string path = directory.file("away.h5");
  write_recording(path, recording);
  return path;
}

bool all_gaps(const SampleMatrix& samples) { return samples.array().isNaN().all(); }

// Reads that fail as on a pulled USB stick while `failing` is set; the file looked for again
// at every read.
FileSourceOptions failing_reads(const std::string& path,
                                std::shared_ptr<std::atomic<bool>> failing) {
  FileSourceOptions options;
  options.retry_seconds = 0.0;
  options.before_read = [failing, path] {
    if (failing->load()) throw Error(path, "cannot read the file: Input/output error");
  };
  return options;
}

TEST(FileSourceFaults, AReadThatHangsLeavesTheCallerWithinItsBudgetAndTheFileReturns) {
  testing::TemporaryDirectory directory;
  const std::string path = write_away_recording(directory);
  auto hold = std::make_shared<std::atomic<bool>>(false);
  FileSourceOptions options;
  options.read_budget_seconds = 0.05;
  options.retry_seconds = 0.0;
  options.before_read = [hold] {
    while (hold->load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  FileSampleSource source(path, options);
  const std::vector<int> channel{1};
  EXPECT_EQ(source.read(channel, 10, 1)(0, 0), 41.0f);  // cached from here on
  EXPECT_EQ(source.unavailable(), "");
  hold->store(true);
  // Uncached samples: gaps, at once; cached ones: as they are.
  EXPECT_TRUE(all_gaps(source.read(channel, 90000, 100)));
  EXPECT_NE(source.unavailable().find("does not answer"), std::string::npos)
      << source.unavailable();
  EXPECT_EQ(source.read(channel, 10, 1)(0, 0), 41.0f);
  EXPECT_TRUE(all_gaps(source.read(channel, 80000, 10)));  // the reader is still stuck: no wait
  hold->store(false);
  // The stuck read ends; the next look finds the file answering again.
  for (int tries = 0; tries < 1000 && !source.unavailable().empty(); ++tries)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_EQ(source.unavailable(), "");
  EXPECT_EQ(source.read(channel, 90000, 1)(0, 0), 90000.0f * 4 + 1);
}

TEST(FileSourceFaults, ASourceClosedWhileAReadHangsDoesNotWaitForIt) {
  testing::TemporaryDirectory directory;
  const std::string path = write_away_recording(directory);
  auto hold = std::make_shared<std::atomic<bool>>(true);
  FileSourceOptions options;
  options.read_budget_seconds = 0.02;
  options.before_read = [hold] {
    while (hold->load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  {
    FileSampleSource source(path, options);
    const std::vector<int> channel{0};
    EXPECT_TRUE(all_gaps(source.read(channel, 0, 10)));
  }                    // closed with its reader stuck
  hold->store(false);  // the stuck read ends by itself, later
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

TEST(FileSourceFaults, ReadsThatFailWithAnIoErrorShowTheCacheAndSayWhyUntilTheFileIsBack) {
  testing::TemporaryDirectory directory;
  const std::string path = write_away_recording(directory);
  auto failing = std::make_shared<std::atomic<bool>>(false);
  const FileSourceOptions options = failing_reads(path, failing);
  FileSampleSource source(path, options);
  const std::vector<int> both{0, 3};
  const SampleMatrix before = source.read(both, 100, 50);
  failing->store(true);
  EXPECT_TRUE(source.read(both, 100, 50).isApprox(before, 0.0f));
  EXPECT_TRUE(all_gaps(source.read(both, 70000, 50)));
  EXPECT_NE(source.unavailable().find("Input/output error"), std::string::npos)
      << source.unavailable();
  EXPECT_TRUE(source.damage().empty());  // not damage: nothing is named as broken
  // values_at, the skin's read, is a gap too and does not throw.
  EXPECT_TRUE(std::isnan(source.values_at(60000)[2]));
  // The stick is back.
  failing->store(false);
  EXPECT_EQ(source.unavailable(), "");
  EXPECT_EQ(source.read(both, 70000, 1)(0, 1), 70000.0f * 4 + 3);
}

TEST(FileSourceFaults, AFileMovedAwayIsLookedForAgainAndReopenedWhereItWas) {
  testing::TemporaryDirectory directory;
  const std::string path = write_away_recording(directory);
  auto failing = std::make_shared<std::atomic<bool>>(false);
  const FileSourceOptions options = failing_reads(path, failing);
  FileSampleSource source(path, options);
  const std::vector<int> channel{2};
  failing->store(true);
  EXPECT_TRUE(all_gaps(source.read(channel, 50000, 5)));
  failing->store(false);
  std::filesystem::rename(path, path + ".moved");
  EXPECT_NE(source.unavailable(), "");  // gone from its place: not reopened
  EXPECT_TRUE(all_gaps(source.read(channel, 50000, 5)));
  std::filesystem::rename(path + ".moved", path);
  EXPECT_EQ(source.unavailable(), "");
  EXPECT_EQ(source.read(channel, 50000, 1)(0, 0), 50000.0f * 4 + 2);
}

TEST(FileSourceFaults, DamagedBytesAreStillDamageNotAnAbsence) {
  testing::TemporaryDirectory directory;
  const std::string path = write_away_recording(directory);
  FileSourceOptions options;
  options.before_read = [path] {
    throw Error(path + ":/streams/skin/samples", "data error detected by fletcher32 checksum");
  };
  FileSampleSource source(path, options);
  const std::vector<int> channel{0};
  EXPECT_THROW(source.read(channel, 0, 10), Error);
  EXPECT_EQ(source.unavailable(), "");
}

}  // namespace
}  // namespace tactile

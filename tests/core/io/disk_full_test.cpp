// A disk that fills while a recording is written: the recorder warns while minutes are left,
// stops with a whole file before the disk is full, and a write that fails anyway leaves every
// flushed sample readable in a file that verifies, without HDF5's error stack on stderr.
// `tactile repair` mends the rest. The file-size limit (ulimit -f) stands in for a full disk:
// the same failing write(), no mount needed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/disk_room.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/recording_writer.h"
#include "tactile/live/live_recorder.h"
#include "tactile/verify/repair.h"
#include "tactile/verify/verify.h"

namespace tactile {
namespace {

constexpr int kFullChannels = 24;
constexpr double kFullRate = 500.0;

// Values that do not compress (the file grows as a real skin's does), the same for a row
// whatever writes or reads it.
float full_value(int64_t row, int channel) {
  uint64_t x = static_cast<uint64_t>(row) * 0x9E3779B97F4A7C15ull +
               static_cast<uint64_t>(channel) * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 31;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 29;
  return static_cast<float>(x % 100000) / 100.0f;
}

SampleMatrix full_rows(int64_t first, int64_t count) {
  SampleMatrix rows(count, kFullChannels);
  for (int64_t row = 0; row < count; ++row)
    for (int channel = 0; channel < kFullChannels; ++channel)
      rows(row, channel) = full_value(first + row, channel);
  return rows;
}

std::vector<std::string> full_channels() {
  std::vector<std::string> names;
  for (int channel = 0; channel < kFullChannels; ++channel)
    names.push_back("c" + std::to_string(channel));
  return names;
}

struct FilledRun {
  int64_t flushed = 0;  // as the writer last reported
  std::string error;    // the writer's error message
  std::string stderr_text;
};

// A child process, its files limited to `limit` bytes, appends a tenth of a second at a time
// from a thread of its own (as a live recorder does) until a write fails.
FilledRun fill_until_it_fails(const std::string& path, int64_t limit) {
  const std::string errors = path + ".stderr", report = path + ".report";
  const pid_t child = fork();
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);
    FILE* captured = std::freopen(errors.c_str(), "w", stderr);
    if (captured == nullptr) _exit(3);
    int64_t flushed = 0;
    std::string message = "no error";
    std::thread writer_thread([&] {
      try {
        RecordingWriter writer(path, "filled", "grid:4x6", {}, "skin", kFullRate, 0.0,
                               full_channels(), std::vector<std::string>(kFullChannels, "V"));
        struct rlimit size {
          static_cast<rlim_t>(limit), static_cast<rlim_t>(limit)
        };
        setrlimit(RLIMIT_FSIZE, &size);
        for (int64_t first = 0; first < 100000000; first += 50) {
          writer.append(full_rows(first, 50));
          flushed = writer.samples_on_disk();
        }
      } catch (const std::exception& error) {
        message = error.what();
      }
    });
    writer_thread.join();
    std::ofstream out(report);
    out << flushed << "\n" << message;
    out.close();
    std::fflush(stderr);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  FilledRun run;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the writer crashed";
  std::istringstream in(testing::read_text(report));
  in >> run.flushed;
  in.get();
  std::getline(in, run.error, '\0');
  run.stderr_text = testing::read_text(errors);
  return run;
}

TEST(DiskFull, AFailedWriteKeepsEveryFlushedSampleInAFileThatVerifies) {
  testing::TemporaryDirectory directory;
  for (const int64_t limit : {int64_t{90000}, int64_t{150000}, int64_t{420000}}) {
    const std::string path = directory.file("full-" + std::to_string(limit) + ".h5");
    const FilledRun run = fill_until_it_fails(path, limit);
    SCOPED_TRACE("limit " + std::to_string(limit));
    EXPECT_GT(run.flushed, 0);
    // One line that says what happened; HDF5's own stack never reaches the terminal.
    EXPECT_NE(run.error.find("File too large"), std::string::npos) << run.error;
    EXPECT_EQ(run.error.find('\n'), std::string::npos) << run.error;
    EXPECT_EQ(run.stderr_text, "");
    // Under a file-size limit the writer cannot even pad its file to the end HDF5 declared
    // (on a full disk it can: the padding is sparse); repair does, and leaves a whole file
    // alone.
    repair_recording(path);
    const std::vector<FileProblem> problems = verify_recording(path);
    EXPECT_TRUE(problems.empty()) << problems.front().message;
    RecordingFile file(path);
    const int64_t count = file.stream("skin").sample_count;
    ASSERT_GE(count, run.flushed);
    const SampleMatrix samples = file.read("skin", 0, run.flushed);
    EXPECT_TRUE(samples.isApprox(full_rows(0, run.flushed), 0.0f));
    // What a failed flush claimed is a gap at most, never numbers that were not sent.
    if (count > run.flushed) {
      const SampleMatrix after = file.read("skin", run.flushed, count - run.flushed);
      const SampleMatrix sent = full_rows(run.flushed, count - run.flushed);
      for (Eigen::Index row = 0; row < after.rows(); ++row)
        for (Eigen::Index column = 0; column < after.cols(); ++column)
          EXPECT_TRUE(std::isnan(after(row, column)) || after(row, column) == sent(row, column));
    }
  }
}

TEST(DiskFull, RepairMakesAFailedWritersFileWholeAndSaysWhatWasCut) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("full.h5");
  const FilledRun run = fill_until_it_fails(path, 150000);
  const RepairReport report = repair_recording(path);
  if (RecordingFile(report.repaired ? report.kept_original : path).cut_off()) {
    EXPECT_TRUE(report.repaired);
  }
  if (!report.repaired) GTEST_SKIP() << "this failure left a whole file";
  EXPECT_TRUE(std::filesystem::exists(report.kept_original));
  EXPECT_TRUE(verify_recording(path).empty());
  RecordingFile file(path);
  EXPECT_FALSE(file.cut_off());
  const int64_t count = file.stream("skin").sample_count;
  EXPECT_GE(count, run.flushed);
  EXPECT_TRUE(
      file.read("skin", 0, count).topRows(run.flushed).isApprox(full_rows(0, run.flushed), 0.0f));
  const std::vector<std::string> lines = repair_lines(path, report);
  EXPECT_NE(std::find_if(
                lines.begin(), lines.end(),
                [](const std::string& line) {
                  return line.find("rebuilt: /streams/skin: the overview and the sample count") !=
                         std::string::npos;
                }),
            lines.end());
  // Repairing a whole file does nothing.
  EXPECT_FALSE(repair_recording(path).repaired);
}

TEST(DiskFull, RepairNamesTheChannelOfAChunkThatFailsItsChecksumAndKeepsTheRest) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("damaged.h5");
  {
    RecordingWriter writer(path, "damaged", "grid:4x6", {}, "skin", kFullRate, 0.0, full_channels(),
                           std::vector<std::string>(kFullChannels, "V"));
    writer.append(full_rows(0, 4000));
    writer.finish();
  }
  // Flip bytes in the middle of the file: some chunk's checksum fails.
  const auto size = static_cast<std::streamoff>(std::filesystem::file_size(path));
  {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(size / 2);
    const char garbage[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    file.write(garbage, sizeof garbage);
  }
  ASSERT_FALSE(verify_recording(path).empty());
  const RepairReport report = repair_recording(path);
  ASSERT_TRUE(report.repaired);
  EXPECT_TRUE(verify_recording(path).empty());
  ASSERT_FALSE(report.lost.empty());
  EXPECT_NE(report.lost.front().find("unreadable"), std::string::npos) << report.lost.front();
  EXPECT_NE(report.lost.front().find("now a gap"), std::string::npos) << report.lost.front();
  // Everything else is as it was written.
  RecordingFile file(path);
  const SampleMatrix samples = file.read("skin", 0, file.stream("skin").sample_count);
  const SampleMatrix sent = full_rows(0, samples.rows());
  int64_t same = 0, gaps = 0;
  for (Eigen::Index row = 0; row < samples.rows(); ++row)
    for (Eigen::Index column = 0; column < samples.cols(); ++column) {
      if (std::isnan(samples(row, column)))
        ++gaps;
      else if (samples(row, column) == sent(row, column))
        ++same;
    }
  EXPECT_GT(gaps, 0);
  EXPECT_EQ(same + gaps, samples.size());
}

TEST(DiskFull, RepairOfAFileThatDoesNotOpenSaysSoAndLeavesItAlone) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("garbage.h5");
  std::ofstream(path) << "not a recording";
  try {
    repair_recording(path);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cannot be repaired"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(testing::read_text(path), "not a recording");
  EXPECT_EQ(directory.entry_count(), 1);
}

// A live source fed by hand, a tenth of a second at a time.
void feed_tenth(LiveSampleSource& source, int64_t& next) {
  for (int k = 0; k < 50; ++k, ++next) {
    std::vector<float> values(kFullChannels);
    for (int channel = 0; channel < kFullChannels; ++channel)
      values[static_cast<size_t>(channel)] = full_value(next, channel);
    source.add(static_cast<double>(next) / kFullRate, values);
  }
}

TEST(DiskFull, TheRecorderWarnsThenStopsWithAWholeFileBeforeTheDiskIsFull) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("live.h5");
  SourceInfo info;
  info.layout_id = "grid:4x6";
  info.stream = "skin";
  info.rate_hz = kFullRate;
  info.channels = full_channels();
  info.units.assign(kFullChannels, "V");
  LiveSampleSource source(info, 100000);
  int64_t next = 0;
  feed_tenth(source, next);
  // A disk of 1.5 MB: what the file has not taken of it is the room.
  constexpr int64_t kDisk = 1500000;
  LiveRecorderOptions options;
  options.pretrigger_seconds = 10.0;
  options.lag_seconds = 0.0;
  options.warn_minutes = 0.05;  // 3 s
  // Fed as fast as the test runs, but as a device would send it: a tenth of a second each.
  auto now = std::make_shared<double>(0.0);
  options.clock = [now] { return *now; };
  options.room = [](const std::string& file) {
    std::error_code error;
    const auto size = std::filesystem::file_size(file, error);
    return kDisk - (error ? int64_t{0} : static_cast<int64_t>(size));
  };
  LiveRecorder recorder(path, source, options);
  bool seen_plenty = false, seen_low = false;
  for (int tenth = 0; tenth < 4000 && !recorder.stopped(); ++tenth) {
    feed_tenth(source, next);
    *now += 0.1;
    recorder.take(source);
    // The writer thread has its own pace; wait until it caught up with what was taken.
    for (int wait = 0; wait < 2000 && recorder.samples_on_disk() + 600 < recorder.samples_taken() &&
                       !recorder.stopped();
         ++wait)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const RecorderRoom room = recorder.room();
    if (room.minutes_left > 0.0 && !room.low) seen_plenty = true;
    if (room.low && room.stopped.empty()) seen_low = true;
  }
  ASSERT_TRUE(recorder.stopped());
  EXPECT_TRUE(seen_plenty);
  EXPECT_TRUE(seen_low);
  EXPECT_NE(recorder.room().stopped.find("stopped recording"), std::string::npos);
  EXPECT_EQ(recorder.error(), "");
  EXPECT_NO_THROW(recorder.finish(source));
  EXPECT_LE(static_cast<int64_t>(std::filesystem::file_size(path)), kDisk);
  EXPECT_TRUE(verify_recording(path).empty());
  RecordingFile file(path);
  EXPECT_FALSE(file.cut_off());
  const int64_t count = file.stream("skin").sample_count;
  EXPECT_GT(count, 0);
  EXPECT_TRUE(file.read("skin", 0, count).isApprox(full_rows(0, count), 0.0f));
}

TEST(DiskFull, RecordingIsRefusedOnADiskWithNoRoomLeft) {
  testing::TemporaryDirectory directory;
  SourceInfo info;
  info.stream = "skin";
  info.rate_hz = kFullRate;
  info.channels = full_channels();
  info.units.assign(kFullChannels, "V");
  LiveSampleSource source(info, 1000);
  LiveRecorderOptions options;
  options.room = [](const std::string&) { return int64_t{1000}; };
  try {
    LiveRecorder recorder(directory.file("none.h5"), source, options);
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("too little to record"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(directory.entry_count(), 0);
}

TEST(DiskFull, RoomToGrowHonoursTheFileSizeLimit) {
  testing::TemporaryDirectory directory;
  EXPECT_GT(room_to_grow(directory.path().string()), 0);
  EXPECT_EQ(byte_text(999), "999 B");
  EXPECT_EQ(byte_text(1500000), "1.5 MB");
  const pid_t child = fork();
  if (child == 0) {
    struct rlimit size {
      100000, 100000
    };
    setrlimit(RLIMIT_FSIZE, &size);
    _exit(room_to_grow(directory.file("new.h5")) == 100000 ? 0 : 1);
  }
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

}  // namespace
}  // namespace tactile

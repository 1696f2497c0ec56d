// A recording written as it happens: the same samples as write_recording would store, an
// ordinary file once finished, never written over another file, and after kill -9 at any
// moment a file that opens with everything up to the last flush.
#include "tactile/io/recording_writer.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "io_test_files.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/verify/verify.h"

namespace tactile {
namespace {

SampleMatrix ramp(int64_t first, int64_t count, int channels) {
  SampleMatrix rows(count, channels);
  for (int64_t row = 0; row < count; ++row)
    for (int channel = 0; channel < channels; ++channel)
      rows(row, channel) = static_cast<float>((first + row) * 10 + channel);
  return rows;
}

std::unique_ptr<RecordingWriter> writer_at(const std::string& path, double rate = 250.0) {
  return std::make_unique<RecordingWriter>(path, "live-1", "grid:2x2", Metadata{{"subject", "s1"}},
                                           "skin", rate, 12.5,
                                           std::vector<std::string>{"c0", "c1", "c2", "c3"},
                                           std::vector<std::string>{"V", "V", "V", "V"});
}

TEST(RecordingWriter, WritesWhatWasAppendedAsAnOrdinaryRecording) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("live.h5");
  auto writer = writer_at(path);
  int64_t first = 0;
  for (int64_t count : {1, 7, 300, 256, 1000, 3}) {
    SampleMatrix rows = ramp(first, count, 4);
    if (first == 8) rows.row(0).setConstant(NAN);  // a gap stays a gap
    writer->append(rows);
    first += count;
  }
  writer->finish();
  RecordingFile file(path);
  EXPECT_FALSE(file.cut_off());
  EXPECT_EQ(file.format_version(), kRecordingFormatVersion);
  EXPECT_EQ(file.layout_id(), "grid:2x2");
  EXPECT_EQ(file.metadata().at("subject"), "s1");
  const StreamInfo& info = file.stream("skin");
  EXPECT_EQ(info.sample_count, first);
  EXPECT_DOUBLE_EQ(info.start_time, 12.5);
  const Recording recording = file.read_all();
  const SampleMatrix expected = ramp(0, first, 4);
  const SampleMatrix& got = recording.streams.front().samples;
  EXPECT_TRUE(std::isnan(got(8, 2)));
  for (int64_t row = 0; row < first; ++row)
    if (row != 8) {
      ASSERT_EQ(got.row(row), expected.row(row)) << "sample " << row;
    }
  // The overview agrees with the samples (verify reads every chunk and checks it).
  const std::vector<FileProblem> problems = verify_recording(path);
  EXPECT_TRUE(problems.empty()) << problems.front().message;
}

TEST(RecordingWriter, NeverWritesOverAFile) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("taken.h5");
  { std::ofstream(path) << "precious"; }
  EXPECT_THROW(writer_at(path), Error);
  std::ifstream in(path);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "precious");
}

TEST(RecordingWriter, IsReadableWhileItIsWritten) {
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("growing.h5");
  auto writer = writer_at(path);
  writer->append(ramp(0, 600, 4));  // 2.4 s at 250 Hz: flushed
  // (In this process HDF5 shares the open file; another process sees it cut_off().)
  RecordingFile file(path);
  EXPECT_GE(file.stream("skin").sample_count, 500);
  EXPECT_EQ(file.read("skin", 100, 1)(0, 3), 1003.0f);
}

TEST(RecordingWriter, AKilledWriterLeavesAFileWithAllButTheLastSecond) {
  // A child appends a second of samples every 20 ms (50 s of samples a second, flushed at
  // each) and is killed at a different moment each round.
  testing::TemporaryDirectory directory;
  for (int round = 0; round < 8; ++round) {
    const std::string path = directory.file("killed-" + std::to_string(round) + ".h5");
    int pipe_ends[2];
    ASSERT_EQ(pipe(pipe_ends), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(pipe_ends[0]);
      auto writer = writer_at(path);
      for (int64_t second = 0;; ++second) {
        writer->append(ramp(second * 250, 250, 4));
        const int64_t on_disk = writer->samples_on_disk();
        if (write(pipe_ends[1], &on_disk, sizeof on_disk) != sizeof on_disk) _exit(1);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
    close(pipe_ends[1]);
    std::this_thread::sleep_for(std::chrono::milliseconds(150 + 37 * round));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    int64_t reported = 0, value = 0;
    while (read(pipe_ends[0], &value, sizeof value) == sizeof value) reported = value;
    close(pipe_ends[0]);
    RecordingFile file(path);
    EXPECT_TRUE(file.cut_off());
    const int64_t count = file.stream("skin").sample_count;
    // Everything the writer had reported flushed is there (it may have flushed one more).
    EXPECT_GE(count, reported) << "round " << round;
    const Recording recording = file.read_all();
    const SampleMatrix& samples = recording.streams.front().samples;
    ASSERT_EQ(samples.rows(), count);
    if (count > 0) {
      EXPECT_EQ(samples(count - 1, 1), static_cast<float>((count - 1) * 10 + 1));
    }
    // Every chunk and the overview check out as they are.
    const std::vector<FileProblem> problems = verify_recording(path);
    EXPECT_TRUE(problems.empty()) << problems.front().message;
  }
}

TEST(RecordingWriter, AKilledWritersFileIsCutOffHoweverOftenItIsOpened) {
  // The second open of a file this process has open already shares HDF5's file, so it
  // never sees the open-for-write flag; it must still read the file as cut off (and accept
  // samples a flush ahead of the overview, as a kill between the two leaves them).
  testing::TemporaryDirectory directory;
  const std::string path = directory.file("killed.h5");
  int pipe_ends[2];
  ASSERT_EQ(pipe(pipe_ends), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(pipe_ends[0]);
    auto writer = writer_at(path);
    writer->append(ramp(0, 500, 4));
    const char done = 1;
    if (write(pipe_ends[1], &done, 1) != 1) _exit(1);
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  close(pipe_ends[1]);
  char done = 0;
  ASSERT_EQ(read(pipe_ends[0], &done, 1), 1);
  close(pipe_ends[0]);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  RecordingFile first(path);
  RecordingFile second(path);
  EXPECT_TRUE(first.cut_off());
  EXPECT_TRUE(second.cut_off());
  const std::vector<FileProblem> problems = verify_recording(path);
  EXPECT_TRUE(problems.empty()) << problems.front().message;
}

TEST(RecordingWriter, RefusesAWrongSampleWidth) {
  testing::TemporaryDirectory directory;
  auto writer = writer_at(directory.file("w.h5"));
  EXPECT_THROW(writer->append(ramp(0, 3, 5)), Error);
  writer->finish();
  EXPECT_THROW(writer->append(ramp(0, 3, 4)), Error);
}

}  // namespace
}  // namespace tactile

// VideoFile reads back exactly the frames VideoWriter wrote: each frame's coded number is its
// index, at every time, in any order, at constant and variable rates, in three containers.
#include "tactile/video/video_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/video/video_writer.h"
#include "temp_folder.h"
#include "video_test_files.h"

namespace tactile {
namespace {

using test::number_in_frame;
using test::TempFolder;
using test::write_numbered_video;

// The stored times' resolution: Matroska keeps milliseconds, AVI whole frames, MP4 the
// writer's 1/(rate*100) s.
double time_tolerance(const std::string& path) {
  if (path.ends_with(".mkv")) return 0.001 + 1e-9;
  return 1.0 / 3000 + 1e-9;
}

// Every promise of the header about where frames are and what they show, for a file written
// with frame i showing i at times[i].
void expect_frames_read_back(const std::string& path, const std::vector<double>& times) {
  SCOPED_TRACE(path);
  VideoFile video(path);
  const VideoInfo& info = video.info();
  ASSERT_EQ(info.frame_count, static_cast<int64_t>(times.size()));
  ASSERT_EQ(video.frame_times().size(), times.size());
  EXPECT_EQ(info.width, 64);
  EXPECT_EQ(info.height, 48);
  const double tolerance = time_tolerance(path);
  for (size_t i = 0; i < times.size(); ++i)
    ASSERT_NEAR(video.frame_times()[i], times[i] - times[0], tolerance) << "frame " << i;
  const double last_interval = times.back() - times[times.size() - 2];
  EXPECT_GT(info.duration, times.back() - times[0]);
  EXPECT_LE(info.duration, times.back() - times[0] + 2 * last_interval);

  // The frame shown at a time: just after each frame's start and just before the next's.
  for (size_t i = 0; i < times.size(); ++i) {
    const double start = video.frame_times()[i];
    const double end = i + 1 < times.size() ? video.frame_times()[i + 1] : info.duration;
    EXPECT_EQ(video.frame_index_at(start), static_cast<int64_t>(i));
    EXPECT_EQ(video.frame_index_at(start + 0.25 * (end - start)), static_cast<int64_t>(i));
    EXPECT_EQ(video.frame_index_at(end - 1e-6), static_cast<int64_t>(i));
  }
  EXPECT_EQ(video.frame_index_at(-0.001), -1);
  EXPECT_EQ(video.frame_index_at(info.duration), -1);
  EXPECT_EQ(video.frame_index_at(info.duration + 5), -1);

  // Random order, then backwards, then forwards: each frame shows its own number.
  std::vector<int64_t> order(times.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int64_t>(i);
  std::mt19937 random(45);
  std::shuffle(order.begin(), order.end(), random);
  for (int64_t index : order) {
    const VideoFrame& frame = video.frame(index);
    ASSERT_EQ(frame.index, index);
    ASSERT_EQ(number_in_frame(frame), index) << "random order, frame " << index;
    ASSERT_NEAR(frame.time, video.frame_times()[index], 1e-12);
  }
  for (int64_t index = info.frame_count - 1; index >= 0; index -= 7)
    ASSERT_EQ(number_in_frame(video.frame(index)), index) << "backwards, frame " << index;
  for (int64_t index = 0; index < info.frame_count; ++index)
    ASSERT_EQ(number_in_frame(video.frame(index)), index) << "forwards, frame " << index;
}

TEST(VideoFileConstantRate, Mp4H264FramesReadBackExactlyInAnyOrder) {
  TempFolder folder;
  const std::string path = folder.file("h264.mp4");
  const std::vector<double> times = test::constant_rate_times(150, 30);
  write_numbered_video(path, times);
  expect_frames_read_back(path, times);
  VideoFile video(path);
  EXPECT_EQ(video.info().codec, video.info().codec == "h264" ? "h264" : "mpeg4");
  EXPECT_FALSE(video.info().variable_rate);
  EXPECT_NEAR(video.info().mean_rate, 30, 0.01);
  EXPECT_NEAR(video.info().duration, 5.0, 1e-3);
}

TEST(VideoFileConstantRate, MkvMjpegFramesReadBackExactlyInAnyOrder) {
  TempFolder folder;
  const std::string path = folder.file("mjpeg.mkv");
  const std::vector<double> times = test::constant_rate_times(90, 25);
  write_numbered_video(path, times, 64, 48, "mjpeg", 25);
  expect_frames_read_back(path, times);
  EXPECT_EQ(VideoFile(path).info().codec, "mjpeg");
}

TEST(VideoFileConstantRate, AviMjpegFramesReadBackExactlyInAnyOrder) {
  TempFolder folder;
  const std::string path = folder.file("mjpeg.avi");
  const std::vector<double> times = test::constant_rate_times(90, 30);
  EXPECT_EQ(write_numbered_video(path, times), "mjpeg");
  expect_frames_read_back(path, times);
  EXPECT_FALSE(VideoFile(path).info().variable_rate);
}

TEST(VideoFileVariableRate, Mp4H264FramesAtUnevenTimesReadBackExactly) {
  TempFolder folder;
  const std::string path = folder.file("vfr.mp4");
  const std::vector<double> times = test::variable_rate_times(120);
  write_numbered_video(path, times);
  expect_frames_read_back(path, times);
  VideoFile video(path);
  EXPECT_TRUE(video.info().variable_rate);
  EXPECT_NEAR(video.info().mean_rate, 119 / times.back(), 0.5);
}

TEST(VideoFileVariableRate, MkvMjpegFramesAtUnevenTimesReadBackExactly) {
  TempFolder folder;
  const std::string path = folder.file("vfr.mkv");
  const std::vector<double> times = test::variable_rate_times(60);
  write_numbered_video(path, times, 64, 48, "mjpeg");
  expect_frames_read_back(path, times);
  EXPECT_TRUE(VideoFile(path).info().variable_rate);
}

TEST(VideoFileVariableRate, FirstFrameIsAtZeroWhateverTimeItWasWrittenAt) {
  TempFolder folder;
  const std::string path = folder.file("late.mkv");
  std::vector<double> times = test::constant_rate_times(30, 30);
  for (double& time : times) time += 2.5;
  write_numbered_video(path, times, 64, 48, "mjpeg");
  VideoFile video(path);
  EXPECT_EQ(video.frame_times().front(), 0);
  EXPECT_NEAR(video.frame_times()[10], 10 / 30.0, 0.001);
  EXPECT_EQ(number_in_frame(video.frame(video.frame_index_at(0.34))), 10);
}

//---- Playing, cache, sizes

TEST(VideoFilePlaying, PlayingForwardDecodesEachFrameOnceWithoutSeeking) {
  TempFolder folder;
  const std::string path = folder.file("play.mp4");
  write_numbered_video(path, test::constant_rate_times(200, 30));  // key frames at 0, 60, ...
  VideoFile video(path);
  for (int64_t index = 0; index < 200; ++index)
    ASSERT_EQ(number_in_frame(video.frame(index)), index);
  EXPECT_EQ(video.seek_count(), 0);
  EXPECT_EQ(video.decoded_frame_count(), 200);

  // Twice the speed: every second frame, still no seek after the one back to the start.
  video.frame(0);
  const int64_t seeks = video.seek_count();
  EXPECT_EQ(seeks, 1);
  for (int64_t index = 0; index < 200; index += 2)
    ASSERT_EQ(number_in_frame(video.frame(index)), index);
  EXPECT_EQ(video.seek_count(), seeks);
}

TEST(VideoFilePlaying, FarJumpsSeekInsteadOfDecodingEverythingBetween) {
  TempFolder folder;
  const std::string path = folder.file("jump.mp4");
  write_numbered_video(path, test::constant_rate_times(300, 30));  // key frames every 60
  VideoFile video(path);
  const int64_t decoded = video.decoded_frame_count();
  ASSERT_EQ(number_in_frame(video.frame(250)), 250);
  EXPECT_EQ(video.seek_count(), 1);
  // From the key frame at 240 to 250, with a few frames of the decoder's delay at most.
  EXPECT_LE(video.decoded_frame_count() - decoded, 11 + 4);
}

TEST(VideoFileCache, ARecentFrameIsServedWithoutDecodingAgain) {
  TempFolder folder;
  const std::string path = folder.file("cache.mkv");
  write_numbered_video(path, test::constant_rate_times(40, 30), 64, 48, "mjpeg");
  VideoOpenOptions options;
  options.cache_frames = 3;
  VideoFile video(path, options);
  video.frame(20);
  video.frame(21);
  video.frame(22);
  const int64_t decoded = video.decoded_frame_count();
  EXPECT_EQ(number_in_frame(video.frame(20)), 20);
  EXPECT_EQ(number_in_frame(video.frame(22)), 22);
  EXPECT_EQ(video.decoded_frame_count(), decoded);
  video.frame(23);  // evicts 21, the least recently used
  const int64_t after = video.decoded_frame_count();
  EXPECT_EQ(number_in_frame(video.frame(21)), 21);
  EXPECT_GT(video.decoded_frame_count(), after);
}

TEST(VideoFileSize, MaxWidthScalesDownKeepingAspectAndEvenSizes) {
  TempFolder folder;
  const std::string path = folder.file("big.mp4");
  write_numbered_video(path, test::constant_rate_times(10, 30), 160, 120);
  VideoOpenOptions options;
  options.max_width = 50;
  VideoFile video(path, options);
  const VideoFrame& frame = video.frame(7);
  EXPECT_EQ(frame.width, 50);
  EXPECT_EQ(frame.height, 38);  // 37.5 to the nearest even
  EXPECT_EQ(frame.rgba.size(), size_t{50} * 38 * 4);
  EXPECT_EQ(number_in_frame(frame), 7);
  EXPECT_EQ(video.info().width, 160);
}

TEST(VideoFileSize, GreyFramesHoldOneBytePerPixel) {
  TempFolder folder;
  const std::string path = folder.file("grey.mp4");
  write_numbered_video(path, test::constant_rate_times(10, 30));
  VideoOpenOptions options;
  options.grey = true;
  VideoFile video(path, options);
  const VideoFrame& frame = video.frame(5);
  EXPECT_EQ(frame.rgba.size(), size_t{64} * 48);
  EXPECT_EQ(number_in_frame(frame), 5);
}

TEST(VideoFileSize, MaxWidthWiderThanTheVideoKeepsItsSize) {
  TempFolder folder;
  const std::string path = folder.file("small.mkv");
  write_numbered_video(path, test::constant_rate_times(4, 30), 64, 48, "mjpeg");
  VideoOpenOptions options;
  options.max_width = 960;
  VideoFile video(path, options);
  EXPECT_EQ(video.frame(1).width, 64);
  EXPECT_EQ(video.frame(1).height, 48);
}

//---- Times in words

TEST(VideoTimeProblem, SaysWhetherARecordingTimeFallsBeforeInsideOrPastTheVideo) {
  VideoInfo info;
  info.duration = 83.2;
  EXPECT_EQ(video_time_problem(info, 0, 12), "");
  EXPECT_EQ(video_time_problem(info, 83.1, 12), "");
  EXPECT_EQ(video_time_problem(info, -0.5, 12), "before the video (it starts at 12.0 s)");
  EXPECT_EQ(video_time_problem(info, 83.2, 12), "past the video's end (it ends at 95.2 s)");
}

}  // namespace
}  // namespace tactile

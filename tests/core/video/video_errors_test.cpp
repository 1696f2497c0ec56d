// A file that is not a readable video is refused with a tactile::Error naming the file and what
// is wrong; a damaged one gives the frames that remain and names the ones that do not decode.
// Nothing crashes (these tests also run under ASan: `make sanitize`).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/video/video_file.h"
#include "tactile/video/video_writer.h"
#include "temp_folder.h"
#include "video_test_files.h"

namespace tactile {
namespace {

using test::number_in_frame;
using test::refusal_of;
using test::TempFolder;
using test::write_numbered_video;

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Reads every frame the index holds; each either shows its own number or is refused with an
// Error naming the file and the frame. Returns how many read back.
int64_t frames_that_read_back(VideoFile& video, const std::string& path) {
  int64_t good = 0;
  for (int64_t index = 0; index < video.info().frame_count; ++index) {
    try {
      if (number_in_frame(video.frame(index)) == index) ++good;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("frame " + std::to_string(index)), std::string::npos)
          << error.what();
    }
  }
  return good;
}

TEST(VideoFileErrors, MissingFileIsNamed) {
  TempFolder folder;
  const std::string path = folder.file("absent.mp4");
  const std::string message = refusal_of([&] { VideoFile video(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST(VideoFileErrors, EmptyFileIsNamedEmpty) {
  TempFolder folder;
  const std::string path = folder.file("empty.mp4");
  write_bytes(path, "");
  const std::string message = refusal_of([&] { VideoFile video(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("empty"), std::string::npos) << message;
}

TEST(VideoFileErrors, TextFileNamedMp4IsNotAVideo) {
  TempFolder folder;
  const std::string path = folder.file("notes.mp4");
  write_bytes(path, "These are the notes of Tuesday's session.\nThe camera was off.\n");
  const std::string message = refusal_of([&] { VideoFile video(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("not a video"), std::string::npos) << message;
}

TEST(VideoFileErrors, FolderIsNotAVideo) {
  TempFolder folder;
  const std::string message = refusal_of([&] { VideoFile video(folder.path().string()); });
  EXPECT_NE(message.find(folder.path().string()), std::string::npos) << message;
  EXPECT_NE(message.find("folder"), std::string::npos) << message;
}

TEST(VideoFileErrors, Mp4CutInHalfIsRefusedNamingTheFile) {
  // An MP4 written front to back keeps its index at the end: without it nothing can be placed.
  TempFolder folder;
  const std::string path = folder.file("cut.mp4");
  write_numbered_video(path, test::constant_rate_times(60, 30));
  const std::string bytes = contents(path);
  write_bytes(path, bytes.substr(0, bytes.size() / 2));
  const std::string message = refusal_of([&] { VideoFile video(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(VideoFileErrors, MkvCutInHalfGivesTheFramesThatRemain) {
  TempFolder folder;
  const std::string path = folder.file("cut.mkv");
  write_numbered_video(path, test::constant_rate_times(60, 30), 64, 48, "mjpeg");
  const std::string bytes = contents(path);
  write_bytes(path, bytes.substr(0, bytes.size() / 2));
  VideoFile video(path);
  EXPECT_GT(video.info().frame_count, 20);
  EXPECT_LT(video.info().frame_count, 60);
  EXPECT_GE(frames_that_read_back(video, path), video.info().frame_count - 1);
}

TEST(VideoFileErrors, H264MkvCutInHalfGivesTheFramesThatRemain) {
  TempFolder folder;
  const std::string path = folder.file("cut264.mkv");
  write_numbered_video(path, test::constant_rate_times(120, 30));
  const std::string bytes = contents(path);
  write_bytes(path, bytes.substr(0, bytes.size() / 2));
  VideoFile video(path);
  EXPECT_LT(video.info().frame_count, 120);
  EXPECT_GT(frames_that_read_back(video, path), 10);
}

TEST(VideoFileErrors, FileCutAfterItsHeaderHasNoFrameToShow) {
  TempFolder folder;
  const std::string path = folder.file("header.mkv");
  write_numbered_video(path, test::constant_rate_times(30, 30), 64, 48, "mjpeg");
  write_bytes(path, contents(path).substr(0, 400));
  const std::string message = refusal_of([&] { VideoFile video(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(VideoFileErrors, RandomBytesInTheMiddleCrashNothing) {
  TempFolder folder;
  for (const std::string name : {"noise.mkv", "noise.mp4", "noise.avi"}) {
    const std::string path = folder.file(name);
    write_numbered_video(path, test::constant_rate_times(90, 30), 64, 48,
                         name.ends_with(".mp4") ? "" : "mjpeg");
    std::string bytes = contents(path);
    std::mt19937 random(7);
    for (size_t i = bytes.size() * 2 / 5; i < bytes.size() * 3 / 5; ++i)
      bytes[i] = static_cast<char>(random());
    write_bytes(path, bytes);
    try {
      VideoFile video(path);
      EXPECT_GT(frames_that_read_back(video, path), 0) << name;
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
}

//---- The writer's refusals

TEST(VideoWriterErrors, TimeThatDoesNotIncreaseIsRefusedNamingFileAndTime) {
  TempFolder folder;
  const std::string path = folder.file("back.mp4");
  VideoWriter writer(path, {64, 48, 30, "", 23});
  const std::vector<uint8_t> image = test::numbered_image(1, 64, 48);
  writer.write(image.data(), 0.0);
  writer.write(image.data(), 0.5);
  std::string message = refusal_of([&] { writer.write(image.data(), 0.5); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("0.5 s"), std::string::npos) << message;
  message = refusal_of([&] { writer.write(image.data(), 0.25); });
  EXPECT_NE(message.find("0.25 s"), std::string::npos) << message;
  writer.finish();
  EXPECT_EQ(VideoFile(path).info().frame_count, 2);
}

TEST(VideoWriterErrors, OddSizeIsRefused) {
  TempFolder folder;
  const std::string path = folder.file("odd.mp4");
  const std::string message = refusal_of([&] { VideoWriter writer(path, {65, 48, 30, "", 23}); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("even"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(VideoWriterErrors, UnknownExtensionAndUnknownCodecAreRefused) {
  TempFolder folder;
  std::string message = refusal_of([&] {
    VideoWriter writer(folder.file("clip.notavideo"), {64, 48, 30, "", 23});
  });
  EXPECT_NE(message.find("clip.notavideo"), std::string::npos) << message;
  message = refusal_of([&] {
    VideoWriter writer(folder.file("clip.mkv"), {64, 48, 30, "no-such-codec", 23});
  });
  EXPECT_NE(message.find("no-such-codec"), std::string::npos) << message;
}

TEST(VideoWriterErrors, FolderThatDoesNotExistIsNamed) {
  TempFolder folder;
  const std::string path = folder.file("missing/clip.mp4");
  const std::string message = refusal_of([&] { VideoWriter writer(path, {64, 48, 30, "", 23}); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

//---- The writer's choices

TEST(VideoWriter, ChoosesTheEncoderByExtension) {
  TempFolder folder;
  const std::vector<double> times = test::constant_rate_times(3, 30);
  const std::string mp4 = write_numbered_video(folder.file("a.mp4"), times);
  EXPECT_TRUE(mp4 == "libx264" || mp4 == "mpeg4") << mp4;
  EXPECT_EQ(write_numbered_video(folder.file("a.avi"), times), "mjpeg");
  EXPECT_EQ(write_numbered_video(folder.file("a.webm"), times), "libvpx-vp9");
  EXPECT_EQ(VideoFile(folder.file("a.webm")).info().codec, "vp9");
  EXPECT_EQ(number_in_frame(VideoFile(folder.file("a.webm")).frame(2)), 2);
}

TEST(VideoWriter, MpegFourPartTwoWritesReadableFrames) {
  TempFolder folder;
  const std::string path = folder.file("m4.mp4");
  write_numbered_video(path, test::constant_rate_times(20, 30), 64, 48, "mpeg4");
  VideoFile video(path);
  EXPECT_EQ(video.info().codec, "mpeg4");
  for (int64_t index : {19, 3, 11}) EXPECT_EQ(number_in_frame(video.frame(index)), index);
}

TEST(VideoWriter, FileIsFinishedWhenTheWriterGoesWithoutFinish) {
  TempFolder folder;
  const std::string path = folder.file("unfinished.mp4");
  {
    VideoWriter writer(path, {64, 48, 30, "", 23});
    for (int i = 0; i < 12; ++i) {
      const std::vector<uint8_t> image = test::numbered_image(i, 64, 48);
      writer.write(image.data(), i / 30.0);
    }
  }
  VideoFile video(path);
  EXPECT_EQ(video.info().frame_count, 12);
  EXPECT_EQ(number_in_frame(video.frame(11)), 11);
}

}  // namespace
}  // namespace tactile

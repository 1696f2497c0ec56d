// `tactile video attach|list|detach` end to end: a video checked before it is attached, the
// attachment kept beside the recording, listed, detached; bad values refused naming the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/video/attachments.h"
#include "video_test_files.h"

namespace tactile {
namespace {

using test::CommandResult;
using test::run_program;
using test::TempFolder;

class VideoCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // 12 s of a 100 Hz stream.
    Recording recording;
    recording.id = "session";
    recording.layout_id = "grid:2x2";
    Stream skin;
    skin.name = "skin";
    skin.rate_hz = 100;
    skin.channels = {"r0c0", "r0c1", "r1c0", "r1c1"};
    skin.units = {"", "", "", ""};
    skin.samples = SampleMatrix::Zero(1200, 4);
    recording.streams = {skin};
    write_recording(recording_, recording);
    std::filesystem::create_directories(folder_.path() / "videos");
    test::write_numbered_video(video_, test::constant_rate_times(300, 30));  // 10 s
  }

  CommandResult tactile(const std::string& arguments) {
    return run_program("tactile", arguments, folder_);
  }

  TempFolder folder_;
  const std::string recording_ = folder_.file("session.h5");
  const std::string video_ = folder_.file("videos/front.mp4");
};

TEST_F(VideoCli, AttachChecksTheVideoKeepsItRelativeAndSaysWhatItCovers) {
  const CommandResult result = tactile("video attach '" + recording_ + "' '" + video_ + "'");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("attached \"front\": videos/front.mp4, h264 64x48, 10.00 s, 300 "
                            "frames, 30.00 fps, offset 0 s"),
            std::string::npos)
      << result.out;
  // 10 s of video over a 12 s recording.
  EXPECT_NE(result.err.find("the video covers 0.0-10.0 s of the recording's 0-12.0 s"),
            std::string::npos)
      << result.err;
  const std::vector<VideoAttachment> attachments = read_attachments(recording_);
  ASSERT_EQ(attachments.size(), 1u);
  EXPECT_EQ(attachments[0].name, "front");
  EXPECT_EQ(attachments[0].path, "videos/front.mp4");
}

TEST_F(VideoCli, AttachWithNameOffsetAndRate) {
  const CommandResult result = tactile("video attach '" + recording_ + "' '" + video_ +
                                       "' --name cam-2 --offset 2.5 --rate 0.8");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::vector<VideoAttachment> attachments = read_attachments(recording_);
  ASSERT_EQ(attachments.size(), 1u);
  EXPECT_EQ(attachments[0].name, "cam-2");
  EXPECT_EQ(attachments[0].offset, 2.5);
  EXPECT_EQ(attachments[0].rate, 0.8);
  // 10 s of video at 0.8 video s per recording s lasts 12.5 s of the recording: from 2.5 s.
  EXPECT_NE(result.err.find("covers 2.5-15.0 s"), std::string::npos) << result.err;
}

TEST_F(VideoCli, AttachingTwiceNumbersTheSecondAndAnExplicitTakenNameIsRefused) {
  ASSERT_EQ(tactile("video attach '" + recording_ + "' '" + video_ + "'").exit_code, 0);
  ASSERT_EQ(tactile("video attach '" + recording_ + "' '" + video_ + "'").exit_code, 0);
  EXPECT_NE(find_attachment(read_attachments(recording_), "front-2"), nullptr);
  const CommandResult taken =
      tactile("video attach '" + recording_ + "' '" + video_ + "' --name front");
  EXPECT_EQ(taken.exit_code, 1);
  EXPECT_NE(taken.err.find("--name"), std::string::npos) << taken.err;
  EXPECT_EQ(read_attachments(recording_).size(), 2u);
}

TEST_F(VideoCli, BadVideosAndValuesAreRefusedAndNothingIsWritten) {
  test::write_script(folder_, "not a video\n", "notes.mp4");
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"'" + folder_.file("absent.mp4") + "'", "absent.mp4: no such file"},
      {"'" + folder_.file("notes.mp4") + "'", "notes.mp4: not a video"},
      {"'" + video_ + "' --rate 0", "--rate"},
      {"'" + video_ + "' --rate -1", "--rate"},
      {"'" + video_ + "' --offset nan", "--offset"},
      {"'" + video_ + "' --name 'a b'", "--name"},
  };
  for (const Case& bad : cases) {
    const CommandResult result = tactile("video attach '" + recording_ + "' " + bad.arguments);
    EXPECT_EQ(result.exit_code, 1) << bad.arguments;
    EXPECT_NE(result.err.find(bad.expected), std::string::npos)
        << bad.arguments << ": " << result.err;
    EXPECT_FALSE(std::filesystem::exists(attachments_path(recording_))) << bad.arguments;
  }
  const CommandResult no_recording =
      tactile("video attach '" + folder_.file("none.h5") + "' '" + video_ + "'");
  EXPECT_EQ(no_recording.exit_code, 1);
  EXPECT_NE(no_recording.err.find("none.h5"), std::string::npos) << no_recording.err;
}

TEST_F(VideoCli, ListShowsEachVideoAndWhichAreMissing) {
  ASSERT_EQ(tactile("video attach '" + recording_ + "' '" + video_ + "' --offset -1").exit_code, 0);
  const std::string other = folder_.file("side.mkv");
  test::write_numbered_video(other, test::constant_rate_times(30, 30), 64, 48, "mjpeg");
  ASSERT_EQ(tactile("video attach '" + recording_ + "' '" + other + "'").exit_code, 0);
  std::filesystem::remove(other);

  CommandResult result = tactile("video list '" + recording_ + "'");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("front  videos/front.mp4  offset -1 s  rate 1  h264, 10.00 s"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("side  side.mkv  offset 0 s  rate 1  missing"), std::string::npos)
      << result.out;

  result = tactile("video list '" + recording_ + "' --json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json listed = nlohmann::json::parse(result.out);
  ASSERT_EQ(listed["videos"].size(), 2u);
  EXPECT_EQ(listed["videos"][0]["name"], "front");
  EXPECT_EQ(listed["videos"][0]["offset"], -1.0);
  EXPECT_TRUE(listed["videos"][0]["problem"].is_null());
  EXPECT_EQ(listed["videos"][1]["problem"], "missing");
}

TEST_F(VideoCli, DetachRemovesTheAttachmentAndLeavesTheVideo) {
  ASSERT_EQ(tactile("video attach '" + recording_ + "' '" + video_ + "'").exit_code, 0);
  const CommandResult unknown = tactile("video detach '" + recording_ + "' back");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("no video named \"back\""), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("attached: front"), std::string::npos) << unknown.err;

  const CommandResult result = tactile("video detach '" + recording_ + "' front");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(std::filesystem::exists(attachments_path(recording_)));
  EXPECT_TRUE(std::filesystem::exists(video_));
  EXPECT_NE(tactile("video list '" + recording_ + "'").out.find("no videos attached"),
            std::string::npos);
}

TEST_F(VideoCli, EachCommandHasHelp) {
  for (const std::string command : {"attach", "list", "detach"}) {
    const CommandResult result = tactile("video " + command + " --help");
    EXPECT_EQ(result.exit_code, 0) << command;
    EXPECT_NE(result.out.find("RECORDING"), std::string::npos) << command << ": " << result.out;
  }
  EXPECT_NE(tactile("video attach --help").out.find("--offset"), std::string::npos);
}

}  // namespace
}  // namespace tactile

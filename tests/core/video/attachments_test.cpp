// Videos attached to a recording: kept in RECORDING.videos.json, relative paths that follow the
// folder, malformed entries named, the two-point sync's numbers.
#include "tactile/video/attachments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "temp_folder.h"

namespace tactile {
namespace {

using test::refusal_of;
using test::TempFolder;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(VideoAttachments, RoundTripKeepsEveryField) {
  TempFolder folder;
  const std::string recording = folder.file("session.h5");
  EXPECT_TRUE(read_attachments(recording).empty());
  const std::vector<VideoAttachment> written = {{"front", "front.mp4", 12.5, 1.0},
                                                {"camera-2", "/videos/side.mkv", -3.25, 1.0004}};
  write_attachments(recording, written);
  EXPECT_EQ(attachments_path(recording), recording + ".videos.json");
  EXPECT_TRUE(std::filesystem::exists(recording + ".videos.json"));
  const std::vector<VideoAttachment> read = read_attachments(recording);
  ASSERT_EQ(read.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(read[i].name, written[i].name);
    EXPECT_EQ(read[i].path, written[i].path);
    EXPECT_EQ(read[i].offset, written[i].offset);
    EXPECT_EQ(read[i].rate, written[i].rate);
  }
}

TEST(VideoAttachments, EmptyListRemovesTheFile) {
  TempFolder folder;
  const std::string recording = folder.file("session.h5");
  write_attachments(recording, {{"front", "front.mp4", 0, 1}});
  ASSERT_TRUE(std::filesystem::exists(attachments_path(recording)));
  write_attachments(recording, {});
  EXPECT_FALSE(std::filesystem::exists(attachments_path(recording)));
  EXPECT_TRUE(read_attachments(recording).empty());
  EXPECT_EQ(folder.entry_count(), 0);
}

TEST(VideoAttachments, PathInsideTheFolderIsKeptRelativeAndFollowsAMove) {
  TempFolder folder;
  const std::filesystem::path session = folder.path() / "day1";
  std::filesystem::create_directories(session / "videos");
  const std::string recording = (session / "session.h5").string();
  const std::string video = (session / "videos" / "front.mp4").string();
  write_text(video, "not really a video");

  const std::string kept = kept_video_path(recording, video);
  EXPECT_EQ(kept, "videos/front.mp4");
  EXPECT_EQ(kept_video_path(recording, (session / "videos" / ".." / "front.mp4").string()),
            "front.mp4");
  write_attachments(recording, {{"front", kept, 0, 1}});

  const std::filesystem::path moved = folder.path() / "archive" / "day1";
  std::filesystem::create_directories(moved.parent_path());
  std::filesystem::rename(session, moved);
  const std::string moved_recording = (moved / "session.h5").string();
  const std::vector<VideoAttachment> read = read_attachments(moved_recording);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].path, "videos/front.mp4");
  EXPECT_EQ(video_path(moved_recording, read[0]), (moved / "videos" / "front.mp4").string());
  EXPECT_TRUE(std::filesystem::exists(video_path(moved_recording, read[0])));
}

TEST(VideoAttachments, PathOutsideTheFolderIsKeptAbsolute) {
  TempFolder folder;
  std::filesystem::create_directories(folder.path() / "recordings");
  const std::string recording = folder.file("recordings/session.h5");
  const std::string video = folder.file("videos/front.mp4");
  const std::string kept = kept_video_path(recording, video);
  EXPECT_EQ(kept, video);
  EXPECT_TRUE(std::filesystem::path(kept).is_absolute());
  EXPECT_EQ(video_path(recording, {"front", kept, 0, 1}), video);
}

TEST(VideoAttachments, MalformedEntriesAreNamedByFileAndNumber) {
  TempFolder folder;
  const std::string recording = folder.file("session.h5");
  const std::string path = attachments_path(recording);
  const auto refusal_for = [&](const std::string& text) {
    write_text(path, text);
    return refusal_of([&] { read_attachments(recording); });
  };
  const std::string good = R"({"name": "front", "path": "a.mp4", "offset": 1, "rate": 1})";
  std::string message = refusal_for(R"({"format": 1, "videos": [)" + good +
                                    R"(, {"name": "side", "path": "b.mp4", "offset": "x"}]})");
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("entry 2: offset is not a number"), std::string::npos) << message;

  message = refusal_for(R"({"format": 1, "videos": [{"path": "a.mp4"}]})");
  EXPECT_NE(message.find("entry 1: name is missing"), std::string::npos) << message;
  message = refusal_for(R"({"format": 1, "videos": [)" + good + "," + good + "]}");
  EXPECT_NE(message.find("entry 2"), std::string::npos) << message;
  EXPECT_NE(message.find("\"front\""), std::string::npos) << message;
  message = refusal_for(R"({"format": 1, "videos": [{"name": "a b", "path": "a.mp4"}]})");
  EXPECT_NE(message.find("entry 1: the name \"a b\""), std::string::npos) << message;
  message = refusal_for(R"({"format": 1, "videos": [{"name": "a", "path": "a.mp4", "rate": 0}]})");
  EXPECT_NE(message.find("entry 1: the rate"), std::string::npos) << message;
  message = refusal_for(R"({"format": 1, "videos": [{"name": "a", "path": "a.mp4", "rate": -2}]})");
  EXPECT_NE(message.find("entry 1: the rate"), std::string::npos) << message;
  message = refusal_for("{\"format\": 1, \"videos\": [");
  EXPECT_NE(message.find("not valid JSON"), std::string::npos) << message;
  message = refusal_for(R"({"format": 2, "videos": []})");
  EXPECT_NE(message.find("format 2"), std::string::npos) << message;
  message = refusal_for(R"({"format": 1})");
  EXPECT_NE(message.find("\"videos\""), std::string::npos) << message;
}

TEST(VideoAttachments, MissingOffsetAndRateMeanTheClocksAgree) {
  TempFolder folder;
  const std::string recording = folder.file("session.h5");
  write_text(attachments_path(recording),
             R"({"format": 1, "videos": [{"name": "front", "path": "a.mp4"}]})");
  const std::vector<VideoAttachment> read = read_attachments(recording);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].offset, 0);
  EXPECT_EQ(read[0].rate, 1);
}

TEST(VideoAttachments, WritingRefusesDuplicateNamesBadNamesAndBadRates) {
  TempFolder folder;
  const std::string recording = folder.file("session.h5");
  EXPECT_NE(refusal_of([&] {
              write_attachments(recording, {{"front", "a.mp4", 0, 1}, {"front", "b.mp4", 0, 1}});
            }).find("two videos are named \"front\""),
            std::string::npos);
  EXPECT_NE(refusal_of([&] { write_attachments(recording, {{"front/1", "a.mp4", 0, 1}}); }), "");
  EXPECT_NE(refusal_of([&] { write_attachments(recording, {{"front", "a.mp4", 0, 0}}); }), "");
  EXPECT_NE(refusal_of([&] {
              write_attachments(recording, {{"front", "a.mp4", 0, INFINITY}});
            }),
            "");
  EXPECT_NE(refusal_of([&] { write_attachments(recording, {{"front", "a.mp4", NAN, 1}}); }), "");
  EXPECT_EQ(folder.entry_count(), 0);
}

TEST(VideoAttachments, TwoPointsGiveRateAndOffset) {
  VideoAttachment attachment{"front", "a.mp4", 0, 1};
  // The clap at recording 10 s is at video 2 s; the second at recording 110 s at video 102.5 s.
  sync_from_two_points(attachment, 10, 2, 110, 102.5);
  EXPECT_DOUBLE_EQ(attachment.rate, 1.005);
  EXPECT_DOUBLE_EQ(attachment.offset, 10 - 2 / 1.005);
  EXPECT_NEAR(attachment.video_time(10), 2, 1e-12);
  EXPECT_NEAR(attachment.video_time(110), 102.5, 1e-12);
  EXPECT_NEAR(attachment.recording_time(102.5), 110, 1e-12);

  VideoAttachment late{"side", "b.mp4", 0, 1};
  sync_from_two_points(late, 0, 0, 60, 60);
  EXPECT_DOUBLE_EQ(late.rate, 1);
  EXPECT_DOUBLE_EQ(late.offset, 0);
  sync_from_two_points(late, 5, 0, 65, 60);  // the video starts 5 s into the recording
  EXPECT_DOUBLE_EQ(late.offset, 5);

  EXPECT_NE(refusal_of([&] { sync_from_two_points(attachment, 10, 2, 10, 5); }).find("same"),
            std::string::npos);
  EXPECT_NE(refusal_of([&] { sync_from_two_points(attachment, 10, 5, 20, 2); }), "");
  EXPECT_NE(refusal_of([&] { sync_from_two_points(attachment, 10, 5, 20, 5); }), "");
  EXPECT_DOUBLE_EQ(attachment.rate, 1.005);  // a refused sync changes nothing
}

TEST(VideoAttachments, FreeNameIsTheStemThenNumbered) {
  std::vector<VideoAttachment> attachments;
  EXPECT_EQ(free_attachment_name(attachments, "/data/front.mp4"), "front");
  attachments.push_back({"front", "front.mp4", 0, 1});
  EXPECT_EQ(free_attachment_name(attachments, "/other/front.mkv"), "front-2");
  attachments.push_back({"front-2", "x.mkv", 0, 1});
  EXPECT_EQ(free_attachment_name(attachments, "front.avi"), "front-3");
  EXPECT_EQ(free_attachment_name(attachments, "my camera (1).mp4"), "my-camera--1-");
  EXPECT_EQ(find_attachment(attachments, "front-2")->path, "x.mkv");
  EXPECT_EQ(find_attachment(attachments, "back"), nullptr);
}

}  // namespace
}  // namespace tactile

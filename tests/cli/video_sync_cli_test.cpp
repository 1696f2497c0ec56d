// `tactile video sync`: by hand (--offset, --points) and proposed (--auto), written only when
// accepted and sure; bad values named by their option.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "tactile/signal/sample_source.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_writer.h"
#include "temp_folder.h"
#include "touch_videos.h"

namespace tactile {
namespace {

struct SyncFixture {
  test::TempFolder folder{"tactile-video-sync"};
  std::string recording;
};

// A simulated 8 x 8 grid recording with two videos attached at offset 0: "front", a video of
// its touches whose time 0 is shown at recording time 7.5 s, and "still", a still picture.
std::unique_ptr<SyncFixture> make_fixture() {
  auto fixture = std::make_unique<SyncFixture>();
  const test::TempFolder& folder = fixture->folder;
  const auto simulated = test::run_program(
      "tactile",
      "simulate --skin grid:8x8 --subjects 1 --trials 1 --repetitions 6 --seed 5 --out " +
          folder.file("rec"),
      folder);
  EXPECT_EQ(simulated.exit_code, 0) << simulated.err;
  fixture->recording = folder.file("rec/grid-8x8-s01-t01.h5");
  const Recording recording = read_all(*open_sample_source(fixture->recording));
  test::TouchVideoOptions options;
  options.offset = 7.5;
  options.seconds = 60;
  test::write_touch_video(folder.file("rec/front.mp4"), recording.streams.at(0), 8, 8, options);
  VideoWriterOptions still_options;
  still_options.width = 64;
  still_options.height = 48;
  VideoWriter still(folder.file("rec/still.mp4"), still_options);
  const std::vector<uint8_t> grey(64 * 48 * 4, 128);
  for (int frame = 0; frame < 600; ++frame) still.write(grey.data(), frame / 30.0);
  still.finish();
  VideoAttachment front{"front", "front.mp4", 0, 1};
  VideoAttachment quiet{"still", "still.mp4", 0, 1};
  write_attachments(fixture->recording, {front, quiet});
  return fixture;
}

const VideoAttachment& attachment(const std::string& recording, const std::string& name) {
  static std::vector<VideoAttachment> attachments;
  attachments = read_attachments(recording);
  const VideoAttachment* found = find_attachment(attachments, name);
  EXPECT_NE(found, nullptr) << name;
  return *found;
}

test::CommandResult sync(const SyncFixture& fixture, const std::string& arguments) {
  return test::run_program("tactile", "video sync " + fixture.recording + " " + arguments,
                           fixture.folder);
}

TEST(VideoSyncCli, ProposesTheOffsetAndWritesItOnlyWhenAccepted) {
  const auto fixture = make_fixture();
  const auto proposed = sync(*fixture, "front --auto");
  ASSERT_EQ(proposed.exit_code, 0) << proposed.err;
  EXPECT_NE(proposed.out.find("proposed offset 7.5"), std::string::npos) << proposed.out;
  EXPECT_NE(proposed.out.find("sure"), std::string::npos);
  EXPECT_NE(proposed.out.find("not written"), std::string::npos);
  EXPECT_EQ(attachment(fixture->recording, "front").offset, 0.0);

  const auto accepted = sync(*fixture, "front --auto --accept --max-lag 20");
  ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
  EXPECT_NEAR(attachment(fixture->recording, "front").offset, 7.5, 1.0 / 30.0);
}

TEST(VideoSyncCli, RefusesToAcceptAProposalThatIsNotSureUnlessForced) {
  const auto fixture = make_fixture();
  const auto refused = sync(*fixture, "still --auto --accept");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("--accept"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("no motion"), std::string::npos) << refused.err;
  EXPECT_EQ(attachment(fixture->recording, "still").offset, 0.0);
  // Forced, the proposal (nothing better than the present offset) is written.
  const auto forced = sync(*fixture, "still --auto --accept --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
}

TEST(VideoSyncCli, SetsTheOffsetOrOffsetAndRateFromTwoInstants) {
  const auto fixture = make_fixture();
  ASSERT_EQ(sync(*fixture, "front --offset -3.25").exit_code, 0);
  EXPECT_DOUBLE_EQ(attachment(fixture->recording, "front").offset, -3.25);
  // Recording 10 s shows video 2 s, recording 110 s shows video 102.1 s.
  const auto points = sync(*fixture, "front --points 10=2,110=102.1");
  ASSERT_EQ(points.exit_code, 0) << points.err;
  const VideoAttachment& synced = attachment(fixture->recording, "front");
  EXPECT_NEAR(synced.rate, 1.001, 1e-9);
  EXPECT_NEAR(synced.video_time(10.0), 2.0, 1e-9);
  EXPECT_NEAR(synced.video_time(110.0), 102.1, 1e-9);
  // The still video was left alone.
  EXPECT_DOUBLE_EQ(attachment(fixture->recording, "still").offset, 0.0);
}

TEST(VideoSyncCli, BadValuesAreNamedByTheirOption) {
  const auto fixture = make_fixture();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"front --offset soon", "--offset"},
      {"front --points 10=2", "--points"},
      {"front --points 10=2,10=5", "--points"},
      {"front --auto --region 0,0,2,1", "--region"},
      {"front --auto --max-lag -1", "--max-lag"},
      {"front --offset 1 --accept", "--accept"},
      {"front --offset 1 --auto", "one of --offset, --points and --auto"},
      {"back --offset 1", "no video named \"back\""},
  };
  for (const auto& [arguments, expected] : cases) {
    const auto result = sync(*fixture, arguments);
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_NE(result.err.find(expected), std::string::npos) << arguments << ": " << result.err;
  }
  EXPECT_DOUBLE_EQ(attachment(fixture->recording, "front").offset, 0.0);
}

}  // namespace
}  // namespace tactile

// The live camera on FFmpeg's lavfi test source paced in real time: frames arrive stamped on
// the live clock, a recording holds the pre-trigger frames and starts at the time it returns,
// and a camera that cannot be opened is named.
#include "tactile/video/camera.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "tactile/error.h"
#include "tactile/video/video_file.h"
#include "temp_folder.h"

namespace tactile {
namespace {

constexpr const char* kTestCamera = "lavfi:testsrc2=size=160x120:rate=30,realtime";

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

CameraOptions test_camera(double pre_trigger = 0.5) {
  CameraOptions options;
  options.url = kTestCamera;
  options.max_width = 160;
  options.pre_trigger = pre_trigger;
  return options;
}

void wait_seconds(double seconds) {
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

TEST(Camera, FramesArriveStampedOnTheLiveClockInOrder) {
  Camera camera(test_camera(), steady_seconds);
  double last_time = -1;
  int64_t last_index = -1, seen = 0;
  for (int poll = 0; poll < 100 && seen < 10; ++poll) {
    wait_seconds(0.02);
    const std::shared_ptr<const VideoFrame> frame = camera.latest();
    if (!frame || frame->index == last_index) continue;
    EXPECT_GT(frame->time, last_time);
    EXPECT_GT(frame->index, last_index);
    EXPECT_EQ(frame->width, 160);
    EXPECT_EQ(frame->height, 120);
    EXPECT_EQ(frame->rgba.size(), 160u * 120u * 4u);
    last_time = frame->time;
    last_index = frame->index;
    ++seen;
  }
  EXPECT_GE(seen, 10);
  EXPECT_EQ(camera.error(), "");
  // Paced by `realtime`: about 30 frames a second, not thousands.
  EXPECT_LT(camera.frames_received(), 30 * 5);
}

TEST(Camera, ARecordingStartsWithThePreTriggerFramesAtTheTimeItReturns) {
  test::TempFolder folder;
  const std::string path = folder.file("camera.mp4");
  Camera camera(test_camera(0.5), steady_seconds);
  wait_seconds(1.0);
  const double start = steady_seconds();
  const double first_frame = camera.start_recording(path);
  // The pre-trigger frames go back about half a second.
  EXPECT_LT(first_frame, start - 0.3);
  EXPECT_GT(first_frame, start - 0.7);
  wait_seconds(1.0);
  camera.stop_recording();
  EXPECT_EQ(camera.error(), "");

  VideoFile video(path);
  // About 1.5 s at 30 fps; a loaded machine may deliver some late, none double.
  EXPECT_GT(video.info().frame_count, 30);
  EXPECT_LT(video.info().frame_count, 60);
  EXPECT_GT(video.info().duration, 1.2);
  EXPECT_LT(video.info().duration, 2.0);
  EXPECT_EQ(video.info().width, 160);
  EXPECT_DOUBLE_EQ(video.frame_times().front(), 0.0);
}

TEST(Camera, ACameraThatCannotBeOpenedIsNamed) {
  for (const std::string url :
       {"lavfi:nosuchfilter", "v4l2:/dev/nonexistent", "nosuchdevice:x", "no-colon"}) {
    CameraOptions options;
    options.url = url;
    try {
      Camera camera(options, steady_seconds);
      ADD_FAILURE() << url << " opened";
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), url) << error.what();
    }
  }
}

}  // namespace
}  // namespace tactile

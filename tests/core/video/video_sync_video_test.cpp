// Motion energy read from real (encoded) videos, and the offset proposal end to end: a
// simulated recording, a video of its touches written with VideoWriter, the proposal.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/signal/sample_source.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/video/video_file.h"
#include "tactile/video/video_sync.h"
#include "tactile/video/video_writer.h"
#include "temp_folder.h"
#include "touch_videos.h"

namespace tactile {
namespace {

using test::TempFolder;

VideoOpenOptions small_grey() {
  VideoOpenOptions options;
  options.max_width = 160;
  options.grey = true;
  return options;
}

// 4 s at 30 fps, 64 x 48: a white square moving right in the left half during [1, 2) s, still
// otherwise.
std::string write_square_video(const TempFolder& folder) {
  const std::string path = folder.file("square.mp4");
  VideoWriterOptions options;
  options.width = 64;
  options.height = 48;
  VideoWriter writer(path, options);
  std::vector<uint8_t> rgba(64 * 48 * 4);
  for (int frame = 0; frame < 120; ++frame) {
    const double t = frame / 30.0;
    const int left = 2 + static_cast<int>(std::clamp(t - 1.0, 0.0, 1.0) * 18);
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool square = x >= left && x < left + 10 && y >= 19 && y < 29;
        uint8_t* pixel = &rgba[(y * 64 + x) * 4];
        pixel[0] = pixel[1] = pixel[2] = square ? 240 : static_cast<uint8_t>(60 + x + y / 2);
        pixel[3] = 255;
      }
    writer.write(rgba.data(), t);
  }
  writer.finish();
  return path;
}

TEST(MotionEnergy, IsHighOnlyWhileSomethingMovesAndOnlyInsideTheRegionWhereItMoves) {
  TempFolder folder;
  VideoFile video(write_square_video(folder), small_grey());
  const ActivitySeries whole = motion_energy(video, 10.0, std::nullopt);
  EXPECT_DOUBLE_EQ(whole.start, 0.0);
  ASSERT_GE(whole.values.size(), 39u);
  // Moving (steps 11..19): a 10-pixel square moving 18 px/s changes 2 columns of it per
  // frame by ~180 levels, over 64 x 48 pixels: about 1 level. Still: codec noise only.
  for (size_t step = 11; step < 19; ++step) EXPECT_GT(whole.values[step], 0.4) << step;
  for (size_t step : {3u, 6u, 25u, 35u}) EXPECT_LT(whole.values[step], 0.1) << step;
  // The right half never moves: only the key frame every 2 s (frame 60) re-encodes it, by a
  // fraction of a level after the median is taken off.
  VideoFile again(video.info().path, small_grey());
  const ActivitySeries right = motion_energy(again, 10.0, VideoRegion{0.6, 0, 0.4, 1});
  for (size_t step = 0; step < right.values.size(); ++step)
    EXPECT_LT(right.values[step], 0.3) << step << " whole " << whole.values[step];
}

TEST(MotionEnergy, StopsWithAnErrorWhenItsJobIsCancelled) {
  TempFolder folder;
  VideoFile video(write_square_video(folder), small_grey());
  const std::atomic<bool> cancelled{true};
  const CancelScope scope(&cancelled);
  try {
    motion_energy(video, 10.0, std::nullopt);
    FAIL() << "not cancelled";
  } catch (const Error& error) {
    EXPECT_EQ(error.message(), "cancelled");
  }
}

TEST(VideoSync, FindsTheOffsetOfAVideoOfTheSimulatedTouchesWithinOneFrame) {
  TempFolder folder;
  const SkinLayout layout = make_grid_layout(8, 8);
  SimulationOptions simulation;
  simulation.seed = 5;
  simulation.repetitions = 6;
  const SimulatedTrial trial = simulate_grid_trial(layout, simulation, 0, 0);
  const Stream& stream = trial.recording.streams.at(0);
  ASSERT_GT(stream.duration(), 100.0);
  const MemorySampleSource source(trial.recording, stream);
  const ActivitySeries skin = skin_activity(source, 10.0);

  for (double offset : {-12.34, 21.7}) {
    test::TouchVideoOptions options;
    options.offset = offset;
    options.seconds = 70;
    const std::string path = folder.file("touches.mp4");
    test::write_touch_video(path, stream, 8, 8, options);
    VideoFile video(path, small_grey());
    const ActivitySeries motion = motion_energy(video, 10.0, std::nullopt);
    const SyncProposal proposal = propose_offset(skin, motion, 0.0, 30.0);
    EXPECT_NEAR(proposal.offset, offset, 1.0 / 30.0) << "offset " << offset;
    EXPECT_TRUE(proposal.sure) << "offset " << offset << ": " << proposal.why;
  }
}

TEST(VideoSync, AVideoWhoseMotionIsUnrelatedToTheTouchesIsNotSure) {
  TempFolder folder;
  const SkinLayout layout = make_grid_layout(8, 8);
  SimulationOptions simulation;
  simulation.seed = 6;
  simulation.repetitions = 6;
  const SimulatedTrial trial = simulate_grid_trial(layout, simulation, 0, 0);
  const MemorySampleSource source(trial.recording, trial.recording.streams.at(0));
  // The video of another subject's touches.
  const SimulatedTrial other = simulate_grid_trial(layout, simulation, 1, 0);
  test::TouchVideoOptions options;
  options.seconds = 70;
  const std::string path = folder.file("control.mp4");
  test::write_touch_video(path, other.recording.streams.at(0), 8, 8, options);
  VideoFile video(path, small_grey());
  const SyncProposal proposal = propose_offset(skin_activity(source, 10.0),
                                               motion_energy(video, 10.0, std::nullopt), 0.0, 30.0);
  EXPECT_FALSE(proposal.sure) << proposal.offset << " correlation " << proposal.correlation
                              << " confidence " << proposal.confidence;
}

}  // namespace
}  // namespace tactile

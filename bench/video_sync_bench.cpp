// The offset proposal on 20 synthetic cases (docs/VIDEO.md, "Synchronising"): each a simulated
// 8 x 8 pressure grid recording and a 160 x 120, 30 fps video of its touches (tests/support/
// touch_videos.h: a blob as large as the pressure, sensor noise, a person drifting now and
// then), whose time 0 is shown at an offset spread over -30..+30 s. The proposal searches
// +-40 s around 0 at 10 Hz. Prints a table: true offset, proposed, error in video frames,
// correlation, confidence, sure; the count within one frame; and a control case whose video
// shows another recording's touches, which must not be sure. bench/VIDEO_SYNC.md keeps a run.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "tactile/layout/skin_layout.h"
#include "tactile/signal/sample_source.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/video/video_file.h"
#include "tactile/video/video_sync.h"
#include "touch_videos.h"

namespace {

using namespace tactile;

constexpr int kCases = 20;
constexpr double kFrameRate = 30.0;
constexpr double kGridRate = 10.0;

SimulatedTrial trial_of(const SkinLayout& layout, int subject) {
  SimulationOptions options;
  options.seed = 41;
  options.repetitions = 10;
  return simulate_grid_trial(layout, options, subject, 0);
}

SyncProposal propose(const SimulatedTrial& trial, const Stream& filmed, double offset,
                     const std::string& path, uint64_t seed) {
  test::TouchVideoOptions options;
  options.offset = offset;
  options.seconds = 120;
  options.seed = seed;
  test::write_touch_video(path, filmed, 8, 8, options);
  VideoOpenOptions open;
  open.max_width = 160;
  open.grey = true;
  VideoFile video(path, open);
  const MemorySampleSource source(trial.recording, trial.recording.streams.at(0));
  return propose_offset(skin_activity(source, kGridRate),
                        motion_energy(video, kGridRate, std::nullopt), 0.0, 40.0);
}

}  // namespace

int main() {
  const SkinLayout layout = make_grid_layout(8, 8);
  const std::string folder =
      (std::filesystem::temp_directory_path() / "tactile-video-sync-bench").string();
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/case.mp4";
  std::printf(
      "| case | recording (s) | true offset (s) | proposed (s) | error (frames) | "
      "correlation | confidence | sure |\n|---|---|---|---|---|---|---|---|\n");
  int within_frame = 0, sure = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kCases; ++k) {
    const double offset = -30.0 + 60.0 * k / (kCases - 1) + 0.0137 * k;
    const SimulatedTrial trial = trial_of(layout, k);
    const Stream& stream = trial.recording.streams.at(0);
    const SyncProposal proposal = propose(trial, stream, offset, path, 1000 + k);
    const double frames = std::abs(proposal.offset - offset) * kFrameRate;
    within_frame += frames <= 1.0;
    sure += proposal.sure;
    std::printf("| %d | %.0f | %.3f | %.3f | %.2f | %.2f | %.2f | %s |\n", k + 1, stream.duration(),
                offset, proposal.offset, frames, proposal.correlation, proposal.confidence,
                proposal.sure ? "yes" : ("no: " + proposal.why).c_str());
    std::fflush(stdout);
  }
  const SimulatedTrial trial = trial_of(layout, 0);
  const SimulatedTrial other = trial_of(layout, 77);
  const SyncProposal control = propose(trial, other.recording.streams.at(0), 5.0, path, 999);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("\nwithin one frame: %d of %d; sure: %d of %d\n", within_frame, kCases, sure, kCases);
  std::printf(
      "control (the video of another recording): proposed %.3f s, correlation %.2f, "
      "confidence %.2f, %s\n",
      control.offset, control.correlation, control.confidence,
      control.sure ? "SURE (wrong)" : ("not sure: " + control.why).c_str());
  std::printf("%.0f s in all\n", seconds);
  std::filesystem::remove_all(folder);
  return within_frame >= kCases - 1 && !control.sure ? 0 : 1;
}

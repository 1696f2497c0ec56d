// The video view's player on a long file (docs/VIDEO.md, bench/VIDEO.md): what the window sees.
//   video_play_bench VIDEO [SECONDS]
// 1. Random times: the player asked for the frame at each of 100 random times (as a click on
//    the time axis does), the wall time until it shows that frame: median and worst.
// 2. Playing at 1x and 2x for SECONDS (default 20) of wall time, the window's 60 Hz ticks: at
//    each, the frame due against the frame shown; ticks whose frame is late by more than one
//    video frame; the window thread's cost of asking and taking (want + shown) per tick.
// 3. Memory: peak resident, and what the player's cache holds.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "process_memory.h"
#include "tactile/video/video_player.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double percentile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<size_t>(share * values.size()))];
}

int64_t index_at(const std::vector<double>& times, double time) {
  const auto after = std::upper_bound(times.begin(), times.end(), time);
  return static_cast<int64_t>(after - times.begin()) - 1;
}

tactile::VideoOpenOptions view_options() {
  tactile::VideoOpenOptions options;
  options.max_width = 960;  // as the workbench's video view decodes
  options.cache_frames = 12;
  return options;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: video_play_bench VIDEO [SECONDS]\n");
    return 2;
  }
  const std::string path = argv[1];
  const double play_seconds = argc > 2 ? std::stod(argv[2]) : 20.0;
  tactile::bench::reset_peak_memory();
  const double memory_before = tactile::bench::peak_memory_mb();
  const auto opening = Clock::now();
  tactile::VideoPlayer player(path, view_options());
  while (player.opening()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (!player.problem().empty()) {
    std::fprintf(stderr, "%s\n", player.problem().c_str());
    return 1;
  }
  const double opened = seconds_since(opening);
  const auto info = player.info();
  const auto times = player.frame_times();
  std::printf("%s: %s %dx%d, %.0f s, %lld frames at %.2f fps; opened and indexed in %.2f s\n",
              path.c_str(), info->codec.c_str(), info->width, info->height, info->duration,
              static_cast<long long>(info->frame_count), info->mean_rate, opened);

  // 1. Random times.
  std::mt19937_64 engine(1);
  std::vector<double> waits;
  for (int k = 0; k < 100; ++k) {
    const double time = info->duration * static_cast<double>(engine() % 1000000) / 1e6;
    const auto asked = Clock::now();
    player.want(time, false);
    while (!player.caught_up()) std::this_thread::sleep_for(std::chrono::microseconds(200));
    waits.push_back(seconds_since(asked) * 1000.0);
  }
  std::printf("random frame shown: median %.0f ms, 90th %.0f ms, worst %.0f ms (100 times)\n",
              percentile(waits, 0.5), percentile(waits, 0.9), percentile(waits, 1.0));

  // 2. Playing.
  const double frame_seconds = 1.0 / info->mean_rate;
  for (double speed : {1.0, 2.0}) {
    const double start_time = 0.37 * info->duration;
    player.want(start_time, false);
    while (!player.caught_up()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    int64_t ticks = 0, late = 0, on_time = 0, most_behind = 0;
    std::vector<double> costs;
    const auto began = Clock::now();
    auto next = began;
    while (seconds_since(began) < play_seconds) {
      next += std::chrono::microseconds(16667);
      std::this_thread::sleep_until(next);
      const double time = start_time + speed * seconds_since(began);
      const auto asked = Clock::now();
      player.want(time, true);
      const std::shared_ptr<const tactile::VideoFrame> shown = player.shown();
      costs.push_back(seconds_since(asked) * 1e6);
      const int64_t due = index_at(*times, time);
      const int64_t behind = shown ? due - shown->index : due;
      most_behind = std::max(most_behind, behind);
      ++ticks;
      if (behind > 1) ++late;
      if (behind <= 0) ++on_time;
    }
    std::printf(
        "play %.0fx for %.0f s: %lld ticks at 60 Hz, %.1f %% showing the frame due, %lld late "
        "by more than one frame (%.0f ms), most behind %lld frames; window's cost per tick "
        "median %.0f us, worst %.0f us\n",
        speed, play_seconds, static_cast<long long>(ticks), 100.0 * on_time / ticks,
        static_cast<long long>(late), 1000.0 * frame_seconds, static_cast<long long>(most_behind),
        percentile(costs, 0.5), percentile(costs, 1.0));
  }
  const auto frame = player.shown();
  const double frame_mb = frame ? frame->rgba.size() / 1048576.0 : 0.0;
  std::printf(
      "memory: peak resident %.0f MB over %.0f MB before; the cache holds at most %d "
      "frames of %.1f MB (%.0f MB)\n",
      tactile::bench::peak_memory_mb(), memory_before, view_options().cache_frames, frame_mb,
      view_options().cache_frames * frame_mb);
  return 0;
}

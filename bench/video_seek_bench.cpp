// The video view's reads on a long file (bench/VIDEO.md, issue 45): opening and indexing, 100
// frames at random times, and play at 1x and 2x on a 60 Hz display, one worker decoding at real
// time. Usage: video_seek_bench VIDEO (bench/video_seek.sh makes a 30-minute 1080p H.264 file).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "process_memory.h"
#include "tactile/error.h"
#include "tactile/video/video_file.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double percentile(std::vector<double> values, double share) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(share * static_cast<double>(values.size() - 1) + 0.5)];
}

struct Play {
  int frames = 0;
  int late = 0;
  double first_ms = 0;  // the jump to the start: a seek, not counted late
  std::vector<double> decode_ms;
  int64_t seeks = 0;
};

// `seconds` of video from `start` at `speed`: at each 60 Hz tick the frame due is asked for once;
// a single worker decodes the frames in the order they fall due, starting each when it is free
// and the frame is due. Late: ready more than one frame interval (in wall time) after due.
Play play(tactile::VideoFile& video, double start, double seconds, double speed) {
  Play result;
  const double interval = 1.0 / video.info().mean_rate / speed;  // wall seconds per frame
  const int64_t seeks_before = video.seek_count();
  int64_t last = -1;
  double worker_free = 0;
  for (int tick = 0; tick * speed / 60.0 < seconds; ++tick) {
    const double now = tick / 60.0;
    const int64_t index = video.frame_index_at(start + now * speed);
    if (index < 0 || index == last) continue;
    last = index;
    const Clock::time_point begin = Clock::now();
    video.frame(index);
    const double decode = ms_since(begin);
    if (result.frames++ == 0) {
      result.first_ms = decode;
      worker_free = now;
      continue;
    }
    result.decode_ms.push_back(decode);
    worker_free = std::max(worker_free, now) + decode / 1000;
    if (worker_free - now > interval) ++result.late;
  }
  result.seeks = video.seek_count() - seeks_before - 1;
  return result;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: video_seek_bench VIDEO\n");
    return 2;
  }
  try {
    const double memory_before = tactile::bench::resident_memory_mb();
    tactile::VideoOpenOptions options;
    options.max_width = 960;  // as the video view asks
    Clock::time_point begin = Clock::now();
    tactile::VideoFile video(argv[1], options);
    const double open_ms = ms_since(begin);
    const double memory_opened = tactile::bench::resident_memory_mb();
    const tactile::VideoInfo& info = video.info();

    std::mt19937 random(45);
    std::uniform_real_distribution<double> anywhere(0, info.duration);
    std::vector<double> random_ms;
    for (int read = 0; read < 100; ++read) {
      const double time = anywhere(random);
      begin = Clock::now();
      video.frame(video.frame_index_at(time));
      random_ms.push_back(ms_since(begin));
    }

    const double play_seconds = 30;
    const Play normal = play(video, info.duration * 0.3, play_seconds, 1);
    const Play fast = play(video, info.duration * 0.6, play_seconds, 2);
    const double memory_after = tactile::bench::resident_memory_mb();

    std::printf("video: %s\n  %s %dx%d, %.1f s, %lld frames, %.2f fps%s, frames read at %dx%d\n",
                argv[1], info.codec.c_str(), info.width, info.height, info.duration,
                static_cast<long long>(info.frame_count), info.mean_rate,
                info.variable_rate ? " (variable)" : "", video.frame(0).width,
                video.frame(0).height);
    std::printf("%-44s %12s %12s\n", "measure", "value", "target");
    std::printf("%-44s %9.0f ms %12s\n", "open + index (+ frame 0)", open_ms, "");
    std::printf("%-44s %9.1f ms %9s ms\n", "random frame: median (100 reads)",
                percentile(random_ms, 0.5), "<= 150");
    std::printf("%-44s %9.1f ms %9s ms\n", "random frame: worst",
                *std::max_element(random_ms.begin(), random_ms.end()), "<= 400");
    for (const auto& [name, run] : {std::pair{"1x", &normal}, std::pair{"2x", &fast}}) {
      std::printf("%-44s %12d\n",
                  (std::string("play ") + name + ": frames shown in 30 s of video").c_str(),
                  run->frames);
      std::printf("%-44s %9.1f ms\n",
                  (std::string("play ") + name + ": first frame (the jump)").c_str(),
                  run->first_ms);
      std::printf("%-44s %9.1f ms\n",
                  (std::string("play ") + name + ": decode per frame, median").c_str(),
                  percentile(run->decode_ms, 0.5));
      std::printf("%-44s %9.1f ms\n",
                  (std::string("play ") + name + ": decode per frame, p99").c_str(),
                  percentile(run->decode_ms, 0.99));
      std::printf("%-44s %12d %12s\n",
                  (std::string("play ") + name + ": frames late > 1 frame").c_str(), run->late,
                  "0");
      std::printf("%-44s %12lld %12s\n",
                  (std::string("play ") + name + ": seeks after the jump").c_str(),
                  static_cast<long long>(run->seeks), "0");
    }
    std::printf("%-44s %9.0f MB\n", "resident memory before open", memory_before);
    std::printf("%-44s %9.0f MB\n", "resident memory after open + index", memory_opened);
    std::printf("%-44s %9.0f MB\n", "resident memory after the reads", memory_after);
    std::printf("%-44s %5d x %.2f MB\n", "cache: frames x bytes", options.cache_frames,
                static_cast<double>(video.cached_bytes()) / options.cache_frames / 1e6);
  } catch (const tactile::Error& error) {
    std::fprintf(stderr, "video_seek_bench: %s\n", error.what());
    return 1;
  }
  return 0;
}

// Disk-full benchmark of issue 27 ("Faults of the world"): a live recording at the size of
// NAO's skin at 4x (128 channels, 1000 samples/s of noise that does not compress) runs into a
// full disk at `--points` fill points. Each run is a child process (a crash is seen as one):
//   clean stop   the recorder watches its disk (LiveRecorderOptions::room) and stops itself;
//                the file must verify as it is.
//   failed write the recorder does not watch: a write fails. The file must verify after
//                `repair` (or before it), with every sample the writer had reported flushed.
// The disk is a tmpfs of the point's size when this process may mount one (root), else a
// file-size limit (ulimit -f) of that size: the same failing write(). After a run the
// tmpfs is made larger (the user freed space) for repair.
//
//   disk_full_bench [--points N] [--work DIR] [--no-mount]   (--no-mount: the file-size limit)
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "tactile/io/disk_room.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/live/live_recorder.h"
#include "tactile/verify/repair.h"
#include "tactile/verify/verify.h"

namespace fs = std::filesystem;
using namespace tactile;

namespace {

constexpr int kChannels = 128;
constexpr double kRate = 1000.0;

float sent_value(int64_t row, int channel) {
  uint64_t x = static_cast<uint64_t>(row) * 0x9E3779B97F4A7C15ull +
               static_cast<uint64_t>(channel + 1) * 0xBF58476D1CE4E5B9ull;
  x ^= x >> 31;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 29;
  return static_cast<float>(x % 100000) / 100.0f;
}

struct ChildResult {
  bool crashed = false;
  int64_t flushed = 0;
  bool stopped = false;
  std::string message;
  std::string stderr_text;
};

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Records into `path` until the recorder stops or fails (or 600 s of samples).
ChildResult record_child(const std::string& path, bool watch, int64_t limit,
                         const std::string& scratch) {
  const std::string report = scratch + "/report.txt", errors = scratch + "/stderr.txt";
  const pid_t child = fork();
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);
    if (std::freopen(errors.c_str(), "w", stderr) == nullptr) _exit(3);
    if (limit > 0) {
      struct rlimit size {
        static_cast<rlim_t>(limit), static_cast<rlim_t>(limit)
      };
      setrlimit(RLIMIT_FSIZE, &size);
    }
    SourceInfo info;
    info.layout_id = "grid:8x16";
    info.stream = "skin";
    info.rate_hz = kRate;
    for (int channel = 0; channel < kChannels; ++channel)
      info.channels.push_back("c" + std::to_string(channel));
    info.units.assign(kChannels, "V");
    LiveSampleSource source(info, 200000);
    LiveRecorderOptions options;
    options.pretrigger_seconds = 1000.0;
    options.lag_seconds = 0.0;
    if (!watch) options.room = nullptr;
    int64_t next = 0, flushed = 0;
    std::string message;
    bool stopped = false;
    try {
      LiveRecorder recorder(path, source, options);
      std::vector<float> values(kChannels);
      while (next < 600 * static_cast<int64_t>(kRate) && recorder.error().empty() &&
             !recorder.stopped()) {
        for (int k = 0; k < 100; ++k, ++next) {
          for (int channel = 0; channel < kChannels; ++channel)
            values[static_cast<size_t>(channel)] = sent_value(next, channel);
          source.add(static_cast<double>(next) / kRate, values);
        }
        recorder.take(source);
        while (recorder.samples_on_disk() + 1500 < recorder.samples_taken() &&
               recorder.error().empty() && !recorder.stopped())
          std::this_thread::sleep_for(std::chrono::microseconds(200));
        flushed = recorder.samples_on_disk();
      }
      stopped = recorder.stopped();
      message = stopped ? recorder.room().stopped : recorder.error();
      try {
        recorder.finish(source);
      } catch (const std::exception& error) {
        if (message.empty()) message = error.what();
      }
    } catch (const std::exception& error) {
      message = error.what();
    }
    std::ofstream out(report);
    out << flushed << " " << stopped << "\n" << message;
    out.close();
    std::fflush(stderr);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ChildResult result;
  result.crashed = !WIFEXITED(status) || WEXITSTATUS(status) != 0;
  std::istringstream in(file_text(report));
  in >> result.flushed >> result.stopped;
  in.get();
  std::getline(in, result.message, '\0');
  result.stderr_text = file_text(errors);
  return result;
}

bool flushed_samples_intact(const std::string& path, int64_t flushed) {
  try {
    RecordingFile file(path);
    const StreamInfo& stream = file.stream("skin");
    if (stream.sample_count < flushed) return false;
    for (int64_t first = 0; first < flushed; first += 8192) {
      const int64_t count = std::min<int64_t>(8192, flushed - first);
      const SampleMatrix samples = file.read("skin", first, count);
      for (int64_t row = 0; row < count; ++row)
        for (int channel = 0; channel < kChannels; ++channel)
          if (samples(row, channel) != sent_value(first + row, channel)) return false;
    }
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

struct Totals {
  int runs = 0, crashes = 0, stopped = 0, failed = 0, verify_before = 0, verify_after = 0,
      repaired = 0;
  int intact = 0, quiet_stderr = 0, one_line = 0;
  int64_t flushed = 0;
};

}  // namespace

int main(int argc, char** argv) {
  int points = 20;
  fs::path work = fs::temp_directory_path() / "tactile-disk-full-bench";
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string option = argv[k];
    if (option == "--points")
      points = std::stoi(argv[k + 1]);
    else if (option == "--work")
      work = argv[k + 1];
  }
  bool no_mount = false;
  for (int k = 1; k < argc; ++k) no_mount = no_mount || std::string(argv[k]) == "--no-mount";
  fs::remove_all(work);
  fs::create_directories(work / "disk");
  const std::string disk = (work / "disk").string(), scratch = work.string();
  const bool can_mount = !no_mount && ::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=256k") == 0;
  if (can_mount) ::umount(disk.c_str());
  std::printf("disk: %s\n", can_mount ? "tmpfs of each size (real ENOSPC)"
                                      : "file-size limit of each size (EFBIG)");
  Totals totals[2];
  for (int mode = 0; mode < 2; ++mode) {
    const bool watch = mode == 0;
    for (int point = 0; point < points; ++point) {
      // 1 MB to about 21 MB, spread so that failures land at different places of a flush.
      const int64_t size = 1000000 + static_cast<int64_t>(point) * 1000000 + point * 37000;
      if (can_mount) {
        const std::string data = "size=" + std::to_string(size);
        if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, data.c_str()) != 0) return 2;
      }
      const std::string path = disk + "/run.h5";
      const ChildResult result = record_child(path, watch, can_mount ? 0 : size, scratch);
      Totals& total = totals[mode];
      ++total.runs;
      total.crashes += result.crashed;
      total.stopped += result.stopped;
      total.failed += !result.stopped;
      total.flushed += result.flushed;
      total.quiet_stderr += result.stderr_text.empty();
      total.one_line += result.message.find('\n') == std::string::npos;
      const bool whole = verify_recording(path).empty();
      total.verify_before += whole;
      if (can_mount) {
        const std::string data = "size=" + std::to_string(3 * size);
        ::mount("tmpfs", disk.c_str(), "tmpfs", MS_REMOUNT, data.c_str());
      }
      bool verified = whole;
      try {
        const RepairReport report = repair_recording(path);
        total.repaired += report.repaired;
        verified = verify_recording(path).empty();
      } catch (const std::exception& error) {
        std::printf("  point %d: repair failed: %s\n", point, error.what());
      }
      total.verify_after += verified;
      total.intact += flushed_samples_intact(path, result.flushed);
      std::printf("  %s %2d: %5.1f MB, %6.1f s flushed, %s%s\n", watch ? "stop" : "fail", point,
                  size / 1e6, static_cast<double>(result.flushed) / kRate,
                  result.stopped ? "stopped" : "failed", whole ? ", whole" : ", repaired");
      if (!result.stderr_text.empty())
        std::printf("    stderr: %.200s\n", result.stderr_text.c_str());
      if (can_mount)
        ::umount(disk.c_str());
      else
        fs::remove_all(disk), fs::create_directories(disk);
    }
  }
  std::printf(
      "\n| runs | recorder | crashes | stopped itself | write failed | verify as left | verify "
      "after repair | flushed samples all there | HDF5 stack on stderr | one-line message |\n");
  std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int mode = 0; mode < 2; ++mode) {
    const Totals& t = totals[mode];
    std::printf("| %d | %s | %d | %d | %d | %d | %d | %d of %d (%lld samples) | %d | %d |\n",
                t.runs, mode == 0 ? "watches its disk" : "does not watch", t.crashes, t.stopped,
                t.failed, t.verify_before, t.verify_after, t.intact, t.runs,
                static_cast<long long>(t.flushed), t.runs - t.quiet_stderr, t.one_line);
  }
  return 0;
}

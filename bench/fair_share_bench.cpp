// Jobs on a busy desktop (issue 41): the workbench's Train all job (every preset, 5-fold, on
// a simulated skin's own features) run to the end idle, then beside one and beside two
// busy processes (`sh -c 'while :; do :; done'`, as a compiler or a browser would be); one
// run, so the figures are ratios. The goal: at most 2.5x beside two on 2 cores (a job's fair
// share: two busy loops and the job's thread share two cores).
//   fair_share_bench DIR [SKIN]   (the workspace is simulated into DIR once; SKIN: nao)
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tactile/error.h"
#include "tactile/labels/training_job.h"
#include "tactile/skins/skin.h"
#include "tactile/skins/workspace.h"

extern char** environ;

namespace {

// Busy processes, stopped when this goes.
class BusyLoops {
 public:
  explicit BusyLoops(int count) {
    for (int k = 0; k < count; ++k) {
      char shell[] = "/bin/sh", flag[] = "-c", loop[] = "while :; do :; done";
      char* arguments[] = {shell, flag, loop, nullptr};
      pid_t pid = 0;
      if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, arguments, environ) != 0)
        throw tactile::Error("fair_share_bench", "cannot start a busy loop");
      pids_.push_back(pid);
    }
  }
  ~BusyLoops() {
    for (const pid_t pid : pids_) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
  BusyLoops(const BusyLoops&) = delete;
  BusyLoops& operator=(const BusyLoops&) = delete;

 private:
  std::vector<pid_t> pids_;
};

double seconds_of(const tactile::TrainingRequest& request) {
  const auto start = std::chrono::steady_clock::now();
  const auto job = tactile::start_training_job(request);
  job->wait();
  if (job->status() != tactile::JobStatus::kDone)
    throw tactile::Error("fair_share_bench", "the training job ended " +
                                                 std::string(tactile::to_string(job->status())) +
                                                 ": " + job->error());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: fair_share_bench DIR [SKIN]\n");
    return 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    const std::string skin = argc == 3 ? argv[2] : "nao";
    if (!std::filesystem::exists(folder / "labels.db")) {
      tactile::SimulationOptions options;
      options.subjects = 3;
      options.trials = 1;
      tactile::write_simulation(folder.string(), skin, options);
    }
    tactile::TrainingRequest request;
    request.database = (folder / "labels.db").string();
    request.folder = folder.string();
    request.layout = skin;
    request.pipeline = tactile::default_pipeline(skin);
    request.classifier = "all";
    // As the workbench starts it: a core left to the window.
    request.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) - 1);
    seconds_of(request);  // warm up: the recordings in the page cache
    const double idle = seconds_of(request);
    double beside[3] = {idle, 0.0, 0.0};
    for (int busy = 1; busy <= 2; ++busy) {
      const BusyLoops loops(busy);
      beside[busy] = seconds_of(request);
    }
    std::printf(
        "{\"skin\": \"%s\", \"cores\": %u, \"idle_s\": %.2f, \"beside_one_s\": %.2f, "
        "\"beside_two_s\": %.2f, \"ratio_one\": %.2f, \"ratio_two\": %.2f}\n",
        skin.c_str(), std::thread::hardware_concurrency(), idle, beside[1], beside[2],
        beside[1] / idle, beside[2] / idle);
    return 0;
  } catch (const tactile::Error& error) {
    std::fprintf(stderr, "fair_share_bench: %s\n", error.what());
    return 1;
  }
}

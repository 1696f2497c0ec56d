// Job: a step on a worker thread with progress, cancel and its result taken once.
#include "tactile/jobs/job.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "tactile/ml/som.h"
#include "tactile/parameters.h"

namespace tactile {
namespace {

using namespace std::chrono_literals;

TEST(Job, RunsOnAWorkerReportsProgressAndGivesItsResultOnce) {
  const std::thread::id caller = std::this_thread::get_id();
  Job<std::thread::id> job("worker", [](JobProgress& progress) {
    progress.report(0.5, "half way");
    return std::this_thread::get_id();
  });
  job.wait();
  EXPECT_EQ(job.status(), JobStatus::kDone);
  EXPECT_DOUBLE_EQ(job.progress(), 1.0);
  EXPECT_EQ(job.stage(), "half way");
  const std::optional<std::thread::id> ran_on = job.take();
  ASSERT_TRUE(ran_on);
  EXPECT_NE(*ran_on, caller);
  EXPECT_FALSE(job.take());
}

TEST(Job, GivesNothingBeforeItIsDone) {
  std::atomic<bool> release{false};
  Job<int> job("held", [&](JobProgress&) {
    while (!release.load()) std::this_thread::sleep_for(1ms);
    return 7;
  });
  EXPECT_EQ(job.status(), JobStatus::kRunning);
  EXPECT_FALSE(job.take());
  release.store(true);
  job.wait();
  EXPECT_EQ(job.take(), 7);
}

TEST(Job, AFailureKeepsWhatTheWorkThrew) {
  Job<int> job("failing", [](JobProgress&) -> int { throw std::runtime_error("no table"); });
  job.wait();
  EXPECT_EQ(job.status(), JobStatus::kFailed);
  EXPECT_EQ(job.error(), "no table");
  EXPECT_FALSE(job.take());
}

TEST(Job, CancelEndsAWorkThatChecksBetweenSteps) {
  // Counted, not timed: once cancel is asked, the work ends at its next check, so it finishes
  // at most the one step it had begun.
  std::atomic<int> steps{0};
  Job<int> job("endless", [&](JobProgress& progress) {
    for (;;) {
      progress.check();
      steps.fetch_add(1);
      std::this_thread::sleep_for(1ms);
    }
    return 0;
  });
  while (steps.load() < 3) std::this_thread::sleep_for(1ms);
  job.cancel();
  const int steps_when_asked = steps.load();
  job.wait();
  EXPECT_LE(steps.load() - steps_when_asked, 1);
  EXPECT_EQ(job.status(), JobStatus::kCancelled);
  EXPECT_FALSE(job.take());
}

TEST(Job, DestroyingARunningJobCancelsAndWaitsForIt) {
  std::atomic<bool> started{false}, ended{false};
  {
    Job<int> job("dropped", [&](JobProgress& progress) {
      started.store(true);
      while (!progress.cancelled()) std::this_thread::sleep_for(1ms);
      ended.store(true);
      return 0;
    });
    while (!started.load()) std::this_thread::sleep_for(1ms);
  }
  EXPECT_TRUE(ended.load());
}

// The workbench's SOM fit as a job: cancelled mid-fit, it stops within an epoch.
TEST(Job, ASomFitStopsAtTheEpochAfterCancel) {
  ml::Matrix x = ml::Matrix::Random(200, 40);
  std::vector<int> y(200);
  for (size_t i = 0; i < y.size(); ++i) y[i] = static_cast<int>(i % 3);
  std::atomic<int> epochs_seen{0};
  Job<int> job("som", [&](JobProgress& progress) {
    ml::SomClassifier som(Parameters::parse("epochs=100000", "som"));
    som.set_epoch_observer([&](int epoch, int epochs) {
      epochs_seen.store(epoch);
      progress.report(static_cast<double>(epoch) / epochs, "epoch " + std::to_string(epoch));
      progress.check();
    });
    som.fit(x, y, 3, 1);
    return 1;
  });
  while (epochs_seen.load() < 2) std::this_thread::sleep_for(1ms);
  job.cancel();
  const int epoch_when_asked = epochs_seen.load();
  job.wait();
  // Counted, not timed: the epoch under way ends, and no other begins.
  EXPECT_LE(epochs_seen.load() - epoch_when_asked, 1);
  EXPECT_EQ(job.status(), JobStatus::kCancelled);
  EXPECT_GT(job.progress(), 0.0);
  EXPECT_NE(job.stage().find("epoch"), std::string::npos);
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// Deep code polls the cancel flag of the job its thread works for, with no flag passed down.
TEST(JobCancelFlag, IsTheWorkersJobsAndScopesPassItOn) {
  EXPECT_EQ(current_cancel_flag(), nullptr);
  EXPECT_FALSE(cancel_requested());
  std::atomic<bool> seen{false}, started{false};
  Job<int> job("polls", [&](JobProgress& progress) {
    EXPECT_EQ(current_cancel_flag(), progress.flag());
    started = true;
    while (!cancel_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    seen = true;
    progress.check();
    return 0;
  });
  while (!started.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  job.cancel();
  job.wait();
  EXPECT_TRUE(seen.load());
  EXPECT_EQ(job.status(), JobStatus::kCancelled);
  std::atomic<bool> flag{true};
  {
    const CancelScope scope(&flag);
    EXPECT_TRUE(cancel_requested());
  }
  EXPECT_FALSE(cancel_requested());
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

TEST(JobTimeLeft, FollowsThePaceSoFarOnceItSaysSomething) {
  EXPECT_LT(seconds_left(0.0, 10.0), 0.0);   // nothing done yet
  EXPECT_LT(seconds_left(0.01, 10.0), 0.0);  // under 2 %
  EXPECT_LT(seconds_left(0.5, 0.2), 0.0);    // under half a second in
  EXPECT_DOUBLE_EQ(seconds_left(0.25, 30.0), 90.0);
  EXPECT_DOUBLE_EQ(seconds_left(1.0, 30.0), 0.0);
  EXPECT_EQ(progress_text(0.427, -1.0), "42 %");
  EXPECT_EQ(progress_text(0.5, 9.2), "50 %, 10 s left");
  EXPECT_EQ(progress_text(0.5, 70.0), "50 %, 1 min 10 s left");
  EXPECT_EQ(progress_text(0.1, 3 * 3600.0 + 125.0), "10 %, 3 h 2 min left");
  EXPECT_EQ(progress_text(1.5, 0.0), "100 %, 0 s left");
}

TEST(ThreadBudget, EveryCoreUnlessAScopeSaysFewer) {
  const int cores = thread_budget();
  EXPECT_GE(cores, 1);
  {
    const ThreadBudget one(1);
    EXPECT_EQ(thread_budget(), 1);
    {
      const ThreadBudget none(0);  // at least one
      EXPECT_EQ(thread_budget(), 1);
    }
    std::thread([&] { EXPECT_EQ(thread_budget(), cores); }).join();  // per thread
  }
  EXPECT_EQ(thread_budget(), cores);
}

}  // namespace
}  // namespace tactile

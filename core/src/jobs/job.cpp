#include "tactile/jobs/job.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

namespace tactile {

namespace {
thread_local const std::atomic<bool>* thread_cancel_flag = nullptr;
thread_local int thread_budget_now = 0;  // 0: none set, every core
}  // namespace

double seconds_left(double fraction, double elapsed) {
  if (!(fraction >= 0.02) || !(elapsed >= 0.5)) return -1.0;
  return elapsed * (1.0 - std::min(fraction, 1.0)) / fraction;
}

std::string progress_text(double fraction, double left) {
  std::string text =
      std::to_string(static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)))) + " %";
  if (!(left >= 0.0)) return text;
  const auto seconds = static_cast<long long>(std::ceil(left));
  if (seconds < 60) return text + ", " + std::to_string(seconds) + " s left";
  if (seconds < 3600)
    return text + ", " + std::to_string(seconds / 60) + " min " + std::to_string(seconds % 60) +
           " s left";
  return text + ", " + std::to_string(seconds / 3600) + " h " +
         std::to_string(seconds % 3600 / 60) + " min left";
}

int thread_budget() {
  if (thread_budget_now > 0) return thread_budget_now;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

ThreadBudget::ThreadBudget(int threads) : previous_(thread_budget_now) {
  thread_budget_now = std::max(1, threads);
}

ThreadBudget::~ThreadBudget() { thread_budget_now = previous_; }

const std::atomic<bool>* current_cancel_flag() { return thread_cancel_flag; }

CancelScope::CancelScope(const std::atomic<bool>* flag) : previous_(thread_cancel_flag) {
  thread_cancel_flag = flag;
}

CancelScope::~CancelScope() { thread_cancel_flag = previous_; }

const char* to_string(JobStatus status) {
  switch (status) {
    case JobStatus::kRunning:
      return "running";
    case JobStatus::kDone:
      return "done";
    case JobStatus::kFailed:
      return "failed";
    case JobStatus::kCancelled:
      return "cancelled";
  }
  return "?";
}

void JobProgress::report(double fraction, std::string stage) {
  fraction_.store(fraction < 0.0 ? 0.0 : fraction > 1.0 ? 1.0 : fraction);
  if (stage.empty()) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  stage_ = std::move(stage);
}

std::string JobProgress::stage() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return stage_;
}

JobRunner::JobRunner(std::string name, std::function<void(JobProgress&)> work)
    : name_(std::move(name)) {
  worker_ = std::thread([this, work = std::move(work)] {
    // At the process's own priority: a job shares the machine with whatever else runs on it
    // as any program does. (At nice 19 it starved beside one busy process.) The window's
    // thread keeps its frames by being light and mostly asleep, not by outranking the workers.
    const CancelScope scope(progress_.flag());
    try {
      progress_.check();
      work(progress_);
      progress_.report(1.0);
      status_.store(JobStatus::kDone);
    } catch (const JobCancelled&) {
      status_.store(JobStatus::kCancelled);
    } catch (const std::exception& error) {
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        error_ = error.what();
      }
      status_.store(progress_.cancelled() ? JobStatus::kCancelled : JobStatus::kFailed);
    } catch (...) {
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        error_ = "unknown error";
      }
      status_.store(JobStatus::kFailed);
    }
  });
}

JobRunner::~JobRunner() {
  cancel();
  wait();
}

double JobRunner::seconds_left() const {
  if (status() != JobStatus::kRunning) return -1.0;
  return tactile::seconds_left(
      progress_.fraction(),
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
}

std::string JobRunner::error() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void JobRunner::wait() {
  if (worker_.joinable()) worker_.join();
}

}  // namespace tactile

#include "tactile/jobs/job.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include <exception>

namespace tactile {

namespace {
[[maybe_unused]] constexpr int kWorkerNice = 19;
thread_local const std::atomic<bool>* thread_cancel_flag = nullptr;
}

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
#if defined(__linux__)
    // Below the window's thread, as the training job: frames keep their time.
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kWorkerNice);
#endif
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

std::string JobRunner::error() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

void JobRunner::wait() {
  if (worker_.joinable()) worker_.join();
}

}  // namespace tactile

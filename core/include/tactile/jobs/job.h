#pragma once
// A step that may take longer than a frame, run on a worker thread: the window's thread starts
// it, draws its progress, may cancel it, and takes its result in one step when it is done. The
// worker runs at the process's own priority, sharing the machine fairly with other programs;
// the window keeps its frames by being light. Cancel is
// cooperative: the work calls JobProgress::check() between steps (a SOM epoch, a file) and
// ends within one step.
//
//   Job<Pca> job("scatter", [table](JobProgress& progress) { return fit_pca(table, {}); });
//   ... each frame: draw job.progress(); if (auto pca = job.take()) apply(*pca);

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace tactile {

enum class JobStatus { kRunning, kDone, kFailed, kCancelled };
const char* to_string(JobStatus status);

// Thrown by JobProgress::check() in a cancelled job; ends the job as cancelled.
struct JobCancelled {};

// The state a worker and the thread that polls it share.
class JobProgress {
 public:
  // `fraction` of the work done (0..1) and what is being done ("epoch 40 of 200").
  void report(double fraction, std::string stage = {});
  bool cancelled() const { return cancel_.load(); }
  // Throws JobCancelled once the job was cancelled.
  void check() const {
    if (cancelled()) throw JobCancelled{};
  }

  // The callback core functions take as `step(fraction)` (reading a recording, a map's
  // correlations, predicting segments): reports fraction under `stage`, then check().
  std::function<void(double)> steps(std::string stage, double from = 0.0, double to = 1.0) {
    return [this, stage = std::move(stage), from, to](double fraction) {
      report(from + (to - from) * fraction, stage);
      check();
    };
  }

  // For the polling side.
  double fraction() const { return fraction_.load(); }
  std::string stage() const;
  void cancel() { cancel_.store(true); }
  // The flag itself, for code that takes a cancel flag (corpus extraction).
  const std::atomic<bool>* flag() const { return &cancel_; }

 private:
  std::atomic<bool> cancel_{false};
  std::atomic<double> fraction_{0.0};
  mutable std::mutex mutex_;
  std::string stage_;
};

// The cancel flag of the job the calling thread works for; null on a thread that works for
// none. Long loops deep in core that take no flag of their own (a classifier's fit, one
// learner after another) poll it, so a job stops there too. JobRunner sets it for its worker;
// code that starts threads for a job (an evaluation's folds) passes it on with CancelScope.
const std::atomic<bool>* current_cancel_flag();
// True when the calling thread's job was cancelled.
inline bool cancel_requested() {
  const std::atomic<bool>* flag = current_cancel_flag();
  return flag && flag->load();
}
// Sets the calling thread's cancel flag for a scope.
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>* flag);
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

// Seconds a job has left when `fraction` of it is done after `elapsed` seconds, at the pace so
// far; negative while that says nothing yet (under 2 % done or under half a second in).
double seconds_left(double fraction, double elapsed);
// What a progress bar says: "42 %", with ", 1 min 10 s left" when `left` >= 0 (rounded up
// to whole seconds; minutes past 60 s, hours past 60 min).
std::string progress_text(double fraction, double left);

// How many threads code on this thread may keep busy in its own parallel loops (a forest's
// trees, XGBoost's nthread, an evaluation's folds): every core, unless an enclosing
// ThreadBudget says fewer. An evaluation whose folds run side by side gives each fold its
// share, so nested loops never ask for more cores than the job was given (beside busy
// programs, threads beyond the cores wait on each other's spins and barriers).
int thread_budget();
class ThreadBudget {
 public:
  explicit ThreadBudget(int threads);  // at least 1
  ~ThreadBudget();
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

 private:
  int previous_;
};

// The part of a job that does not depend on its result's type.
class JobRunner {
 public:
  JobRunner(std::string name, std::function<void(JobProgress&)> work);
  ~JobRunner();  // cancels and waits for the worker
  JobRunner(const JobRunner&) = delete;
  JobRunner& operator=(const JobRunner&) = delete;

  const std::string& name() const { return name_; }
  JobStatus status() const { return status_.load(); }
  double progress() const { return progress_.fraction(); }
  // Time left at the pace so far (seconds_left above); negative when not known yet.
  double seconds_left() const;
  std::string stage() const { return progress_.stage(); }
  std::string error() const;  // when failed: what the work threw
  void cancel() { progress_.cancel(); }
  void wait();  // blocks until the worker ends (tests and the command line)

 private:
  std::string name_;
  JobProgress progress_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::atomic<JobStatus> status_{JobStatus::kRunning};
  mutable std::mutex mutex_;
  std::string error_;
  std::thread worker_;
};

// Any job, whatever its result: what a window lists, draws and cancels.
class AnyJob {
 public:
  virtual ~AnyJob() = default;
  virtual JobRunner& runner() = 0;
  const std::string& name() { return runner().name(); }
  JobStatus status() { return runner().status(); }
  double progress() { return runner().progress(); }
  double seconds_left() { return runner().seconds_left(); }
  std::string stage() { return runner().stage(); }
  std::string error() { return runner().error(); }
  void cancel() { runner().cancel(); }
  void wait() { runner().wait(); }
};

template <typename Result>
class Job final : public AnyJob {
 public:
  Job(std::string name, std::function<Result(JobProgress&)> work)
      : result_(std::make_shared<Slot>()),
        runner_(std::move(name), [slot = result_, work = std::move(work)](JobProgress& progress) {
          Result result = work(progress);
          const std::lock_guard<std::mutex> lock(slot->mutex);
          slot->value.emplace(std::move(result));
        }) {}

  JobRunner& runner() override { return runner_; }
  // The result once done, moved out on the first call; nothing before and after.
  std::optional<Result> take() {
    if (status() != JobStatus::kDone) return std::nullopt;
    const std::lock_guard<std::mutex> lock(result_->mutex);
    std::optional<Result> taken = std::move(result_->value);
    result_->value.reset();
    return taken;
  }

 private:
  struct Slot {
    std::mutex mutex;
    std::optional<Result> value;
  };
  std::shared_ptr<Slot> result_;
  JobRunner runner_;  // last: joined before the slot goes
};

}  // namespace tactile

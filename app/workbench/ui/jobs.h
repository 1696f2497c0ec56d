#pragma once
// The workbench's jobs (tactile/jobs/job.h): a segmenter run, a prediction, training, the SOM
// map, the scatter's PCA, a somatosensory map, a view's PNG export, the demo workspace, the file
// commands (files.h: import and its preview, exports, labels import, agreement, verify, upgrade).
// All are in one list (WorkbenchState::jobs): each is started with its work and the step that
// applies its end in one call (start_job), and once a frame the window's thread applies the
// ended ones (poll_jobs). Progress, Cancel, the state JSON's "jobs" and a script's `wait jobs`
// read the list; a view declares the kinds it shows (ViewSpec::jobs), and the status bar shows
// the others. A second request of a kind replaces its running job: the old one is retired
// (cancelled, ending on its worker while frames go on, dropped once ended), so the window never
// waits.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/jobs/job.h"
#include "workbench_state.h"

namespace tactile {

// A job's own source of the open recording's samples, opened on its worker: a reader of its own
// on the file (a small cache; the window's source stays the window's), or for a live stream a
// copy of what has arrived, taken now.
std::function<std::shared_ptr<const SampleSource>()> source_for_job(const Document& document);
// How a job reads the whole open recording: through a reader of its own on the file (the
// window's source stays the window's), reporting progress from `from` to `to` of the job; for
// a live stream, a copy of what has arrived, taken now.
std::function<Recording(JobProgress&)> recording_for_job(const Document& document, double from,
                                                         double to);

//---- The list (WorkbenchState::jobs) --------------------------------------------------------

// Cancels `job` and keeps it until its worker has ended.
void retire_job(WorkbenchState& state, std::unique_ptr<AnyJob> job);
// Notes a job's start and end in the state's log (state JSON "jobs").
void log_job_start(WorkbenchState& state, const std::string& name);
void log_job_end(WorkbenchState& state, const std::string& name, const std::string& status);

// The job of this kind whose end the window has not applied yet; nullptr for none.
AnyJob* find_job(const WorkbenchState& state, const std::string& kind);
// The same while it runs.
AnyJob* running_job(const WorkbenchState& state, const std::string& kind);
// Retires the job of this kind (cancelled, its end never applied).
void drop_job(WorkbenchState& state, const std::string& kind);

// The step that applies a job's end on the window's thread: its result (job_result), or what
// a failure or a cancel leaves.
template <typename Result>
using JobApply = std::function<void(WorkbenchState&, Job<Result>&)>;

// What else a job may have: a step for each frame while it runs (training shows its results so
// far), and whether the log (state JSON "jobs") notes it (not a preview made after each key).
struct JobExtras {
  std::function<void(WorkbenchState&)> while_running;
  bool logged = true;
};

// Puts a started job on the list as `kind` (one at a time per kind: a job of that kind still
// running is retired, its end never applied) with the step that applies its end.
template <typename Result>
Job<Result>& adopt_job(WorkbenchState& state, const std::string& kind,
                       std::unique_ptr<Job<Result>> job, JobApply<Result> apply,
                       JobExtras extras = {}) {
  drop_job(state, kind);
  Job<Result>& started = *job;
  WindowJob entry;
  entry.kind = kind;
  entry.apply = [apply = std::move(apply), &started](WorkbenchState& window) {
    apply(window, started);
  };
  entry.while_running = std::move(extras.while_running);
  entry.logged = extras.logged;
  entry.job = std::move(job);
  state.jobs.push_back(std::move(entry));
  if (extras.logged) log_job_start(state, started.name());
  return started;
}

// Starts `work` on a worker as `kind`, named `name` in the status bar and the log.
template <typename Result>
Job<Result>& start_job(WorkbenchState& state, const std::string& kind, const std::string& name,
                       std::function<Result(JobProgress&)> work, JobApply<Result> apply,
                       JobExtras extras = {}) {
  return adopt_job(state, kind, std::make_unique<Job<Result>>(name, std::move(work)),
                   std::move(apply), std::move(extras));
}

// Gives the memory a finished job freed back to the system (glibc keeps freed heap pages of
// a large job's tables resident otherwise: 240 MB after training on 30 minutes of Robovie).
void return_freed_memory();

// An ended job's result, in an apply step: a failure goes to the status bar, a cancel to the
// notice.
template <typename Result>
std::optional<Result> job_result(WorkbenchState& state, Job<Result>& job) {
  std::optional<Result> result = job.take();
  if (job.status() == JobStatus::kFailed) fail(state, job.name() + ": " + job.error());
  if (job.status() == JobStatus::kCancelled) state.notice = job.name() + ": cancelled";
  return result;
}

// Once a frame, and before a view decides whether to start its job: the while-running steps,
// then each ended job taken off the list, logged and applied; retired jobs that ended dropped.
void poll_jobs(WorkbenchState& state);
// Every job whose end the window has not applied yet (retired ones left out).
std::vector<AnyJob*> pending_jobs(const WorkbenchState& state);

// A job's progress bar: `label` (the job's stage when empty), the share done and the time
// left when the job can know it ("fitting the map · 42 %, 1 min 10 s left"). `width` as
// ImGui::ProgressBar's (-1: the rest of the line).
void draw_job_progress(AnyJob& job, const std::string& label = {}, float width = -1.0f);
// A job in a view: what it does, how far, and Cancel; after a cancel (`held`, when given), a
// Compute button that asks for it again. False when there is neither.
bool draw_job(WorkbenchState& state, AnyJob* job, bool* held, const char* what);
// The status bar's line while a job that no view or dialog shows runs (segmenter, prediction, a
// file command): its name, its progress and Cancel. False when none runs.
bool draw_job_status(WorkbenchState& state);

}  // namespace tactile

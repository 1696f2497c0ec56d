#pragma once
// The workbench's jobs (tactile/jobs/job.h): a segmenter run, a prediction, training, the SOM
// map, the scatter's PCA, a somatosensory map, a view's PNG export, the demo workspace, the file
// commands (files.h: import and its preview, exports, labels import, agreement, verify, upgrade).
// Each is a handle in the state, started by a key, a menu or a view; once a frame the window's
// thread takes a finished job's result and applies it in one step. A second request replaces the
// running job: the old one is retired (cancelled, ending on its worker while frames go on, dropped
// once ended), so the window never waits.

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

// Cancels `job` and keeps it until its worker has ended.
void retire_job(WorkbenchState& state, std::unique_ptr<AnyJob> job);
// Drops the retired jobs that have ended (once a frame).
void drop_ended_jobs(WorkbenchState& state);
// Every job whose result the window has not applied yet (retired ones left out).
std::vector<AnyJob*> pending_jobs(const WorkbenchState& state);
// Notes a job's end in the state's log (state JSON "jobs").
void log_job_start(WorkbenchState& state, const std::string& name);
void log_job_end(WorkbenchState& state, const std::string& name, const std::string& status);

// Starts `work` as `job`, replacing (retiring) a job still running there.
template <typename Result>
void start_job(WorkbenchState& state, std::unique_ptr<Job<Result>>& job, const std::string& name,
               std::function<Result(JobProgress&)> work) {
  if (job) retire_job(state, std::move(job));
  job = std::make_unique<Job<Result>>(name, std::move(work));
  log_job_start(state, name);
}

// Gives the memory a finished job freed back to the system (glibc keeps freed heap pages of
// a large job's tables resident otherwise: 240 MB after training on 30 minutes of Robovie).
void return_freed_memory();

// A job's end, on the window's thread: its result when it gave one (a failure goes to the
// status bar). The handle is emptied once the job has ended.
template <typename Result>
std::optional<Result> finished_job(WorkbenchState& state, std::unique_ptr<Job<Result>>& job) {
  if (!job || job->status() == JobStatus::kRunning) return std::nullopt;
  std::optional<Result> result = job->take();
  if (job->status() == JobStatus::kFailed) fail(state, job->name() + ": " + job->error());
  if (job->status() == JobStatus::kCancelled) state.notice = job->name() + ": cancelled";
  log_job_end(state, job->name(), to_string(job->status()));
  job.reset();
  return_freed_memory();
  return result;
}

// A job's progress bar: `label` (the job's stage when empty), the share done and the time
// left when the job can know it ("fitting the map · 42 %, 1 min 10 s left"). `width` as
// ImGui::ProgressBar's (-1: the rest of the line).
void draw_job_progress(AnyJob& job, const std::string& label = {}, float width = -1.0f);
// A job in a view: what it does, how far, and Cancel; after a cancel (`held`, when given), a
// Compute button that asks for it again. False when there is neither.
bool draw_job(WorkbenchState& state, AnyJob* job, bool* held, const char* what);
// The status bar's line while a job that belongs to no view runs (segmenter, prediction, a
// file command):
// its name, its progress and Cancel. False when none runs.
bool draw_job_status(WorkbenchState& state);

}  // namespace tactile

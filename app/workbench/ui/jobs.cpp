#include "jobs.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <imgui.h>

#include "tactile/signal/sample_source.h"
#include "views.h"

namespace tactile {

std::function<std::shared_ptr<const SampleSource>()> source_for_job(const Document& document) {
  const SampleSource& source = document.samples();
  if (dynamic_cast<const FileSampleSource*>(&source))
    return [path = document.path,
            stream = source.info().stream]() -> std::shared_ptr<const SampleSource> {
      FileSourceOptions options;
      options.stream = stream;
      options.cache_bytes = int64_t{8} << 20;
      options.damaged_chunks_as_gaps = true;
      return std::make_shared<FileSampleSource>(path, options);
    };
  // A live stream: what has arrived so far (a bounded buffer), copied now.
  Recording copy = read_all(source);
  auto memory = std::make_shared<const MemorySampleSource>(copy, copy.streams.front());
  return [memory] { return memory; };
}

std::function<Recording(JobProgress&)> recording_for_job(const Document& document, double from,
                                                         double to) {
  return [open = source_for_job(document), from, to](JobProgress& progress) {
    return read_all(*open(), progress.steps("reading the recording", from, to));
  };
}

void return_freed_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

void retire_job(WorkbenchState& state, std::unique_ptr<AnyJob> job) {
  if (!job) return;
  if (job->status() == JobStatus::kRunning) {
    job->cancel();
    log_job_end(state, job->name(), "replaced");
  }
  state.retired_jobs.push_back(std::move(job));
}

AnyJob* find_job(const WorkbenchState& state, const std::string& kind) {
  for (const WindowJob& entry : state.jobs)
    if (entry.kind == kind) return entry.job.get();
  return nullptr;
}

AnyJob* running_job(const WorkbenchState& state, const std::string& kind) {
  AnyJob* job = find_job(state, kind);
  return job && job->status() == JobStatus::kRunning ? job : nullptr;
}

void drop_job(WorkbenchState& state, const std::string& kind) {
  for (auto entry = state.jobs.begin(); entry != state.jobs.end(); ++entry)
    if (entry->kind == kind) {
      std::unique_ptr<AnyJob> job = std::move(entry->job);
      const bool logged = entry->logged;
      state.jobs.erase(entry);
      if (!logged && job->status() == JobStatus::kRunning) {
        job->cancel();
        state.retired_jobs.push_back(std::move(job));
        return;
      }
      retire_job(state, std::move(job));
      return;
    }
}

void poll_jobs(WorkbenchState& state) {
  std::erase_if(state.retired_jobs, [](const std::unique_ptr<AnyJob>& job) {
    return job->status() != JobStatus::kRunning;
  });
  // Taken off the list before they are applied: an apply step may start the next job of its
  // kind (or drop another).
  std::vector<WindowJob> ended;
  for (auto entry = state.jobs.begin(); entry != state.jobs.end();) {
    if (entry->job->status() == JobStatus::kRunning) {
      ++entry;
      continue;
    }
    ended.push_back(std::move(*entry));
    entry = state.jobs.erase(entry);
  }
  for (size_t k = 0; k < state.jobs.size(); ++k)
    if (state.jobs[k].while_running) {
      // A copy: the step may change the list.
      const std::function<void(WorkbenchState&)> step = state.jobs[k].while_running;
      step(state);
    }
  for (WindowJob& entry : ended) {
    if (entry.logged) log_job_end(state, entry.job->name(), to_string(entry.job->status()));
    entry.apply(state);
  }
  if (!ended.empty()) return_freed_memory();
}

std::vector<AnyJob*> pending_jobs(const WorkbenchState& state) {
  std::vector<AnyJob*> jobs;
  for (const WindowJob& entry : state.jobs) jobs.push_back(entry.job.get());
  return jobs;
}

void log_job_start(WorkbenchState& state, const std::string& name) {
  state.job_log.push_back({name, "running", state.frame, -1});
  if (state.job_log.size() > 20) state.job_log.erase(state.job_log.begin());
}

void log_job_end(WorkbenchState& state, const std::string& name, const std::string& status) {
  for (auto record = state.job_log.rbegin(); record != state.job_log.rend(); ++record)
    if (record->name == name && record->status == "running") {
      record->status = status;
      record->finished_frame = state.frame;
      return;
    }
}

void draw_job_progress(AnyJob& job, const std::string& label, float width) {
  const double fraction = job.progress();
  const std::string what = label.empty() ? job.stage() : label;
  const std::string done = progress_text(fraction, job.seconds_left());
  const std::string text = what.empty() ? done : what + " - " + done;
  ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(width, 0), text.c_str());
}

bool draw_job(WorkbenchState& state, AnyJob* job, bool* held, const char* what) {
  if (held && *held) {
    ImGui::Text("%s: cancelled", what);
    if (ImGui::Button("Compute")) *held = false;
    remember_item(state, "button:Compute", "Start the cancelled computation again");
    return true;
  }
  if (!job || job->status() != JobStatus::kRunning) return false;
  ImGui::Text("%s: computing on a worker, the window stays live", job->name().c_str());
  if (ImGui::Button("Cancel")) job->cancel();
  remember_item(state, "button:Cancel", "Stop this computation; the view keeps what it showed");
  ImGui::SameLine();
  draw_job_progress(*job);
  return true;
}

bool draw_job_status(WorkbenchState& state) {
  // The first running job that no view or dialog shows (the segmenter run, Predict, the demo
  // workspace, the file commands: import, export, verify, ...).
  AnyJob* job = nullptr;
  for (const WindowJob& entry : state.jobs)
    if (entry.job->status() == JobStatus::kRunning && job_shown_in(entry.kind).empty()) {
      job = entry.job.get();
      break;
    }
  if (!job) return false;
  if (ImGui::SmallButton("Cancel")) job->cancel();
  remember_item(state, "button:Cancel job",
                "Stop this job; nothing it would have changed is changed");
  ImGui::SameLine();
  const std::string stage = job->stage().empty() ? job->name() : job->name() + ": " + job->stage();
  draw_job_progress(*job, stage, 420.0f);
  ImGui::SameLine();
  ImGui::TextDisabled("the window stays live; the result is applied when it ends");
  return true;
}

}  // namespace tactile

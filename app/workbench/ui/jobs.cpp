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

void drop_ended_jobs(WorkbenchState& state) {
  std::erase_if(state.retired_jobs, [](const std::unique_ptr<AnyJob>& job) {
    return job->status() != JobStatus::kRunning;
  });
}

std::vector<AnyJob*> pending_jobs(const WorkbenchState& state) {
  std::vector<AnyJob*> jobs;
  for (AnyJob* job : std::initializer_list<AnyJob*>{
           state.labelling.segment_job.get(), state.labelling.fit_job.get(),
           state.analysis.predict_job.get(), state.analysis.som_job.get(),
           state.analysis.scatter_job.get(), state.analysis.map_job.get(), state.export_job.get(),
           state.analysis.job.get(), state.demo_job.get(), state.files.import.preview_job.get(),
           state.files.labels_import.read_job.get()})
    if (job) jobs.push_back(job);
  for (const auto& [kind, job] : state.files.jobs)
    if (job) jobs.push_back(job.get());
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
  // The first that runs of the segmenter run, Predict, the demo workspace and the file commands
  // (import, export, verify, ...).
  std::vector<AnyJob*> candidates = {state.labelling.segment_job.get(),
                                     state.labelling.fit_job.get(),
                                     state.analysis.predict_job.get(), state.demo_job.get()};
  for (const auto& [kind, file_job] : state.files.jobs) candidates.push_back(file_job.get());
  AnyJob* job = nullptr;
  for (AnyJob* candidate : candidates)
    if (candidate && candidate->status() == JobStatus::kRunning) {
      job = candidate;
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

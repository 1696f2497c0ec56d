// The file commands as jobs: each runs core's function on a worker, with its own files and
// connections (never the window's document), and hands back a FileOutcome that the window
// applies in one step.
#include <algorithm>
#include <filesystem>

#include "files.h"
#include "jobs.h"
#include "tactile/error.h"
#include "tactile/features/feature_table.h"
#include "tactile/labels/label_file_commands.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"
#include "tactile/verify/verify.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

// A file command's outcome applied once it ends; an import's failure also stays in its dialog.
void apply_file_job(WorkbenchState& state, Job<FileOutcome>& job);

void start_file_job(WorkbenchState& state, const std::string& kind,
                    std::function<FileOutcome(JobProgress&)> work) {
  start_job<FileOutcome>(state, kind, kind, std::move(work), apply_file_job);
}

std::string joined_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

void apply_file_outcome(WorkbenchState& state, FileOutcome outcome) {
  if (!outcome.notice.empty()) state.notice = outcome.notice;
  state.error = outcome.problem;
  if (!outcome.report_title.empty()) {
    ReportWindow& report = state.files.report;
    report.open = report.focus = true;
    report.title = std::move(outcome.report_title);
    report.text = std::move(outcome.report_text);
    report.json = std::move(outcome.report_json);
    report.file_name = std::move(outcome.report_name);
  }
  if (outcome.reload_labels && state.document) {
    try {
      state.document->label_store();  // the store the labels went into, if it is new
      state.document->reload_labels();
      // Our own import, not another writer's edit: its notice stays.
      state.document->mark_store_seen();
    } catch (const Error& failure) {
      state.error = failure.what();
    }
  }
  if (outcome.refresh_workspace) state.files.refresh_workspace = true;
  if (outcome.reopen && state.document) state.open_request = state.document->path;
  if (!outcome.open.empty()) state.open_request = outcome.open;
}

void apply_file_job(WorkbenchState& state, Job<FileOutcome>& job) {
  const std::string error = job.status() == JobStatus::kFailed ? job.error() : std::string();
  std::optional<FileOutcome> outcome = job_result(state, job);
  if (job.name() == "import") {
    ImportDialog& dialog = state.files.import;
    dialog.failure = error;
    if (outcome) dialog.open = false;  // written: the new recording opens
  }
  if (outcome) apply_file_outcome(state, std::move(*outcome));
}

}  // namespace

std::string label_store_path(const WorkbenchState& state) {
  if (!state.document) return {};
  if (!state.document->labels_path.empty()) return state.document->labels_path;
  return (fs::path(state.document->path).parent_path() / "labels.db").string();
}

std::vector<std::string> open_recording_files(const WorkbenchState& state) {
  std::vector<std::string> files;
  if (!state.document) return files;
  files.push_back(state.document->path);
  std::error_code error;
  const std::string store = label_store_path(state);
  if (fs::exists(store, error)) files.push_back(store);
  return files;
}

//---- Import

void start_import(WorkbenchState& state, const FileImportOptions& options) {
  state.files.import.failure.clear();
  const std::string name = fs::path(options.file).filename().string();
  start_file_job(state, "import", [options, name](JobProgress& progress) {
    const FileImportReport report = import_file(options, progress.steps("importing " + name));
    FileOutcome outcome;
    std::vector<std::string> lines;
    for (const ImportedFile& file : report.files) lines.push_back(imported_file_line(file));
    if (report.stored > 0)
      lines.push_back("stored " + std::to_string(report.stored) + " ground-truth labels in " +
                      options.labels);
    for (const std::string& line : lines)
      outcome.notice += (outcome.notice.empty() ? "" : "; ") + line;
    if (!report.files.empty()) outcome.open = report.files.front().path;
    outcome.refresh_workspace = true;
    return outcome;
  });
}

void start_import_preview(WorkbenchState& state, const FileImportOptions& options,
                          const std::string& fields) {
  ImportDialog& dialog = state.files.import;
  dialog.preview_job_for = fields;
  // Not logged: one runs after each change of the fields. `wait jobs` waits for it.
  JobExtras quiet;
  quiet.logged = false;
  start_job<ImportPreview>(
      state, "import preview", "import preview",
      [options](JobProgress& progress) {
        return preview_import(options, 10, progress.steps("reading " + options.file));
      },
      [](WorkbenchState& window, Job<ImportPreview>& job) {
        ImportDialog& shown = window.files.import;
        if (std::optional<ImportPreview> preview = job.take()) {
          shown.preview = std::move(*preview);
        } else {
          ImportPreview failed;  // an exception that is no refusal (memory, ...): shown as one
          failed.refusal = job.error();
          shown.preview = std::move(failed);
        }
        shown.preview_for = shown.preview_job_for;
      },
      std::move(quiet));
}

//---- Labels

void start_labels_export(WorkbenchState& state, const std::string& out) {
  if (!state.document) return;
  const LabelsExportDialog& dialog = state.files.labels_export;
  const std::string database = state.document->labels_path;
  if (database.empty()) {
    fail(state, "export labels: " + state.document->path + " has no label store beside it");
    return;
  }
  LabelFilter filter;
  if (!dialog.every_recording) filter.recording = state.document->recording_id();
  try {
    if (!dialog.source.empty()) filter.source = label_source_option(dialog.source);
  } catch (const Error& failure) {
    fail(state, failure.what());
    return;
  }
  const std::string format = dialog.format;
  const std::vector<std::string> vocabulary = state.document->classes;
  start_file_job(
      state, "export labels", [database, out, format, filter, vocabulary](JobProgress& progress) {
        progress.report(0.0, "writing " + out);
        const LabelExport written = export_label_file(database, out, format, filter, vocabulary);
        FileOutcome outcome;
        outcome.notice = "wrote " + out + ": " + std::to_string(written.labels) + " labels";
        if (!written.damaged.empty())
          outcome.problem = database + ": " + std::to_string(written.damaged.size()) +
                            " damaged row(s) left out of " + out + " (" + written.damaged.front() +
                            ")";
        return outcome;
      });
}

void start_labels_import(WorkbenchState& state, const std::string& file,
                         const InteropImport& options) {
  if (!state.document) return;
  const std::string database = label_store_path(state);
  // Label Studio's epoch milliseconds: the open recording's folder holds its start.
  InteropImport reading = options;
  if (reading.recordings.empty())
    reading.recordings = fs::path(state.document->path).parent_path().string();
  start_file_job(state, "import labels", [database, file, reading](JobProgress& progress) {
    progress.report(0.0, "reading " + file);
    FileOutcome outcome;
    outcome.notice = imported_labels_line(import_label_file(database, file, reading), database);
    outcome.reload_labels = true;
    return outcome;
  });
}

void start_agreement(WorkbenchState& state) {
  if (!state.document) return;
  const AgreementDialog& dialog = state.files.agreement;
  AgreementQuery query;
  query.database = label_store_path(state);
  query.a = dialog.a;
  query.b = dialog.b;
  query.recording = state.document->recording_id();
  query.recordings = fs::path(state.document->path).parent_path().string();
  query.iou = dialog.iou;
  start_file_job(state, "agreement", [query](JobProgress& progress) {
    const AgreementReport report = lane_agreement(query, progress.steps("comparing the lanes"));
    FileOutcome outcome;
    outcome.report_title = "Agreement: " + query.a + " vs " + query.b;
    outcome.report_text = agreement_text(report);
    outcome.report_json = agreement_json(report);
    outcome.report_name = query.recording + "-agreement.txt";
    outcome.notice = "agreement of " + query.a + " and " + query.b + " on " + query.recording;
    if (!report.damaged.empty()) {
      outcome.problem = query.database + ": " + std::to_string(report.damaged.size()) +
                        " damaged row(s) left out of the agreement";
      outcome.report_text = joined_lines(report.damaged) + outcome.report_text;
    }
    return outcome;
  });
}

//---- Features

void start_features_export(WorkbenchState& state, const std::string& out) {
  if (!state.document) return;
  const FeaturesExportDialog& dialog = state.files.features_export;
  if (state.document->labels_path.empty()) {
    fail(state, "export features: " + state.document->path + " has no label store beside it");
    return;
  }
  FeatureTableOptions options;
  options.pipeline =
      dialog.pipeline.empty() ? default_pipeline(state.document->layout.id) : dialog.pipeline;
  options.params = dialog.params.data();
  options.database = state.document->labels_path;
  options.source = dialog.source;
  options.recordings = fs::path(state.document->path).parent_path().string();
  options.out = out;
  if (dialog.workspace)
    options.layout = state.document->layout.id;
  else
    options.recording = state.document->recording_id();
  start_file_job(state, "export features", [options](JobProgress& progress) {
    FeatureTable table;
    try {
      table = extract_feature_table(
          options,
          [&progress](int64_t done, int64_t total) {
            progress.report(
                static_cast<double>(done) / static_cast<double>(std::max<int64_t>(total, 1)),
                std::to_string(done) + " of " + std::to_string(total) + " recordings");
          },
          progress.flag());
    } catch (const Error&) {
      progress.check();  // a cancelled extraction ends as cancelled, not failed
      throw;
    }
    progress.check();
    write_feature_table(table, options);
    FileOutcome outcome;
    outcome.notice = feature_table_line(table, options);
    if (!table.corpus.skipped.empty()) outcome.notice += " (see " + options.out + ".log)";
    return outcome;
  });
}

//---- Verify and upgrade

void start_verify(WorkbenchState& state, const std::vector<std::string>& paths) {
  start_file_job(state, "verify", [paths](JobProgress& progress) {
    const VerifyReport report = verify_paths(paths, progress.steps("verifying"));
    FileOutcome outcome;
    std::vector<std::string> lines;
    for (const FileProblem& problem : report.problems) lines.push_back(problem.message);
    lines.push_back(verify_summary_line(report));
    std::vector<std::string> names;
    for (const std::string& path : paths) names.push_back(fs::path(path).filename().string());
    outcome.report_title = "Verify: " + joined(names);
    outcome.report_text = joined_lines(lines);
    outcome.report_json = verify_report_json(report);
    outcome.report_name = "verify.txt";
    outcome.notice = lines.back();
    if (!report.problems.empty()) outcome.problem = lines.back() + " (File > Verify: the report)";
    return outcome;
  });
}

void start_upgrade(WorkbenchState& state, const std::vector<std::string>& paths) {
  const std::string open = state.document ? state.document->path : std::string();
  start_file_job(state, "upgrade", [paths, open](JobProgress& progress) {
    FileOutcome outcome;
    std::vector<std::string> lines;
    for (size_t index = 0; index < paths.size(); ++index) {
      progress.report(static_cast<double>(index) / static_cast<double>(paths.size()),
                      "upgrading " + fs::path(paths[index]).filename().string());
      // As the command line: the first file that fails stops the upgrade, the ones before stay.
      try {
        const UpgradeResult result = upgrade_file(paths[index]);
        lines.push_back(upgrade_line(paths[index], result));
        if (result.rewritten() && paths[index] == open) outcome.reopen = true;
      } catch (const Error& failure) {
        lines.push_back(failure.what());
        outcome.problem = std::string("upgrade: ") + failure.what();
        break;
      }
    }
    outcome.report_title = "Upgrade";
    outcome.report_text = joined_lines(lines);
    outcome.report_name = "upgrade.txt";
    outcome.notice = lines.empty() ? "nothing to upgrade" : lines.back();
    return outcome;
  });
}

}  // namespace tactile

#pragma once
// The file commands of the window as plain data (files.h draws and runs them): the dialogs'
// fields, the jobs that read and write the files, the report shown. Every command is core's
// (formats/import.h, labels/label_file_commands.h, features/feature_table.h, verify/verify.h), as
// the command line calls it; the window only gathers its options and shows what it did.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/import.h"
#include "tactile/jobs/job.h"
#include "tactile/labels/elan_and_label_studio.h"

namespace tactile {

// What a file job hands the window to apply once it has ended (jobs.h, apply_file_job).
struct FileOutcome {
  std::string notice;   // the status bar's line
  std::string problem;  // shown as the error line ("" clears it): damage left out, problems
  std::string report_title, report_text, report_json;  // a report to show; "" none
  std::string report_name;                             // the file name its Save... proposes
  std::string open;                // a recording to open (an import's first file)
  bool refresh_workspace = false;  // files were written: the workspace list is read again
  bool reload_labels = false;      // the open recording's labels changed
  bool reopen = false;             // the open recording was rewritten (upgrade)
};

// File > Import...: the fields by `tactile import`'s flags ("" = not given) and the preview.
struct ImportDialog {
  bool open = false;
  bool focus = false;  // take the keyboard on the next frame
  std::array<char, 1024> file{}, out{}, labels{};
  std::array<char, 128> layout{}, recording_id{}, annotator{};
  // The format's own fields, by flag (formats/importer.h), made for the importer of the file
  // chosen; kept when the file changes, so that a flag two formats share keeps its value.
  std::map<std::string, std::array<char, 1024>> fields;
  std::map<std::string, bool> switches;
  // The preview of what the fields read, made on a worker; a change of the fields starts the
  // next once the running one has ended.
  // (its job: "import preview")
  std::string preview_job_for;  // the fields (as text) the running preview reads
  std::string preview_for;      // the fields the preview shown was made for
  std::optional<ImportPreview> preview;
  std::string failure;  // why the last import stopped; "" after one that wrote
};

// File > Export labels...: which labels, in which format (the file comes from a save dialog).
struct LabelsExportDialog {
  bool open = false, focus = false;
  bool every_recording = false;  // the whole store, not only the open recording's labels
  std::string source;  // "" = every source, else manual / segmenter / model / ground-truth
  // The label format by name (labels/label_format.h): CSV, JSON ({"labels": [...]}), ELAN
  // .eaf (this recording), Label Studio JSON (docs/INTEROP.md), or one a program added.
  std::string format = "CSV";
};

// Labels > Import labels... of an ELAN .eaf or a Label Studio JSON: its tiers or annotators,
// each chosen or not and mapped to a lane, and the recording they belong to.
struct LabelsImportDialog {
  bool open = false, focus = false;
  std::string file;
  // What the file holds is read on a worker (job "read labels file").
  std::optional<InteropSources> sources;
  std::string failure;  // the file could not be read
  struct Choice {
    bool chosen = true;
    std::array<char, 128> lane{};
  };
  std::vector<Choice> choices;  // one per source
  std::array<char, 256> recording{};
  std::array<char, 32> start_ms{};  // Label Studio: --start-ms
};

// File > Export features...: `tactile features` for the open recording or its workspace.
struct FeaturesExportDialog {
  bool open = false, focus = false;
  std::string pipeline;  // "" = the skin's own
  std::array<char, 256> params{};
  std::string source = "ground-truth";
  bool workspace = false;  // every recording of this skin in the label store, not only this one
  bool arff = false;       // else CSV
};

// Labels > Agreement report...: two lanes of the open recording.
struct AgreementDialog {
  bool open = false, focus = false;
  std::string a, b;  // lane ids
  float iou = 0.5f;
};

// A report shown in a window of its own (verify, upgrade, agreement), savable.
struct ReportWindow {
  bool open = false, focus = false;
  std::string title, text, json, file_name;
};

struct FilesState {
  ImportDialog import;
  LabelsExportDialog labels_export;
  LabelsImportDialog labels_import;
  FeaturesExportDialog features_export;
  AgreementDialog agreement;
  ReportWindow report;
  // The file jobs are in the window's list (jobs.h) by kind: "import", "export labels",
  // "export features", "import labels", "agreement", "verify", "upgrade".
  // A dialog (or the file browser) had the keyboard on the last frame: the window's own keys
  // (labelling, playback) leave it alone.
  bool has_keys = false;
  // Requests for the Workbench, carried out after the frame.
  std::optional<std::string> folder_request;  // Open folder: the new workspace
  bool refresh_workspace = false;
};

}  // namespace tactile

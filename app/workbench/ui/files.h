#pragma once
// Everything the command line does to a user's files, from the window: File > Open folder,
// Import, Export labels, Export features, Verify, Upgrade; Labels > Import labels, Agreement
// report. Each command runs core's function (the same one the command line calls) as a job
// with progress (files_state.h); its dialog is a window of its own that Escape closes.
//
//   file_menu.cpp     the menu items, the file browser's choices, the state JSON
//   import_dialog.cpp File > Import: the options of `tactile import` and a preview
//   file_dialogs.cpp  the export and agreement dialogs, the report window
//   file_jobs.cpp     the jobs and how their outcomes are applied

#include <array>
#include <cstdio>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "file_browser.h"
#include "tactile/formats/import.h"
#include "tactile/labels/elan_and_label_studio.h"
#include "workbench_state.h"

namespace tactile {

//---- Menus (file_menu.cpp), called by the menu bar
// Open folder..., Import... (after File > Open...).
void draw_file_open_items(WorkbenchState& state);
// Export labels..., Export features..., Verify, Upgrade (after Export view as PNG).
void draw_file_export_items(WorkbenchState& state);
// Import labels..., Agreement report... (in the Labels menu).
void draw_labels_file_items(WorkbenchState& state);

// A choice of the file browser, handed to whoever opened it (File > Open: the open request).
void take_browser_choice(WorkbenchState& state, const BrowseChoice& choice);
// The dialogs and the report window; once a frame, after the main window.
void draw_file_dialogs(WorkbenchState& state);
// True while a dialog or the file browser has the keyboard: the window's keys wait.
bool files_have_keys(const WorkbenchState& state);
// The state JSON's "files": the browser, the dialogs open, the import preview, the report.
nlohmann::json files_json(const WorkbenchState& state);

//---- Dialogs (import_dialog.cpp, file_dialogs.cpp)
// A text field of a dialog set to `text` (cut to its size).
template <size_t Size>
void set_field(std::array<char, Size>& field, const std::string& text) {
  std::snprintf(field.data(), field.size(), "%s", text.c_str());
}
// A field's text without the spaces and tabs around it.
std::string trimmed_field(const char* text);

void open_import_dialog(WorkbenchState& state);
void draw_import_dialog(WorkbenchState& state);
// The import's options from the dialog's fields, with the window's defaults for what was left
// empty (the output in the workspace, labels.db beside it). False with `refusal` set when a
// field does not parse ("--rate: 'x' is not a positive number").
bool import_options_of(const WorkbenchState& state, FileImportOptions& options,
                       std::string& refusal);
void draw_labels_export_dialog(WorkbenchState& state);
// Labels > Import labels... of an .eaf or a .json: what the file holds is read on a worker;
// an ELAN or Label Studio file shows its tiers or annotators to choose and map to lanes, our
// own CSV or JSON is imported at once.
void open_labels_import_dialog(WorkbenchState& state, const std::string& file);
void draw_labels_import_dialog(WorkbenchState& state);
void draw_features_export_dialog(WorkbenchState& state);
void draw_agreement_dialog(WorkbenchState& state);
void draw_report_window(WorkbenchState& state);
// Escape closes the window being drawn when it has the keyboard; notes that it has it.
bool dialog_keys(WorkbenchState& state, bool& open);

//---- Jobs (file_jobs.cpp)
void start_import(WorkbenchState& state, const FileImportOptions& options);
void start_import_preview(WorkbenchState& state, const FileImportOptions& options,
                          const std::string& fields);
void start_labels_export(WorkbenchState& state, const std::string& out);
void start_features_export(WorkbenchState& state, const std::string& out);
void start_labels_import(WorkbenchState& state, const std::string& file,
                         const InteropImport& options = {});
void start_agreement(WorkbenchState& state);
void start_verify(WorkbenchState& state, const std::vector<std::string>& paths);
void start_upgrade(WorkbenchState& state, const std::vector<std::string>& paths);
// The open recording and its label store (when it has one): what Verify and Upgrade of "the
// open recording" check.
std::vector<std::string> open_recording_files(const WorkbenchState& state);
// The open recording's label store: its own, else labels.db beside it.
std::string label_store_path(const WorkbenchState& state);
// The jobs the dialogs show themselves (the status bar leaves them out): the import's preview,
// what a label file holds.
inline constexpr const char* kDialogJobs[] = {"import preview", "read labels file"};

}  // namespace tactile

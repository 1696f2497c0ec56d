// The file commands' menu items, where the file browser's choices go, and how they show in
// the state JSON.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "files.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/labels/label_format.h"
#include "tactile/text.h"
#include "video.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

std::string browse_start(const WorkbenchState& state) {
  if (state.document) return fs::path(state.document->path).parent_path().string();
  return state.workspace.empty() ? "." : state.workspace;
}

void browse(WorkbenchState& state, BrowseMode mode, const std::string& purpose,
            const std::string& title, std::vector<std::string> extensions) {
  BrowseRequest request;
  request.mode = mode;
  request.purpose = purpose;
  request.title = title;
  request.directory = browse_start(state);
  request.extensions = std::move(extensions);
  state.file_browser.open(std::move(request));
}

void save_report(WorkbenchState& state, const std::string& path) {
  const ReportWindow& report = state.files.report;
  const bool json = fs::path(path).extension() == ".json" && !report.json.empty();
  try {
    write_file_atomically(path, json ? report.json : report.text, "report");
    state.notice = "wrote " + path;
  } catch (const Error& failure) {
    fail(state, failure.what());
  }
}

const std::vector<std::string> kRecordingAndStoreExtensions = {".h5", ".hdf5", ".db", ".sqlite",
                                                               ".sqlite3"};

}  // namespace

//---- Menus

void draw_file_open_items(WorkbenchState& state) {
  if (ImGui::MenuItem("Open folder..."))
    browse(state, BrowseMode::kChooseFolder, "open folder", "Open a folder of recordings", {});
  remember_item(state, "menu:File/Open folder...");
  if (ImGui::MenuItem("Import...")) open_import_dialog(state);
  remember_item(state, "menu:File/Import...");
}

void draw_file_export_items(WorkbenchState& state) {
  const bool document = state.document != nullptr;
  if (ImGui::MenuItem("Export labels...", nullptr, false, document)) {
    state.files.labels_export.open = state.files.labels_export.focus = true;
  }
  remember_item(state, "menu:File/Export labels...");
  if (ImGui::MenuItem("Export features...", nullptr, false, document)) {
    state.files.features_export.open = state.files.features_export.focus = true;
  }
  remember_item(state, "menu:File/Export features...");
  for (const char* command : {"Verify", "Upgrade"}) {
    const bool verify = command == std::string("Verify");
    if (ImGui::BeginMenu(command)) {
      const std::string menu = std::string("menu:File/") + command;
      if (ImGui::MenuItem("Open recording and its labels", nullptr, false, document)) {
        if (verify)
          start_verify(state, open_recording_files(state));
        else
          start_upgrade(state, open_recording_files(state));
      }
      remember_item(state, menu + "/Open recording and its labels");
      if (ImGui::MenuItem("File..."))
        browse(state, BrowseMode::kOpenFile, verify ? "verify" : "upgrade",
               std::string(command) + ": a recording or a label store",
               kRecordingAndStoreExtensions);
      remember_item(state, menu + "/File...");
      if (verify && ImGui::MenuItem("Folder..."))
        browse(state, BrowseMode::kChooseFolder, "verify", "Verify: every file of a folder", {});
      if (verify) remember_item(state, menu + "/Folder...");
      ImGui::EndMenu();
    }
    remember_item(state, std::string("menu:File/") + command);
  }
}

void draw_labels_file_items(WorkbenchState& state) {
  if (ImGui::MenuItem("Import labels...")) {
    // Every label format's files (labels/label_format.h).
    std::vector<std::string> names, extensions;
    for (const LabelFormat* format : label_formats()) {
      names.push_back(format->name());
      if (std::find(extensions.begin(), extensions.end(), format->extension()) == extensions.end())
        extensions.push_back(format->extension());
    }
    browse(state, BrowseMode::kOpenFile, "import labels", "Import labels (" + joined(names) + ")",
           extensions);
  }
  remember_item(state, "menu:Labels/Import labels...");
  if (ImGui::MenuItem("Agreement report...")) {
    AgreementDialog& dialog = state.files.agreement;
    dialog.open = dialog.focus = true;
    // Ground truth against the operator's lane when both are there; else the first two.
    const Lanes& lanes = state.document->lanes;
    std::vector<std::string> ids;
    for (const LaneKey& key : lanes.keys) ids.push_back(key.id());
    const auto has = [&ids](const std::string& id) {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    };
    if (!has(dialog.a))
      dialog.a = has("ground-truth") ? "ground-truth" : (ids.empty() ? "" : ids[0]);
    if (!has(dialog.b) || dialog.b == dialog.a) {
      dialog.b.clear();
      for (const std::string& id : ids)
        if (id != dialog.a) {
          dialog.b = id;
          if (id == state.labelling.active_lane()) break;
        }
    }
  }
  remember_item(state, "menu:Labels/Agreement report...");
}

//---- The browser's choices

void take_browser_choice(WorkbenchState& state, const BrowseChoice& choice) {
  const std::string& purpose = choice.purpose;
  ImportDialog& import = state.files.import;
  if (purpose == "open") {
    state.open_request = choice.path;
  } else if (purpose == "open folder") {
    state.files.folder_request = choice.path;
  } else if (purpose == "import file") {
    set_field(import.file, choice.path);
    import.focus = true;
  } else if (purpose == "import out") {
    set_field(import.out, choice.path);
    import.focus = true;
  } else if (purpose.starts_with("import option ")) {
    // A file option of the format (Browse... beside it): "import option --labels-file".
    set_field(import.fields[purpose.substr(14)], choice.path);
    import.focus = true;
  } else if (purpose == "import labels db") {
    set_field(import.labels, choice.path);
    import.focus = true;
  } else if (purpose == "export labels") {
    start_labels_export(state, choice.path);
  } else if (purpose == "export features") {
    start_features_export(state, choice.path);
  } else if (purpose == "import labels") {
    // A file with sources to choose (ELAN tiers, Label Studio annotators) opens the dialog;
    // one of our own formats is imported at once (open_labels_import_dialog).
    open_labels_import_dialog(state, choice.path);
  } else if (purpose == "attach video") {
    attach_video(state, choice.path);
  } else if (purpose == "export clip") {
    export_clip(state, choice.path);
  } else if (purpose == "verify") {
    start_verify(state, {choice.path});
  } else if (purpose == "upgrade") {
    start_upgrade(state, {choice.path});
  } else if (purpose == "save report") {
    save_report(state, choice.path);
  }
}

//---- Once a frame

void draw_file_dialogs(WorkbenchState& state) {
  state.files.has_keys = state.file_browser.is_open();
  draw_import_dialog(state);
  draw_labels_export_dialog(state);
  draw_labels_import_dialog(state);
  draw_features_export_dialog(state);
  draw_agreement_dialog(state);
  draw_report_window(state);
}

bool files_have_keys(const WorkbenchState& state) {
  return state.files.has_keys || state.file_browser.is_open();
}

nlohmann::json files_json(const WorkbenchState& state) {
  const FilesState& files = state.files;
  nlohmann::json browser = nullptr;
  if (state.file_browser.is_open())
    browser = {{"mode", to_string(state.file_browser.request().mode)},
               {"purpose", state.file_browser.request().purpose},
               {"title", state.file_browser.request().title},
               {"directory", state.file_browser.directory()}};
  nlohmann::json dialogs = nlohmann::json::array();
  if (files.import.open) dialogs.push_back("import");
  if (files.labels_export.open) dialogs.push_back("export labels");
  if (files.labels_import.open) dialogs.push_back("import labels");
  if (files.features_export.open) dialogs.push_back("export features");
  if (files.agreement.open) dialogs.push_back("agreement");
  if (files.report.open) dialogs.push_back("report");
  nlohmann::json preview = nullptr;
  if (files.import.preview) {
    const ImportPreview& shown = *files.import.preview;
    preview = {{"refusal", shown.refusal},
               {"format", shown.format},
               {"shape", shown.shape},
               {"layout", shown.layout},
               {"channels", shown.channels},
               {"rate_hz", shown.rate_hz},
               {"recordings", shown.recordings},
               {"samples", shown.samples},
               {"times", shown.times},
               {"frames", shown.frames},
               {"frame_classes", shown.frame_classes},
               {"classes", shown.classes},
               {"labels", shown.labels}};
  }
  FileImportOptions options;
  std::string refusal;
  const bool parsed = import_options_of(state, options, refusal);
  nlohmann::json import = {{"file", options.file},
                           {"out", parsed ? options.out : ""},
                           {"labels", parsed ? options.labels : ""},
                           {"refusal", refusal},
                           {"preview", preview},
                           {"failure", files.import.failure}};
  nlohmann::json report = nullptr;
  if (files.report.open) report = {{"title", files.report.title}, {"text", files.report.text}};
  return {{"browser", browser}, {"dialogs", dialogs}, {"import", import}, {"report", report}};
}

}  // namespace tactile

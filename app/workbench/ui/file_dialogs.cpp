// The small dialogs of the file commands: Export labels, Export features, Agreement report,
// and the window that shows a report (verify, upgrade, agreement) and saves it.
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <utility>

#include "files.h"
#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/atomic_file.h"
#include "tactile/skins/skin.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

// A dialog window in the middle of the screen; false when it is not drawn this frame.
bool begin_file_dialog(const char* title, bool& open, bool& focus, ImVec2 size) {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x * 0.5f,
                                 viewport->WorkPos.y + viewport->WorkSize.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(size, ImGuiCond_Appearing);
  if (std::exchange(focus, false)) ImGui::SetNextWindowFocus();
  ImGui::SetNextWindowBgAlpha(1.0f);
  if (ImGui::Begin(title, &open, ImGuiWindowFlags_NoCollapse)) return true;
  ImGui::End();
  return false;
}

void source_choice(WorkbenchState& state, const std::string& dialog, std::string& source,
                   bool any) {
  ImGui::TextUnformatted("labels of");
  std::vector<std::string> sources = {"ground-truth", "manual", "segmenter", "model"};
  if (any) sources.insert(sources.begin(), "");
  for (const std::string& name : sources) {
    ImGui::SameLine();
    if (ImGui::RadioButton(name.empty() ? "every source" : name.c_str(), source == name))
      source = name;
    remember_item(state, "radio:" + dialog + "/" + (name.empty() ? "every source" : name));
  }
}

bool radio_item(WorkbenchState& state, const std::string& name, const char* label, bool active) {
  const bool pressed = ImGui::RadioButton(label, active);
  remember_item(state, name);
  return pressed;
}

BrowseRequest save_request(const WorkbenchState& state, const std::string& purpose,
                           const std::string& title, const std::string& name,
                           std::vector<std::string> extensions) {
  BrowseRequest request;
  request.mode = BrowseMode::kSaveFile;
  request.purpose = purpose;
  request.title = title;
  request.directory = state.document ? fs::path(state.document->path).parent_path().string()
                                     : (state.workspace.empty() ? "." : state.workspace);
  request.file_name = name;
  request.extensions = std::move(extensions);
  return request;
}

}  // namespace

bool dialog_keys(WorkbenchState& state, bool& open) {
  const bool focused = ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows);
  if (!focused) return false;
  state.files.has_keys = true;
  if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) open = false;
  return true;
}

//---- File > Export labels...

void draw_labels_export_dialog(WorkbenchState& state) {
  LabelsExportDialog& dialog = state.files.labels_export;
  if (!dialog.open) return;
  if (!state.document) {
    dialog.open = false;
    return;
  }
  if (!begin_file_dialog("Export labels###export labels", dialog.open, dialog.focus,
                         ImVec2(560, 220)))
    return;
  dialog_keys(state, dialog.open);
  ImGui::TextDisabled("as tactile labels export: %s", state.document->labels_path.empty()
                                                          ? "(no label store beside the recording)"
                                                          : state.document->labels_path.c_str());
  if (radio_item(state, "radio:export-labels/this recording",
                 ("this recording (" + state.document->recording_id() + ")").c_str(),
                 !dialog.every_recording))
    dialog.every_recording = false;
  ImGui::SameLine();
  if (radio_item(state, "radio:export-labels/every recording", "every recording of the store",
                 dialog.every_recording))
    dialog.every_recording = true;
  source_choice(state, "export-labels", dialog.source, true);
  if (radio_item(state, "radio:export-labels/CSV", "CSV (RFC 4180)", !dialog.json))
    dialog.json = false;
  ImGui::SameLine();
  if (radio_item(state, "radio:export-labels/JSON", "JSON", dialog.json)) dialog.json = true;
  ImGui::Separator();
  AnyJob* running = running_file_job(state, "export labels");
  ImGui::BeginDisabled(running != nullptr);
  if (ImGui::Button("Export...")) {
    const std::string stem =
        dialog.every_recording ? std::string("labels") : state.document->recording_id() + "-labels";
    state.file_browser.open(save_request(state, "export labels", "Export labels to",
                                         stem + (dialog.json ? ".json" : ".csv"),
                                         {dialog.json ? ".json" : ".csv"}));
  }
  remember_item(state, "button:export-labels/Export...",
                "Choose the file and write the labels to it");
  ImGui::EndDisabled();
  if (running) {
    ImGui::SameLine();
    ImGui::ProgressBar(static_cast<float>(running->progress()), ImVec2(-1, 0), "writing");
  }
  ImGui::End();
}

//---- File > Export features...

void draw_features_export_dialog(WorkbenchState& state) {
  FeaturesExportDialog& dialog = state.files.features_export;
  if (!dialog.open) return;
  if (!state.document) {
    dialog.open = false;
    return;
  }
  if (!begin_file_dialog("Export features###export features", dialog.open, dialog.focus,
                         ImVec2(620, 236)))
    return;
  dialog_keys(state, dialog.open);
  const std::string skin = state.document->layout.id;
  const std::string pipeline = dialog.pipeline.empty() ? default_pipeline(skin) : dialog.pipeline;
  ImGui::TextDisabled("as tactile features, from %s", state.document->labels_path.empty()
                                                          ? "(no label store beside the recording)"
                                                          : state.document->labels_path.c_str());
  ImGui::SetNextItemWidth(220);
  if (ImGui::BeginCombo("--pipeline", pipeline.c_str())) {
    for (const std::string& name : feature_pipelines()) {
      if (ImGui::Selectable(name.c_str(), name == pipeline)) dialog.pipeline = name;
      remember_item(state, "pipeline:" + name);
    }
    ImGui::EndCombo();
  }
  remember_item(state, "combo:export-features/--pipeline",
                "The feature set computed from each segment");
  ImGui::SetNextItemWidth(300);
  ImGui::InputTextWithHint("--params", "key=value,...", dialog.params.data(), dialog.params.size());
  remember_item(state, "input:export-features/--params",
                "The feature set's parameters, key=value,... (empty: its defaults)");
  source_choice(state, "export-features", dialog.source, false);
  if (radio_item(state, "radio:export-features/this recording",
                 ("this recording (" + state.document->recording_id() + ")").c_str(),
                 !dialog.workspace))
    dialog.workspace = false;
  ImGui::SameLine();
  if (radio_item(state, "radio:export-features/workspace",
                 ("every " + skin + " recording of the store").c_str(), dialog.workspace))
    dialog.workspace = true;
  if (radio_item(state, "radio:export-features/CSV", "CSV (pandas)", !dialog.arff))
    dialog.arff = false;
  ImGui::SameLine();
  if (radio_item(state, "radio:export-features/ARFF", "ARFF (Weka)", dialog.arff))
    dialog.arff = true;
  ImGui::Separator();
  AnyJob* running = running_file_job(state, "export features");
  ImGui::BeginDisabled(running != nullptr);
  if (ImGui::Button("Export...")) {
    const std::string stem =
        (dialog.workspace ? skin : state.document->recording_id()) + "-" + pipeline;
    state.file_browser.open(save_request(state, "export features", "Export features to",
                                         stem + (dialog.arff ? ".arff" : ".csv"),
                                         {dialog.arff ? ".arff" : ".csv"}));
  }
  remember_item(state, "button:export-features/Export...",
                "Choose the file (.csv or .arff) and write the feature table to it");
  ImGui::EndDisabled();
  if (running) {
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) running->cancel();
    remember_item(state, "button:export-features/Cancel", "Stop computing the features");
    ImGui::SameLine();
    const std::string stage = running->stage();
    ImGui::ProgressBar(static_cast<float>(running->progress()), ImVec2(-1, 0), stage.c_str());
  }
  ImGui::End();
}

//---- Labels > Agreement report...

void draw_agreement_dialog(WorkbenchState& state) {
  AgreementDialog& dialog = state.files.agreement;
  if (!dialog.open) return;
  if (!state.document) {
    dialog.open = false;
    return;
  }
  if (!begin_file_dialog("Agreement report###agreement", dialog.open, dialog.focus,
                         ImVec2(600, 320)))
    return;
  dialog_keys(state, dialog.open);
  const Lanes& lanes = state.document->lanes;
  ImGui::TextDisabled("as tactile labels agreement --recording %s",
                      state.document->recording_id().c_str());
  if (lanes.keys.size() < 2) ImGui::TextUnformatted("This recording has fewer than two lanes.");
  if (ImGui::BeginTable("lanes", 2, ImGuiTableFlags_SizingStretchSame)) {
    ImGui::TableSetupColumn("A: the reference");
    ImGui::TableSetupColumn("B: compared with it");
    ImGui::TableHeadersRow();
    for (size_t k = 0; k < lanes.keys.size(); ++k) {
      const std::string id = lanes.keys[k].id();
      const std::string label = id + " (" + std::to_string(lanes.lanes[k].size()) + ")";
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      if (radio_item(state, "radio:agreement/A/" + id, (label + "##a").c_str(), dialog.a == id))
        dialog.a = id;
      ImGui::TableNextColumn();
      if (radio_item(state, "radio:agreement/B/" + id, (label + "##b").c_str(), dialog.b == id))
        dialog.b = id;
    }
    ImGui::EndTable();
  }
  ImGui::SetNextItemWidth(120);
  ImGui::InputFloat("--iou", &dialog.iou, 0.05f, 0.1f, "%.2f");
  dialog.iou = std::clamp(dialog.iou, 0.01f, 1.0f);
  remember_item(
      state, "input:agreement/--iou",
      "How much two segments must overlap (intersection over union) to count as the same touch");
  ImGui::Separator();
  AnyJob* running = running_file_job(state, "agreement");
  ImGui::BeginDisabled(running != nullptr || dialog.a.empty() || dialog.b.empty());
  if (ImGui::Button("Compute")) start_agreement(state);
  remember_item(state, "button:agreement/Compute",
                "Compare the two lanes: kappa over time, segment F1");
  ImGui::EndDisabled();
  ImGui::End();
}

//---- A report (verify, upgrade, agreement)

void draw_report_window(WorkbenchState& state) {
  ReportWindow& report = state.files.report;
  if (!report.open) return;
  if (!begin_file_dialog((report.title + "###report").c_str(), report.open, report.focus,
                         ImVec2(760, 420)))
    return;
  dialog_keys(state, report.open);
  ImGui::BeginChild("report text", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 1.2f), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::TextUnformatted(report.text.c_str());
  ImGui::EndChild();
  if (ImGui::Button("Save...")) {
    std::vector<std::string> extensions = {".txt"};
    if (!report.json.empty()) extensions.push_back(".json");
    state.file_browser.open(
        save_request(state, "save report", "Save the report", report.file_name, extensions));
  }
  remember_item(state, "button:report/Save...", "Write this report to a file");
  ImGui::SameLine();
  if (ImGui::Button("Close")) report.open = false;
  remember_item(state, "button:report/Close", "Close the report (Escape)");
  if (!report.json.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("a name ending in .json saves the JSON report");
  }
  ImGui::End();
}

}  // namespace tactile

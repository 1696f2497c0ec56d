// The small dialogs of the file commands: Export labels, Export features, Agreement report,
// and the window that shows a report (verify, upgrade, agreement) and saves it.
#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "files.h"
#include "jobs.h"
#include "tactile/error.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/atomic_file.h"
#include "tactile/labels/label_file_commands.h"
#include "tactile/labels/label_format.h"
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
                         ImVec2(640, 220)))
    return;
  dialog_keys(state, dialog.open);
  ImGui::TextDisabled("as tactile labels export: %s", state.document->labels_path.empty()
                                                          ? "(no label store beside the recording)"
                                                          : state.document->labels_path.c_str());
  const std::vector<const LabelFormat*> formats = label_formats();
  const LabelFormat* chosen = label_format_named(dialog.format);
  if (!chosen) chosen = formats.front();
  // A format that holds one recording's labels (an ELAN document's tiers).
  const bool one_recording = chosen->one_recording();
  if (one_recording) dialog.every_recording = false;
  if (radio_item(state, "radio:export-labels/this recording",
                 ("this recording (" + state.document->recording_id() + ")").c_str(),
                 !dialog.every_recording))
    dialog.every_recording = false;
  ImGui::SameLine();
  ImGui::BeginDisabled(one_recording);
  if (radio_item(state, "radio:export-labels/every recording", "every recording of the store",
                 dialog.every_recording))
    dialog.every_recording = true;
  ImGui::EndDisabled();
  source_choice(state, "export-labels", dialog.source, true);
  for (const LabelFormat* format : formats) {
    if (format != formats.front()) ImGui::SameLine();
    if (radio_item(state, "radio:export-labels/" + format->name(), format->description().c_str(),
                   format == chosen))
      dialog.format = format->name();
  }
  // The file's name: a format that shares its extension with one before it says which it is
  // ("-label-studio.json").
  const std::string extension = chosen->extension();
  std::string suffix;
  for (const LabelFormat* format : formats) {
    if (format == chosen) break;
    if (format->extension() == extension) {
      for (char c : chosen->name())
        suffix += c == ' ' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      suffix = "-" + suffix;
      break;
    }
  }
  ImGui::Separator();
  AnyJob* running = running_job(state, "export labels");
  ImGui::BeginDisabled(running != nullptr);
  if (ImGui::Button("Export...")) {
    std::string stem =
        dialog.every_recording ? std::string("labels") : state.document->recording_id() + "-labels";
    stem += suffix;
    state.file_browser.open(
        save_request(state, "export labels", "Export labels to", stem + extension, {extension}));
  }
  remember_item(state, "button:export-labels/Export...",
                "Choose the file and write the labels to it");
  ImGui::EndDisabled();
  if (running) {
    ImGui::SameLine();
    draw_job_progress(*running, "writing");
  }
  ImGui::End();
}

//---- Labels > Import labels... of ELAN and Label Studio

namespace {

// What the file holds, once read: the sources to choose among, or (our own CSV or JSON) the
// import at once.
void take_labels_import_sources(WorkbenchState& state, Job<InteropSources>& job) {
  LabelsImportDialog& dialog = state.files.labels_import;
  std::optional<InteropSources> sources = job.take();
  if (!sources) dialog.failure = job.error();
  if (!sources) return;
  if (sources->format.empty()) {
    // Our own file: nothing to choose.
    dialog.open = false;
    start_labels_import(state, dialog.file);
    return;
  }
  for (const InteropSource& source : sources->sources) {
    LabelsImportDialog::Choice choice;
    set_field(choice.lane, source.lane);
    dialog.choices.push_back(choice);
  }
  // A format of one recording per file (an ELAN document): the open one unless the user says
  // otherwise. Label Studio's tasks name their own files.
  const LabelFormat* format = label_format_named(sources->format);
  if (format && format->one_recording() && state.document)
    set_field(dialog.recording, state.document->recording_id());
  dialog.sources = std::move(*sources);
}

}  // namespace

void open_labels_import_dialog(WorkbenchState& state, const std::string& file) {
  LabelsImportDialog& dialog = state.files.labels_import;
  dialog.open = dialog.focus = true;
  dialog.file = file;
  dialog.sources.reset();
  dialog.failure.clear();
  dialog.choices.clear();
  dialog.recording = {};
  dialog.start_ms = {};
  // Read on a worker: the file may be large or on a disk that hangs.
  JobExtras quiet;
  quiet.logged = false;
  start_job<InteropSources>(
      state, "read labels file", "read labels file",
      [file](JobProgress& progress) {
        progress.report(0.0, "reading " + file);
        return interop_sources(file);
      },
      take_labels_import_sources, std::move(quiet));
}

void draw_labels_import_dialog(WorkbenchState& state) {
  LabelsImportDialog& dialog = state.files.labels_import;
  if (!dialog.open) return;
  if (!state.document) {
    dialog.open = false;
    return;
  }
  if (!begin_file_dialog("Import labels###import labels", dialog.open, dialog.focus,
                         ImVec2(640, 360)))
    return;
  dialog_keys(state, dialog.open);
  ImGui::TextDisabled("as tactile labels import: %s", dialog.file.c_str());
  if (AnyJob* reading = find_job(state, "read labels file")) {
    draw_job_progress(*reading, "reading");
  } else if (!dialog.failure.empty() || !dialog.sources) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", dialog.failure.c_str());
    ImGui::PopTextWrapPos();
  } else {
    const InteropSources& sources = *dialog.sources;
    const bool elan = sources.format == "ELAN";
    ImGui::Text("%s: %zu %s%s%s", sources.format.c_str(), sources.sources.size(),
                elan ? "tiers" : "annotators and models",
                sources.recording.empty() ? "" : ", recording ", sources.recording.c_str());
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted("--recording");
    ImGui::SameLine(150);
    ImGui::SetNextItemWidth(280);
    ImGui::InputTextWithHint("##recording", "default: the file's own", dialog.recording.data(),
                             dialog.recording.size());
    remember_item(state, "input:import-labels/--recording",
                  "The recording the labels belong to (empty: the one the file names)");
    if (!elan) {
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted("--start-ms");
      ImGui::SameLine(150);
      ImGui::SetNextItemWidth(280);
      ImGui::InputTextWithHint("##start-ms", "default: the recording's own start",
                               dialog.start_ms.data(), dialog.start_ms.size());
      remember_item(state, "input:import-labels/--start-ms",
                    "A TimeSeries of dates gives epoch milliseconds: the Unix time in "
                    "milliseconds of the recording's first sample");
    }
    ImGui::TextDisabled(elan ? "Each chosen tier goes to the lane given (--tier NAME=LANE):"
                             : "Each annotator and model goes to the lane given (--annotator):");
    const ImGuiTableFlags flags =
        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY;
    if (ImGui::BeginTable("sources", 3, flags,
                          ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 1.6f))) {
      ImGui::TableSetupColumn(elan ? "tier" : "annotator or model");
      ImGui::TableSetupColumn("labels", ImGuiTableColumnFlags_WidthFixed, 60);
      ImGui::TableSetupColumn("lane", ImGuiTableColumnFlags_WidthFixed, 240);
      ImGui::TableHeadersRow();
      for (size_t k = 0; k < sources.sources.size(); ++k) {
        const InteropSource& source = sources.sources[k];
        LabelsImportDialog::Choice& choice = dialog.choices[k];
        ImGui::PushID(static_cast<int>(k));
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        if (elan) {
          ImGui::Checkbox(source.name.c_str(), &choice.chosen);
          remember_item(state, "checkbox:import-labels/" + source.name, "Import this tier");
        } else {
          ImGui::TextUnformatted(source.name.c_str());
        }
        ImGui::TableNextColumn();
        ImGui::Text("%zu", source.labels);
        ImGui::TableNextColumn();
        ImGui::SetNextItemWidth(-1);
        ImGui::InputText("##lane", choice.lane.data(), choice.lane.size());
        remember_item(state, "input:import-labels/lane " + source.name,
                      "ground-truth, manual:NAME (or NAME), segmenter:METHOD or model:NAME");
        ImGui::PopID();
      }
      ImGui::EndTable();
    }
  }
  AnyJob* running = running_job(state, "import labels");
  ImGui::BeginDisabled(running != nullptr || !dialog.sources);
  if (ImGui::Button("Import")) {
    InteropImport options;
    options.recording = trimmed_field(dialog.recording.data());
    const bool elan = dialog.sources->format == "ELAN";
    for (size_t k = 0; k < dialog.sources->sources.size(); ++k) {
      const InteropSource& source = dialog.sources->sources[k];
      const std::string lane = trimmed_field(dialog.choices[k].lane.data());
      if (elan && dialog.choices[k].chosen) options.tiers[source.name] = lane;
      if (!elan && lane != source.lane) options.annotators[source.name] = lane;
    }
    const std::string start_ms = trimmed_field(dialog.start_ms.data());
    char* end = nullptr;
    const double start = start_ms.empty() ? 0.0 : std::strtod(start_ms.c_str(), &end);
    if (!start_ms.empty() && end && *end == '\0' && std::isfinite(start)) options.start_ms = start;
    if (elan && options.tiers.empty()) {
      state.error = "import labels: no tier chosen";
    } else if (!start_ms.empty() && !options.start_ms) {
      state.error = "import labels: --start-ms: '" + start_ms +
                    "' is not a Unix time in milliseconds (1592250751951)";
    } else {
      start_labels_import(state, dialog.file, options);
      dialog.open = false;
    }
  }
  remember_item(state, "button:import-labels/Import",
                "Add the chosen labels to the open recording's label store");
  ImGui::EndDisabled();
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
  AnyJob* running = running_job(state, "export features");
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
    draw_job_progress(*running);
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
  AnyJob* running = running_job(state, "agreement");
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

// File > Import...: the options of `tactile import` (docs/IMPORT.md) for the format of the file
// chosen, each field named by its flag so that a refusal ("--rate: is needed for an array")
// points at it, and a preview of what the options read: the shape, the channels, the first
// frames and the classes, read on a worker after each change. The format's fields are made
// from its importer's options (formats/importer.h): no format is named here.
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <utility>

#include "files.h"
#include "jobs.h"
#include "tactile/error.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr float kImportLabelWidth = 190.0f;
constexpr int kImportPreviewChannels = 16;  // columns of the preview table at most

// A field of the dialog: its flag on the left, the text field (item "input:import/FLAG").
template <size_t Size>
void import_field(WorkbenchState& state, const char* flag, std::array<char, Size>& buffer,
                  const char* hint, float width = -1.0f) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(flag);
  ImGui::SameLine(kImportLabelWidth);
  ImGui::SetNextItemWidth(width);
  ImGui::InputTextWithHint((std::string("##") + flag).c_str(), hint, buffer.data(), buffer.size());
  remember_item(state, std::string("input:import/") + flag,
                std::string("tactile import ") + flag + ": " + hint + " (docs/IMPORT.md)");
}

bool import_browse(WorkbenchState& state, const char* flag) {
  ImGui::SameLine();
  const bool pressed = ImGui::Button((std::string("Browse...##") + flag).c_str());
  remember_item(state, std::string("button:import/Browse ") + flag, "Choose the file in a browser");
  return pressed;
}

BrowseRequest import_browse_request(const WorkbenchState& state, BrowseMode mode,
                                    const std::string& purpose, const std::string& title) {
  BrowseRequest request;
  request.mode = mode;
  request.purpose = purpose;
  request.title = title;
  const std::string file = state.files.import.file.data();
  request.directory = !state.workspace.empty()
                          ? state.workspace
                          : (file.empty() ? "." : fs::path(file).parent_path().string());
  return request;
}

// The fields that decide what the preview reads, as one text: a change starts a new preview.
std::string preview_fields(const FileImportOptions& options) {
  std::string text = options.file + '\n' + options.layout + '\n';
  for (const auto& [flag, value] : options.values.all()) text += flag + '=' + value + '\n';
  return text;
}

// Whether an option of the format is shown and taken with the switches as they are.
bool option_applies(const ImportDialog& dialog, const ImportOption& option) {
  const auto on = [&dialog](const std::string& flag) {
    const auto found = dialog.switches.find(flag);
    return found != dialog.switches.end() && found->second;
  };
  return (option.only_with.empty() || on(option.only_with)) &&
         (option.never_with.empty() || !on(option.never_with));
}

// The fields of the format's options, as its importer declares them.
void draw_format_fields(WorkbenchState& state, const RecordingImporter& importer) {
  ImportDialog& dialog = state.files.import;
  for (const ImportOption& option : importer.options()) {
    if (!option_applies(dialog, option)) continue;
    const std::string& flag = option.flag;
    const std::string hint = option.hint.empty() ? option.help : option.hint;
    if (option.kind == ImportOption::Kind::kSwitch) {
      ImGui::SetCursorPosX(kImportLabelWidth);
      ImGui::Checkbox((flag + ": " + hint).c_str(), &dialog.switches[flag]);
      remember_item(state, "checkbox:import/" + flag, option.help);
      continue;
    }
    const bool wide =
        option.kind == ImportOption::Kind::kList || option.kind == ImportOption::Kind::kFile;
    import_field(state, flag.c_str(), dialog.fields[flag], hint.c_str(),
                 option.kind == ImportOption::Kind::kFile ? -90.0f : (wide ? 440.0f : 320.0f));
    if (option.kind == ImportOption::Kind::kFile && import_browse(state, flag.c_str())) {
      BrowseRequest request = import_browse_request(state, BrowseMode::kOpenFile,
                                                    "import option " + flag, "Import: " + flag);
      state.file_browser.open(std::move(request));
    }
  }
}

std::string shape_text(const std::vector<int64_t>& shape) {
  std::string text;
  for (int64_t size : shape) {
    text += '[';
    text += std::to_string(size);
    text += ']';
  }
  return text;
}

void draw_preview_table(const ImportPreview& preview) {
  const int channels =
      std::min<int>(kImportPreviewChannels, static_cast<int>(preview.channels.size()));
  const int columns = 2 + channels;
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit;
  const float height = ImGui::GetTextLineHeightWithSpacing() * (preview.frames.size() + 2.5f);
  if (!ImGui::BeginTable("import_preview", columns, flags, ImVec2(0, height))) return;
  ImGui::TableSetupScrollFreeze(2, 1);
  ImGui::TableSetupColumn("t (s)");
  ImGui::TableSetupColumn("class");
  for (int column = 0; column < channels; ++column)
    ImGui::TableSetupColumn(preview.channels[static_cast<size_t>(column)].c_str());
  ImGui::TableHeadersRow();
  for (size_t row = 0; row < preview.frames.size(); ++row) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%.4f", preview.times[row]);
    ImGui::TableNextColumn();
    const std::string& class_name = preview.frame_classes[row];
    if (class_name.empty())
      ImGui::TextDisabled("-");
    else
      ImGui::TextUnformatted(class_name.c_str());
    for (int column = 0; column < channels; ++column) {
      ImGui::TableNextColumn();
      ImGui::Text("%.4g", preview.frames[row][static_cast<size_t>(column)]);
    }
  }
  ImGui::EndTable();
}

void draw_import_preview(const ImportDialog& dialog, bool current) {
  if (!dialog.preview) return;
  const ImportPreview& preview = *dialog.preview;
  if (!current) ImGui::TextDisabled("(the options changed: reading again...)");
  if (!preview.refusal.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "refused: %s", preview.refusal.c_str());
    ImGui::PopTextWrapPos();
    return;
  }
  ImGui::Text("%s %s   layout %s: %zu channels at %s Hz", preview.format.c_str(),
              shape_text(preview.shape).c_str(), preview.layout.c_str(), preview.channels.size(),
              shortest_text(preview.rate_hz).c_str());
  if (preview.recordings.size() == 1)
    ImGui::Text("%lld samples in one recording (%s)", static_cast<long long>(preview.samples),
                preview.recordings.front().c_str());
  else
    ImGui::Text("%lld samples in %zu recordings (%s)", static_cast<long long>(preview.samples),
                preview.recordings.size(), joined(preview.recordings).c_str());
  if (preview.classes.empty())
    ImGui::TextDisabled("no classes: no ground truth");
  else
    ImGui::Text("classes: %s (%zu ground-truth labels)", joined(preview.classes).c_str(),
                preview.labels);
  if (static_cast<int>(preview.channels.size()) > kImportPreviewChannels)
    ImGui::TextDisabled("the first %d of %zu channels, the first %zu frames:",
                        kImportPreviewChannels, preview.channels.size(), preview.frames.size());
  else
    ImGui::TextDisabled("the first %zu frames:", preview.frames.size());
  draw_preview_table(preview);
}

}  // namespace

std::string trimmed_field(const char* text) {
  std::string value(text);
  const size_t first = value.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return value.substr(first, value.find_last_not_of(" \t") - first + 1);
}

void open_import_dialog(WorkbenchState& state) {
  ImportDialog& dialog = state.files.import;
  dialog.open = true;
  dialog.focus = true;
  dialog.failure.clear();
}

bool import_options_of(const WorkbenchState& state, FileImportOptions& options,
                       std::string& refusal) {
  const ImportDialog& dialog = state.files.import;
  options = FileImportOptions{};
  options.file = trimmed_field(dialog.file.data());
  options.layout = trimmed_field(dialog.layout.data());
  if (const RecordingImporter* importer = importer_for(options.file)) {
    for (const ImportOption& option : importer->options()) {
      if (!option_applies(dialog, option)) continue;
      if (option.kind == ImportOption::Kind::kSwitch) {
        const auto found = dialog.switches.find(option.flag);
        options.values.set_switch(option.flag, found != dialog.switches.end() && found->second);
        continue;
      }
      const auto found = dialog.fields.find(option.flag);
      const std::string text =
          found == dialog.fields.end() ? "" : trimmed_field(found->second.data());
      if (!text.empty()) options.values.set(option.flag, text);
    }
    try {
      check_import_values(*importer, options.values);
    } catch (const Error& error) {
      refusal = error.what();
      return false;
    }
  }
  // The window's defaults: the recording in the workspace, its labels in labels.db beside it
  // (where the workbench looks for them).
  const bool grouped = import_writes_folder(options);
  options.out = trimmed_field(dialog.out.data());
  if (options.out.empty() && !options.file.empty()) {
    const fs::path folder = !state.workspace.empty() ? fs::path(state.workspace)
                                                     : fs::absolute(options.file).parent_path();
    const std::string stem = fs::path(options.file).stem().string();
    options.out = (folder / (grouped ? stem : stem + ".h5")).string();
  }
  options.labels = trimmed_field(dialog.labels.data());
  if (options.labels.empty() && !options.out.empty())
    options.labels =
        ((grouped ? fs::path(options.out) : fs::path(options.out).parent_path()) / "labels.db")
            .string();
  options.recording_id = trimmed_field(dialog.recording_id.data());
  options.annotator = trimmed_field(dialog.annotator.data());
  return true;
}

void draw_import_dialog(WorkbenchState& state) {
  ImportDialog& dialog = state.files.import;
  if (!dialog.open) return;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x * 0.5f,
                                 viewport->WorkPos.y + viewport->WorkSize.y * 0.5f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(std::min(900.0f, viewport->WorkSize.x - 40.0f),
                                  std::min(720.0f, viewport->WorkSize.y - 40.0f)),
                           ImGuiCond_Appearing);
  if (std::exchange(dialog.focus, false)) ImGui::SetNextWindowFocus();
  ImGui::SetNextWindowBgAlpha(1.0f);  // the window behind would make the table hard to read
  bool open = true;
  if (!ImGui::Begin("Import###import", &open, ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    dialog.open = open;
    return;
  }
  dialog_keys(state, open);
  const std::string file = trimmed_field(dialog.file.data());
  const RecordingImporter* importer = importer_for(file);
  import_field(state, "FILE", dialog.file, ("a file: " + import_formats_text()).c_str(), -90.0f);
  if (import_browse(state, "FILE")) {
    BrowseRequest request = import_browse_request(state, BrowseMode::kOpenFile, "import file",
                                                  "Import: the file to read");
    request.extensions = import_extensions();
    state.file_browser.open(std::move(request));
  }
  const std::string layouts = joined(known_layout_ids()) + ", grid:RxC, strip:N";
  import_field(state, "--layout", dialog.layout, layouts.c_str(), 440.0f);
  if (importer) draw_format_fields(state, *importer);
  FileImportOptions options;
  std::string refusal;
  const bool parsed = import_options_of(state, options, refusal);
  const bool grouped = parsed && import_writes_folder(options);
  import_field(
      state, "--out", dialog.out,
      ("default: " + (options.out.empty() ? std::string("in the workspace") : options.out)).c_str(),
      -90.0f);
  if (import_browse(state, "--out")) {
    BrowseRequest request = import_browse_request(
        state, grouped ? BrowseMode::kChooseFolder : BrowseMode::kSaveFile, "import out",
        grouped ? "Import: the folder of the recordings" : "Import: the recording to write");
    request.extensions = {".h5"};
    request.file_name = fs::path(options.out).filename().string();
    state.file_browser.open(std::move(request));
  }
  import_field(state, "--labels", dialog.labels,
               ("default: " + (options.labels.empty() ? std::string("labels.db beside the output")
                                                      : options.labels))
                   .c_str(),
               -90.0f);
  if (import_browse(state, "--labels")) {
    BrowseRequest request = import_browse_request(state, BrowseMode::kSaveFile, "import labels db",
                                                  "Import: the label database");
    request.extensions = {".db"};
    request.file_name = "labels.db";
    state.file_browser.open(std::move(request));
  }
  import_field(state, "--recording-id", dialog.recording_id,
               grouped ? "(one per group: STEM-VALUE-VALUE)" : "default: the output's stem",
               320.0f);
  import_field(state, "--annotator", dialog.annotator,
               "store the file's labels as this annotator's (default: the ground truth)", 320.0f);

  ImGui::Separator();
  ImGui::TextUnformatted("Preview");
  // A preview runs for the fields as they are once the one before has ended.
  const std::string fields = parsed ? preview_fields(options) : std::string();
  if (file.empty()) {
    ImGui::TextWrapped("Choose a file: %s (docs/IMPORT.md).", import_formats_text().c_str());
  } else if (!parsed) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "refused: %s", refusal.c_str());
  } else {
    AnyJob* previewing = find_job(state, "import preview");
    if (!previewing && fields != dialog.preview_for) start_import_preview(state, options, fields);
    if ((previewing = find_job(state, "import preview"))) draw_job_progress(*previewing);
    ImGui::BeginChild("preview", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2.2f), false,
                      ImGuiWindowFlags_HorizontalScrollbar);
    draw_import_preview(dialog, fields == dialog.preview_for);
    ImGui::EndChild();
  }
  if (file.empty() || !parsed)
    ImGui::Dummy(
        ImVec2(0, ImGui::GetContentRegionAvail().y - ImGui::GetFrameHeightWithSpacing() * 2.2f));

  ImGui::Separator();
  AnyJob* running = running_job(state, "import");
  ImGui::BeginDisabled(running != nullptr || file.empty() || !parsed);
  if (ImGui::Button("Import")) start_import(state, options);
  remember_item(state, "button:import/Import",
                "Write the recording (and its ground truth) as the preview shows it, then open it");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Close")) open = false;
  remember_item(state, "button:import/Close", "Close the dialog (Escape); nothing is written");
  if (running) {
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) running->cancel();
    remember_item(state, "button:import/Cancel", "Stop the import; the files already written stay");
    ImGui::SameLine();
    draw_job_progress(*running);
  } else if (!dialog.failure.empty()) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", dialog.failure.c_str());
  }
  ImGui::End();
  dialog.open = open;
}

}  // namespace tactile

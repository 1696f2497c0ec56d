// File > Import...: the options of `tactile import` (docs/IMPORT.md) for the format of the file
// chosen, each field named by its flag so that a refusal ("--rate: is needed for an array")
// points at it, and a preview of what the options read: the shape, the channels, the first
// frames and the classes, read on a worker after each change.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "files.h"
#include "jobs.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr float kImportLabelWidth = 190.0f;
constexpr int kImportPreviewChannels = 16;  // columns of the preview table at most

std::vector<std::string> comma_list(const char* text) {
  std::vector<std::string> items;
  std::string item;
  for (const char* c = text;; ++c) {
    if (*c == ',' || *c == '\0') {
      const std::string value = trimmed_field(item.c_str());
      if (!value.empty()) items.push_back(value);
      item.clear();
      if (*c == '\0') break;
    } else {
      item += *c;
    }
  }
  return items;
}

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

// The fields that decide what the preview reads, as one text: a change starts a new preview.
std::string preview_fields(const FileImportOptions& options) {
  std::string text = options.file + '\n' + options.layout + '\n';
  text += (options.rate_hz ? shortest_text(*options.rate_hz) : "-") + '\n';
  text += std::to_string(options.wide) + std::to_string(options.captures) + '\n';
  text += (options.samples_per_capture ? std::to_string(*options.samples_per_capture) : "-") + '\n';
  text += options.labels_file.value_or("-") + '\n';
  text += (options.class_names ? joined(*options.class_names, ",") : "-") + '\n';
  text += options.dataset + '\n' + options.key + '\n' + options.class_array + '\n';
  text += options.rate_variable + '\n';
  text += options.value_key + '\n' + options.class_key + '\n';
  text += options.class_column + '\n' + joined(options.group_columns, ",") + '\n';
  text += joined(options.signals, ",") + '\n';
  text += options.annotation_seconds ? shortest_text(*options.annotation_seconds) : "-";
  text += '\n' + options.stream + '\n' + options.markers;
  return text;
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
  const std::string format = import_format_of(options.file);
  auto positive = [&refusal](const std::string& text, const char* flag, double& value) {
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || value <= 0.0) {
      refusal = std::string(flag) + ": '" + text + "' is not a positive number";
      return false;
    }
    return true;
  };
  const std::string rate = format == ".xdf" ? "" : trimmed_field(dialog.rate.data());
  double value = 0.0;
  // An EDF or BDF file states its rate: the field is hidden for one, and not read.
  if (!rate.empty() && format != ".edf" && format != ".bdf") {
    if (!positive(rate, "--rate", value)) return false;
    options.rate_hz = value;
  }
  if (format == "CSV") {
    options.wide = dialog.wide;
    if (options.wide) {
      const std::string samples = trimmed_field(dialog.samples_per_capture.data());
      if (!samples.empty()) {
        if (!positive(samples, "--samples-per-capture", value)) return false;
        if (value != std::floor(value)) {
          refusal = "--samples-per-capture: '" + samples + "' is not a whole number";
          return false;
        }
        options.samples_per_capture = static_cast<int64_t>(value);
      }
      const std::string labels_file = trimmed_field(dialog.labels_file.data());
      if (!labels_file.empty()) options.labels_file = labels_file;
      const std::vector<std::string> names = comma_list(dialog.class_names.data());
      if (!names.empty()) options.class_names = names;
    } else {
      options.class_column = trimmed_field(dialog.class_column.data());
      options.group_columns = comma_list(dialog.group_columns.data());
    }
  } else if (format == ".edf" || format == ".bdf") {
    options.signals = comma_list(dialog.signals.data());
    const std::string seconds = trimmed_field(dialog.annotation_seconds.data());
    if (!seconds.empty()) {
      if (!positive(seconds, "--annotation-seconds", value)) return false;
      options.annotation_seconds = value;
    }
  } else if (format == ".xdf") {
    options.stream = trimmed_field(dialog.stream.data());
    options.markers = trimmed_field(dialog.markers.data());
  } else if (!format.empty()) {
    if (format == ".npz" || format == ".h5" || format == ".mat")
      options.dataset = trimmed_field(dialog.dataset.data());
    if (format == ".mat") options.rate_variable = trimmed_field(dialog.rate_variable.data());
    if (format == ".json") {
      options.key = trimmed_field(dialog.key.data());
      options.value_key = trimmed_field(dialog.value_key.data());
      options.class_key = trimmed_field(dialog.class_key.data());
    }
    options.class_array = trimmed_field(dialog.class_array.data());
    options.captures = dialog.captures;
  }
  // The window's defaults: the recording in the workspace, its labels in labels.db beside it
  // (where the workbench looks for them).
  const bool grouped = !options.group_columns.empty();
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
  const std::string format = import_format_of(file);
  import_field(state, "FILE", dialog.file,
               "a CSV, .npy, .npz, .json, .h5, .mat, .edf, .bdf or .xdf file", -90.0f);
  if (import_browse(state, "FILE")) {
    BrowseRequest request = import_browse_request(state, BrowseMode::kOpenFile, "import file",
                                                  "Import: the file to read");
    request.extensions = {".csv",  ".txt", ".npy", ".npz", ".json", ".h5",
                          ".hdf5", ".hdf", ".mat", ".edf", ".bdf",  ".xdf"};
    state.file_browser.open(std::move(request));
  }
  const std::string layouts = joined(known_layout_ids()) + ", grid:RxC, strip:N";
  import_field(state, "--layout", dialog.layout, layouts.c_str(), 440.0f);
  const bool edf = format == ".edf" || format == ".bdf";
  // An EDF or BDF file states its rate; an XDF stream has its own nominal rate.
  if (!edf && format != ".xdf")
    import_field(state, "--rate", dialog.rate,
                 format == "CSV" && !dialog.wide ? "Hz (default: from the time column)" : "Hz",
                 320.0f);
  if (format == "CSV") {
    ImGui::SetCursorPosX(kImportLabelWidth);
    ImGui::Checkbox("--wide: one capture per row, with a labels file", &dialog.wide);
    remember_item(
        state, "checkbox:import/--wide",
        "One capture per row, channel-major, with a labels file of one class per capture");
    if (dialog.wide) {
      import_field(state, "--samples-per-capture", dialog.samples_per_capture, "N", 200.0f);
      import_field(state, "--labels-file", dialog.labels_file, "one class per capture", -90.0f);
      if (import_browse(state, "--labels-file")) {
        BrowseRequest request = import_browse_request(
            state, BrowseMode::kOpenFile, "import labels file", "Import: the labels file");
        request.extensions = {".csv", ".txt"};
        state.file_browser.open(std::move(request));
      }
      import_field(state, "--class-names", dialog.class_names, "a,b,c (default: the layout's)",
                   440.0f);
    } else {
      import_field(state, "--class-column", dialog.class_column, "the column of class names",
                   320.0f);
      import_field(state, "--group-columns", dialog.group_columns,
                   "e.g. subject,capture: one recording per group", 320.0f);
    }
  } else if (edf) {
    import_field(state, "--signals", dialog.signals,
                 "labels in channel order, e.g. Fz,Cz (default: every signal)", 440.0f);
    import_field(state, "--annotation-seconds", dialog.annotation_seconds,
                 "length of annotations without one (default: refused)", 320.0f);
  } else if (format == ".xdf") {
    import_field(state, "--stream", dialog.stream,
                 "NAME or type:TYPE (default: the only numeric stream with a rate)", 440.0f);
    import_field(state, "--markers", dialog.markers,
                 "NAME or type:TYPE (default: the only markers stream)", 440.0f);
  } else if (!format.empty()) {
    if (format == ".npz" || format == ".h5" || format == ".mat")
      import_field(state, "--dataset", dialog.dataset,
                   format == ".h5"    ? "the dataset, e.g. /data/pressure"
                   : format == ".mat" ? "the variable, s.field (default: the only array)"
                                      : "the array (default: the only one)",
                   320.0f);
    if (format == ".mat")
      import_field(state, "--rate-variable", dialog.rate_variable,
                   "the variable holding the rate in Hz (not with --rate)", 320.0f);
    if (format == ".json") {
      import_field(state, "--key", dialog.key, "a.b (default: the top level)", 320.0f);
      import_field(state, "--value-key", dialog.value_key,
                   "frames as objects: the member of each frame, e.g. data", 320.0f);
      import_field(state, "--class-key", dialog.class_key,
                   "frames as objects: the member of each class, e.g. label", 320.0f);
    }
    import_field(state, "--class-array", dialog.class_array,
                 format == ".json" ? "the key of the classes" : "the array of the classes", 320.0f);
    ImGui::SetCursorPosX(kImportLabelWidth);
    ImGui::Checkbox("--captures: [captures][channels][samples]", &dialog.captures);
    remember_item(state, "checkbox:import/--captures",
                  "The array is [captures][channels][samples]: captures laid end to end");
  }
  FileImportOptions options;
  std::string refusal;
  const bool parsed = import_options_of(state, options, refusal);
  const bool grouped = !options.group_columns.empty();
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
    ImGui::TextDisabled(
        "Choose a file: long or wide CSV, NumPy .npy / .npz, JSON frames, another program's "
        ".h5, MATLAB .mat, EDF+/BDF+, an XDF recording (docs/IMPORT.md).");
  } else if (!parsed) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "refused: %s", refusal.c_str());
  } else {
    if (!dialog.preview_job && fields != dialog.preview_for)
      start_import_preview(state, options, fields);
    if (dialog.preview_job) draw_job_progress(*dialog.preview_job);
    ImGui::BeginChild("preview", ImVec2(0, -ImGui::GetFrameHeightWithSpacing() * 2.2f), false,
                      ImGuiWindowFlags_HorizontalScrollbar);
    draw_import_preview(dialog, fields == dialog.preview_for);
    ImGui::EndChild();
  }
  if (file.empty() || !parsed)
    ImGui::Dummy(
        ImVec2(0, ImGui::GetContentRegionAvail().y - ImGui::GetFrameHeightWithSpacing() * 2.2f));

  ImGui::Separator();
  AnyJob* running = running_file_job(state, "import");
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

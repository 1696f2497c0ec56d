#include "workbench.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "confusion.h"
#include "files.h"
#include "jobs.h"
#include "keys.h"
#include "labelling.h"
#include "live.h"
#include "results.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/segment/segmenter.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/skins/skin.h"
#include "tactile/skins/workspace.h"
#include "tactile/text.h"
#include "video.h"
#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr float kSplitterThickness = 6.0f;
constexpr float kMinimumPanel = 80.0f;
// A label longer than this is searched for its peak only in its first part.
constexpr int64_t kPeakSearchSamples = 20000;
constexpr double kOpeningSpanSeconds = 60.0;  // the plot's span when a recording opens
constexpr float kVideoShare = 0.5f;  // of the skin's panel, for the videos when there are any

// A bar between two panels; dragging it moves the boundary. Returns true while dragged.
bool splitter(WorkbenchState& state, const char* id, bool vertical, float length, float& value,
              float minimum, float maximum, float direction = 1.0f) {
  const ImVec2 size =
      vertical ? ImVec2(kSplitterThickness, length) : ImVec2(length, kSplitterThickness);
  ImGui::InvisibleButton(id, size);
  remember_item(state, std::string("splitter:") + id);
  const bool active = ImGui::IsItemActive();
  if (ImGui::IsItemHovered() || active)
    ImGui::SetMouseCursor(vertical ? ImGuiMouseCursor_ResizeEW : ImGuiMouseCursor_ResizeNS);
  const ImU32 colour =
      active ? IM_COL32(110, 110, 130, 255)
             : (ImGui::IsItemHovered() ? IM_COL32(80, 80, 95, 255) : IM_COL32(45, 45, 52, 255));
  ImGui::GetWindowDrawList()->AddRectFilled(ImGui::GetItemRectMin(), ImGui::GetItemRectMax(),
                                            colour);
  if (active) {
    const ImVec2 delta = ImGui::GetIO().MouseDelta;
    value = std::clamp(value + direction * (vertical ? delta.x : delta.y), minimum,
                       std::max(minimum, maximum));
  }
  return ImGui::IsItemDeactivated();
}

std::string view_title(const std::string& name) {
  const ViewSpec* view = find_view(name);
  return view ? view->title : name;
}

}  // namespace

Workbench::Workbench(const WorkbenchOptions& options) {
  state_.options = options;
  load_settings();
  // Who edits: the command line, else the settings, else the login name.
  if (!options.annotator.empty()) state_.labelling.annotator = options.annotator;
  if (state_.labelling.annotator.empty()) {
    const char* user = std::getenv("USER");
    state_.labelling.annotator = user && *user ? user : "operator";
  }
  std::error_code error;
  if (!options.connect.empty()) {
    state_.live.buffer_seconds = static_cast<float>(options.buffer_seconds);
    state_.live.pretrigger_seconds = static_cast<float>(options.pretrigger_seconds);
    if (connect_live(state_, services_.live, options.connect, options.skin) &&
        !options.record_path.empty())
      start_recording(state_, services_.live, options.record_path);
  } else if (fs::is_directory(options.open_path, error)) {
    open_folder(options.open_path);
  } else if (!options.open_path.empty()) {
    open(options.open_path);
  }
  if (state_.document && options.time) state_.clock.seek(*options.time);
  if (state_.document && options.play) state_.clock.play();
  open_analysis_files();
}

void Workbench::open_analysis_files() {
  const WorkbenchOptions& options = state_.options;
  if (!options.features_path.empty()) open_features_file(state_, options.features_path);
  if (!options.evaluation_path.empty()) open_evaluation_file(state_, options.evaluation_path);
  // Live, a model classifies the stream; otherwise a SOM model shows its map.
  if (!options.model_path.empty()) {
    if (state_.live.connected)
      load_online_model(state_, services_.live, options.model_path);
    else
      open_model_file(state_, options.model_path);
  }
}

void Workbench::set_workspace(const std::string& folder) {
  std::error_code error;
  const fs::path absolute = fs::absolute(folder, error);
  std::string workspace = (error ? fs::path(folder) : absolute).lexically_normal().string();
  while (workspace.size() > 1 && workspace.back() == '/') workspace.pop_back();
  if (workspace != state_.workspace) state_.damaged.clear();
  state_.workspace = workspace;
  state_.workspace_files.clear();
  for (fs::recursive_directory_iterator it(state_.workspace, error), end; !error && it != end;
       it.increment(error))
    if (it->path().extension() == ".h5") state_.workspace_files.push_back(it->path().string());
  std::sort(state_.workspace_files.begin(), state_.workspace_files.end());
}

DocumentOptions Workbench::document_options(const std::string& stream) const {
  DocumentOptions options;
  options.labels_path = state_.options.labels_path;
  options.stream = stream;
  options.cache_bytes = state_.options.cache_bytes;
  return options;
}

Workbench::~Workbench() { disconnect_live(state_, services_.live); }

bool Workbench::open(const std::string& path) {
  disconnect_live(state_, services_.live);
  std::error_code ignored;
  const std::string absolute = fs::absolute(path, ignored).lexically_normal().string();
  try {
    state_.document = open_document(path, document_options({}));
    state_.error.clear();
  } catch (const std::exception& failure) {
    // Marked in the workspace list instead of failing the workbench.
    state_.damaged[absolute] = failure.what();
    state_.error = std::string("cannot open: ") + failure.what();
    if (state_.workspace.empty()) set_workspace(fs::path(absolute).parent_path().string());
    return false;
  }
  if (state_.workspace.empty() || fs::path(state_.document->path)
                                      .lexically_relative(state_.workspace)
                                      .string()
                                      .starts_with(".."))
    set_workspace(fs::path(state_.document->path).parent_path().string());
  state_.selection = {};
  choose_default_view();
  if (!state_.document->labels_read_only.empty())
    state_.notice = "read-only: " + state_.document->labels_read_only;
  return true;
}

void Workbench::select_stream(const std::string& stream) {
  try {
    state_.document = open_document(state_.document->path, document_options(stream));
  } catch (const std::exception& failure) {
    state_.error = failure.what();
    return;
  }
  choose_default_view();
}

void Workbench::seek(double time) { state_.clock.seek(time); }

// Shows the skin's display modality, plots the channels of that modality that move the
// most, and puts the cursor inside the first labelled touch so the skin is lit on opening.
// Reads the coarse overview and at most one label's samples: opening is as fast for a
// day of data as for a minute.
void Workbench::choose_default_view() {
  const Document& document = *state_.document;
  const SampleSource& source = document.samples();
  state_.clock.pause();
  state_.clock.set_range(source.start_time(), source.end_time());
  state_.modality = std::max(0, document.layout.modality_index(document.layout.display_modality));
  state_.rest_scale_modality = -1;
  state_.skin_zoom = SkinViewZoom{};
  // On a skin's first recording, G runs the skin's own segmenter; one chosen since (Labels > Run
  // segmenter) stays while recordings of the same skin are opened.
  if (state_.labelling.segmenter_skin != document.layout.id) {
    const auto [method, parameters] = default_segmenter(document.layout.id);
    state_.labelling.segmenter_skin = document.layout.id;
    state_.labelling.last_segmenter = method;
    state_.labelling.segmenter_params.fill('\0');
    parameters.copy(state_.labelling.segmenter_params.data(),
                    state_.labelling.segmenter_params.size() - 1);
  }
  plot_moving_channels(state_);
  const std::vector<int> columns =
      taxel_columns(document.layout, source.info().channels, state_.modality);
  state_.plot = SignalPlotState{};
  // The first minute, or the whole of a shorter recording (View > Fit time axis shows the
  // whole): touches last seconds, and the plot of a minute reads a minute's samples, so an
  // hour opens as fast as a minute.
  const double span = std::min(kOpeningSpanSeconds, std::max(1e-3, source.duration()));
  state_.plot.view_t0 = source.start_time();
  state_.plot.view_t1 = source.start_time() + span;
  state_.plot.fitted = true;
  state_.clock.seek(source.start_time());
  if (document.labels.empty() || source.sample_count() == 0) return;
  // The instant of the first labelled touch where the skin changes most from rest, in view.
  const Label& first = document.labels.front();
  if (first.t1 > state_.plot.view_t1) {
    // The label a tenth of the span in, the span within the recording.
    state_.plot.view_t0 =
        std::max(source.start_time(), std::min(first.t0 - 0.1 * span, source.end_time() - span));
    state_.plot.view_t1 = state_.plot.view_t0 + span;
  }
  try {
    state_.clock.seek(peak_change_time(source, columns, current_rest_scale(state_, columns),
                                       first.t0, first.t1, kPeakSearchSamples));
  } catch (const Error& failure) {
    state_.error = failure.what();
  }
}

//---------------------------------------------------------------------------------------------
void Workbench::frame(double seconds) {
  const auto started = std::chrono::steady_clock::now();
  frame_work(seconds);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  state_.longest_frame_seconds = std::max(state_.longest_frame_seconds, took);
  constexpr size_t kFramesKept = 100000;
  if (state_.frame_seconds.size() < kFramesKept)
    state_.frame_seconds.push_back(static_cast<float>(took));
}

void Workbench::frame_work(double seconds) {
  ++state_.frame;
  poll_live(state_, services_.live);
  if (!state_.live.connected) state_.clock.advance(seconds);
  // A landed segment replays once, then the cursor rests in its middle.
  double& until = state_.analysis.confusion.replay_until;
  if (until >= 0.0 && (!state_.clock.playing() || state_.clock.time() >= until)) {
    if (state_.clock.playing() && state_.analysis.confusion.landed) {
      state_.clock.pause();
      state_.clock.seek(
          0.5 * (state_.analysis.confusion.landed->t0 + state_.analysis.confusion.landed->t1));
    }
    until = -1.0;
  }
  poll_jobs(state_);
  update_videos(state_);
  follow_other_writers(state_);
  apply_dragged_bounds(state_);
  // A dialog or the file browser with the keyboard keeps its keys (Escape, Enter, digits).
  if (!files_have_keys(state_)) handle_keys(state_);
  state_.targets = UiTargets{};

  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->WorkPos);
  ImGui::SetNextWindowSize(viewport->WorkSize);
  const bool single = !state_.options.only_view.empty();
  ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoBringToFrontOnFocus |
                           ImGuiWindowFlags_NoSavedSettings;
  if (!single) flags |= ImGuiWindowFlags_MenuBar;
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::Begin("Tactile Workbench", nullptr, flags);
  ImGui::PopStyleVar();
  if (single) {
    draw_view(state_.options.only_view.c_str(), ImGui::GetContentRegionAvail());
  } else {
    draw_menu_bar();
    const ImVec2 area = ImGui::GetContentRegionAvail();
    draw_arrangement(ImVec2(area.x, area.y - ImGui::GetFrameHeightWithSpacing()));
    draw_status_bar();
  }
  ImGui::End();
  // The dialogs before the browser: an Escape that closes the browser is not theirs too.
  draw_file_dialogs(state_);
  if (auto chosen = state_.file_browser.draw(state_)) take_browser_choice(state_, *chosen);
  draw_class_picker(state_);
  draw_key_sheet(state_);
  draw_getting_started();
  carry_out_requests();
  note_damage();
}

void Workbench::note_damage() {
  state_.unavailable = state_.document ? state_.document->source->unavailable() : std::string();
  if (!state_.document) return;
  const std::vector<std::string> damage = state_.document->source->damage();
  if (damage.empty()) return;
  std::string reason = damage.front();
  if (damage.size() > 1) reason += " (and " + std::to_string(damage.size() - 1) + " more)";
  state_.damaged[state_.document->path] = reason;
}

void Workbench::carry_out_requests() {
  carry_out_file_requests();
  if (auto path = std::exchange(state_.open_request, std::nullopt)) open(*path);
  carry_out_landing(state_);
  if (auto stream = std::exchange(state_.stream_request, std::nullopt))
    if (state_.document) select_stream(*stream);
  if (auto view = std::exchange(state_.export_request, std::nullopt)) {
    const auto found = state_.targets.items.find("view:" + *view);
    if (found == state_.targets.items.end()) {
      state_.error = "cannot export view " + *view + ": it is not shown";
    } else {
      const fs::path folder =
          state_.document ? fs::path(state_.document->path).parent_path() : fs::current_path();
      const std::string stem = state_.document ? state_.document->recording_id() : "workbench";
      char name[256];
      std::snprintf(name, sizeof name, "%s-%s-%.3fs.png", stem.c_str(), view->c_str(),
                    state_.clock.time());
      export_ = ViewExport{*view, (folder / name).string(), found->second};
    }
  }
}

std::optional<ViewExport> Workbench::take_export() { return std::exchange(export_, std::nullopt); }

void Workbench::write_export(const ViewExport& request, Image pixels) {
  // Encoding and writing a PNG of the whole window takes tens of milliseconds: a job.
  start_job<std::string>(
      state_, "export view", "export " + request.view,
      [path = request.path, pixels = std::move(pixels)](JobProgress&) {
        write_png(path, pixels);
        return path;
      },
      [](WorkbenchState& state, Job<std::string>& job) {
        if (std::optional<std::string> written = job_result(state, job))
          state.notice = "wrote " + *written;
      });
}

void Workbench::draw_view(const char* name, ImVec2 size) {
  const ViewSpec* view = find_view(name);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  state_.targets.items[std::string("view:") + name] =
      to_rect(origin, ImVec2(origin.x + size.x, origin.y + size.y));
  if (!view) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "no view %s (views: %s)", name,
                       view_names().c_str());
    return;
  }
  if (view->needs_recording && !state_.document) {
    ImGui::BeginChild(name, size, false);
    ImGui::TextDisabled("No recording open.");
    ImGui::EndChild();
    return;
  }
  view->draw(state_, size);
}

void Workbench::draw_arrangement(ImVec2 area) {
  PanelSizes& sizes = state_.sizes;
  bool released = false;
  // Left: workspace and recording, as tabs.
  ImGui::BeginChild("left", ImVec2(sizes.sidebar_width, area.y), true);
  // The recording's labels take the lower part of the sidebar, where a table has its height.
  const float tabs_height =
      state_.document ? std::floor(0.4f * area.y) : ImGui::GetContentRegionAvail().y;
  ImGui::BeginChild("left_tabs_frame", ImVec2(0, tabs_height), false);
  if (ImGui::BeginTabBar("left_tabs")) {
    for (const char* name : {"workspace", "info", "quality"}) {
      if (ImGui::BeginTabItem(view_title(name).c_str())) {
        draw_view(name, ImGui::GetContentRegionAvail());
        ImGui::EndTabItem();
      }
      remember_item(state_, std::string("tab:") + name);
    }
    ImGui::EndTabBar();
  }
  ImGui::EndChild();
  if (state_.document) {
    ImGui::Separator();
    ImGui::TextDisabled("Labels of this recording");
    draw_view("labels", ImGui::GetContentRegionAvail());
  }
  ImGui::EndChild();
  ImGui::SameLine(0.0f, 0.0f);
  released |= splitter(state_, "sidebar", true, area.y, sizes.sidebar_width, kMinimumPanel,
                       area.x - 3 * kMinimumPanel);
  ImGui::SameLine(0.0f, 0.0f);
  ImGui::BeginGroup();
  const float right_width = area.x - sizes.sidebar_width - kSplitterThickness;
  const bool any_analysis = !state_.analysis.results.rows.empty() ||
                            state_.analysis.results.dataset || state_.analysis.som.model;
  if (!state_.document && any_analysis) {
    // Results opened without a recording: the classifier views take the space.
    ImGui::BeginChild("analysis_frame", ImVec2(right_width, area.y), true);
    draw_tabs({"confusion", "scatter", "som"});
    ImGui::EndChild();
  } else if (!state_.document) {
    draw_welcome(ImVec2(right_width, area.y));
  } else {
    sizes.timeline_height = std::clamp(sizes.timeline_height, kMinimumPanel,
                                       std::max(kMinimumPanel, area.y - 2 * kMinimumPanel));
    const float top_height = area.y - sizes.timeline_height - kSplitterThickness;
    const float skin_width = std::floor(right_width * sizes.skin_fraction);
    ImGui::BeginChild("skin_frame", ImVec2(skin_width, top_height), true);
    if (has_videos(state_)) {
      // The videos under the skin, so the hand and the taxels it lights are seen together.
      const ImVec2 room = ImGui::GetContentRegionAvail();
      const float video_height = std::floor(room.y * kVideoShare);
      draw_view("skin", ImVec2(room.x, room.y - video_height - ImGui::GetStyle().ItemSpacing.y));
      draw_view("video", ImVec2(room.x, video_height));
    } else {
      draw_view("skin", ImGui::GetContentRegionAvail());
    }
    ImGui::EndChild();
    ImGui::SameLine(0.0f, 0.0f);
    float skin_pixels = skin_width;
    released |= splitter(state_, "skin", true, top_height, skin_pixels, kMinimumPanel,
                         right_width - kMinimumPanel);
    sizes.skin_fraction = skin_pixels / std::max(1.0f, right_width);
    ImGui::SameLine(0.0f, 0.0f);
    ImGui::BeginChild("signals_frame",
                      ImVec2(right_width - skin_width - kSplitterThickness, top_height), true);
    draw_tabs({"signals", "model", "confusion", "scatter", "som"});
    ImGui::EndChild();
    released |= splitter(state_, "timeline", false, right_width, sizes.timeline_height,
                         kMinimumPanel, area.y - 2 * kMinimumPanel, -1.0f);
    ImGui::BeginChild("timeline_frame", ImVec2(right_width, sizes.timeline_height), true);
    draw_view("timeline", ImGui::GetContentRegionAvail());
    ImGui::EndChild();
  }
  ImGui::EndGroup();
  if (released) save_settings();
}

namespace {

// The demo's folder when the user has not chosen one: beside the workspace, else at home.
std::string default_demo_folder(const WorkbenchState& state) {
  if (!state.workspace.empty()) return (fs::path(state.workspace) / "tactile-demo").string();
  const char* home = std::getenv("HOME");
  return (fs::path(home && *home ? home : ".") / "tactile-demo").string();
}

}  // namespace

void Workbench::draw_welcome(ImVec2 size) {
  ImGui::BeginChild("welcome", size, true);
  ImGui::TextUnformatted("No recording open. To begin:");
  ImGui::Spacing();
  if (ImGui::Button("Open a recording..."))
    state_.file_browser.open(state_.workspace.empty() ? "." : state_.workspace, {".h5"});
  remember_item(
      state_, "button:Open a recording",
      "A recording of this workbench (.h5); Ctrl+O. A folder of them opens as a workspace.");
  ImGui::SameLine();
  ImGui::TextDisabled("Ctrl+O, or pick one from the workspace on the left");
  ImGui::Spacing();
  ImGui::TextUnformatted(
      "No recordings yet? Make the demo workspace: a few touches of each of the five skins.");
  if (demo_folder_[0] == '\0') {
    const std::string folder = default_demo_folder(state_);
    folder.copy(demo_folder_.data(), demo_folder_.size() - 1);
  }
  ImGui::SetNextItemWidth(std::min(420.0f, size.x - 200.0f));
  ImGui::InputText("##demo-folder", demo_folder_.data(), demo_folder_.size());
  remember_item(state_, "input:demo-folder",
                "The folder the demo is written to (created if missing).");
  ImGui::SameLine();
  const bool making = running_job(state_, "demo") != nullptr;
  ImGui::BeginDisabled(making);
  if (ImGui::Button("Make the demo workspace")) start_demo(demo_folder_.data());
  ImGui::EndDisabled();
  remember_item(
      state_, "button:Make the demo workspace",
      "Simulates short recordings of every skin with their ground-truth labels (labels.db) "
      "and opens the folder; the same as `tactile simulate --demo DIR`.");
  ImGui::Spacing();
  ImGui::TextUnformatted(
      "Data of another program (CSV, NumPy, JSON, HDF5): `tactile import` (docs/IMPORT.md).");
  ImGui::TextUnformatted("Every key: Help > Keys, or F1. The first hour: Help > Getting started.");
  ImGui::EndChild();
}

void Workbench::start_demo(const std::string& folder) {
  // Its end opens the folder and its first recording (the Workbench outlives its jobs).
  start_job<std::string>(
      state_, "demo", "demo workspace",
      [folder](JobProgress& progress) {
        progress.report(0.0, "simulating");
        write_demo_workspace(folder, 1, [&progress](int done, int total) {
          progress.report(static_cast<double>(done) / std::max(1, total), "simulating");
        });
        return folder;
      },
      [this](WorkbenchState& state, Job<std::string>& job) {
        std::optional<std::string> made = job_result(state, job);
        if (!made) return;
        set_workspace(*made);
        for (const std::string& file : state_.workspace_files)
          if (open(file)) break;
        state_.notice = "made the demo workspace in " + *made;
      });
}

void Workbench::draw_getting_started() {
  if (!state_.help.about_open) return;
  ImGui::SetNextWindowSize(ImVec2(640, 420), ImGuiCond_Appearing);
  if (!ImGui::Begin("Getting started", &state_.help.about_open, ImGuiWindowFlags_NoCollapse)) {
    ImGui::End();
    return;
  }
  remember_item(state_, "window:getting-started");
  if (ImGui::IsWindowFocused() && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    state_.help.about_open = false;
  const char* steps[] = {
      "1. Open a recording (File > Open, Ctrl+O) or a folder of them: the skin lights up where it "
      "is "
      "touched, the plot shows the channels that move most, the lanes below show the labels.",
      "2. Label: move the cursor (click the plot, arrows), [ and ] mark start and end, a digit "
      "chooses the class (the legend above the lanes shows each class's key), Enter commits. Every "
      "label is saved the moment it is made; Ctrl+Z undoes.",
      "3. Let a segmenter suggest touches: G (or Labels > Run segmenter); A accepts one with the "
      "chosen class, R rejects it.",
      "4. Train: the Model tab's Train all compares every classifier over the workspace's labels; "
      "the confusion matrix's cells lead to the segments behind them (click a cell, Enter).",
      "5. Predict labels the open recording with the best model; U goes to the least sure "
      "prediction, Y confirms it, a digit corrects it.",
      "Every key: F1. The command line does the same headless: tactile --help."};
  for (const char* step : steps) {
    ImGui::TextWrapped("%s", step);
    ImGui::Spacing();
  }
  ImGui::End();
}

void Workbench::draw_tabs(std::initializer_list<const char*> names) {
  if (!ImGui::BeginTabBar("view_tabs")) return;
  const std::string request = std::exchange(state_.analysis.tab_request, std::string());
  for (const char* name : names) {
    const ImGuiTabItemFlags flags = request == name ? ImGuiTabItemFlags_SetSelected : 0;
    const bool open = ImGui::BeginTabItem(view_title(name).c_str(), nullptr, flags);
    remember_item(state_, std::string("tab:") + name);
    if (open) {
      draw_view(name, ImGui::GetContentRegionAvail());
      ImGui::EndTabItem();
    }
  }
  ImGui::EndTabBar();
}

}  // namespace tactile

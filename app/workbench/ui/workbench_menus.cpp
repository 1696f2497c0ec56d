// The workbench's menu bar (File, View, Labels, Help) and its status bar.
#include <imgui.h>

#include <algorithm>
#include <string>

#include "files.h"
#include "jobs.h"
#include "labelling.h"
#include "live.h"
#include "tactile/error.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"
#include "video.h"
#include "views.h"
#include "workbench.h"

namespace tactile {

void Workbench::draw_menu_bar() {
  const std::string start = state_.workspace.empty() ? "." : state_.workspace;
  if (ImGui::BeginMenuBar()) {
    if (ImGui::BeginMenu("File")) {
      if (ImGui::MenuItem("Open...", "Ctrl+O")) state_.file_browser.open(start, {".h5"});
      remember_item(state_, "menu:File/Open...");
      draw_file_open_items(state_);
      if (ImGui::BeginMenu("Connect")) {
        // udp://:PORT listens on loopback; name an interface (udp://0.0.0.0:PORT) to be reached.
        ImGui::SetNextItemWidth(260);
        ImGui::InputTextWithHint(
            "##url", ("udp://:9000, serial:///dev/ttyUSB0, sim://" + skin_ids().front()).c_str(),
            connect_url_.data(), connect_url_.size());
        remember_item(state_, "input:connect-url", "Where the live data comes from (docs/LIVE.md)");
        ImGui::SetNextItemWidth(260);
        const std::string skin_hint = "skin (udp, serial): " + joined(packet_skin_ids());
        ImGui::InputTextWithHint("##skin", skin_hint.c_str(), connect_skin_.data(),
                                 connect_skin_.size());
        remember_item(state_, "input:connect-skin",
                      "The skin whose packets arrive (udp and serial sources)");
        if (ImGui::MenuItem("Connect"))
          connect_live(state_, services_.live, connect_url_.data(), connect_skin_.data());
        remember_item(state_, "menu:File/Connect/Connect");
        if (ImGui::MenuItem("Disconnect", nullptr, false, state_.live.connected))
          disconnect_live(state_, services_.live);
        remember_item(state_, "menu:File/Connect/Disconnect");
        ImGui::EndMenu();
      }
      remember_item(state_, "menu:File/Connect");
      if (ImGui::BeginMenu("Export view as PNG", state_.document != nullptr)) {
        for (const ViewSpec& view : all_views()) {
          if (ImGui::MenuItem(view.title)) state_.export_request = view.name;
          remember_item(state_, std::string("menu:File/Export view as PNG/") + view.title);
        }
        ImGui::EndMenu();
      }
      remember_item(state_, "menu:File/Export view as PNG");
      draw_file_export_items(state_);
      if (ImGui::MenuItem("Quit", "Ctrl+Q")) state_.quit = true;
      remember_item(state_, "menu:File/Quit");
      ImGui::EndMenu();
    }
    remember_item(state_, "menu:File");
    if (ImGui::BeginMenu("View")) {
      ImGui::MenuItem("Stacked lanes", nullptr, &state_.plot.stacked);
      remember_item(state_, "menu:View/Stacked lanes");
      if (ImGui::MenuItem("Fit time axis", nullptr, false, state_.document != nullptr)) {
        state_.plot.view_t0 = state_.document->samples().start_time();
        state_.plot.view_t1 =
            state_.plot.view_t0 + std::max(1e-3, state_.document->samples().duration());
      }
      remember_item(state_, "menu:View/Fit time axis");
      if (ImGui::MenuItem("Export clip...", nullptr, false,
                          state_.document && !state_.live.connected))
        ask_clip_file(state_);
      remember_item(state_, "menu:View/Export clip...",
                    "The selected label as a video: the skin and the videos replaying, the "
                    "signals and the lanes (tactile clip)");
      if (ImGui::MenuItem("Reset panel sizes")) {
        state_.sizes = PanelSizes{};
        save_settings();
      }
      remember_item(state_, "menu:View/Reset panel sizes");
      ImGui::EndMenu();
    }
    remember_item(state_, "menu:View");
    if (ImGui::BeginMenu("Labels", state_.document != nullptr)) {
      // A segmenter's segments become suggestions in its lane: A accepts, R rejects.
      if (ImGui::BeginMenu("Run segmenter")) {
        ImGui::SetNextItemWidth(200);
        ImGui::InputTextWithHint("##params", "parameters: key=value,...",
                                 state_.labelling.segmenter_params.data(),
                                 state_.labelling.segmenter_params.size());
        remember_item(state_, "input:segmenter-params",
                      "Parameters of the segmenter chosen below (tactile segment --help); empty: "
                      "its defaults");
        for (const std::string& method : segmenter_methods()) {
          if (ImGui::MenuItem(method.c_str())) run_segmenter(state_, method);
          remember_item(state_, "menu:Labels/Run segmenter/" + method);
        }
        ImGui::EndMenu();
      }
      remember_item(state_, "menu:Labels/Run segmenter");
      if (ImGui::MenuItem("Fit segmenter to my labels")) fit_segmenter_to_labels(state_);
      remember_item(state_, "menu:Labels/Fit segmenter to my labels",
                    "Choose the segmenter's parameters from the touches you labelled here (three "
                    "or more); G then suggests touches the way you label them");
      if (ImGui::MenuItem("Keep labels in my own store", nullptr, false,
                          !state_.document->labels_read_only.empty())) {
        try {
          state_.document->keep_labels_in_own_store();
          state_.notice = "labels are kept in " + state_.document->labels_path;
        } catch (const Error& failure) {
          state_.error = failure.what();
        }
      }
      remember_item(state_, "menu:Labels/Keep labels in my own store",
                    "For a recording in a read-only folder: save labels in your own store instead");
      draw_labels_file_items(state_);
      ImGui::EndMenu();
    }
    remember_item(state_, "menu:Labels");
    draw_video_menu();
    if (ImGui::BeginMenu("Help")) {
      if (ImGui::MenuItem("Keys", "F1", state_.help.keys_open))
        state_.help.keys_open = !state_.help.keys_open;
      remember_item(state_, "menu:Help/Keys");
      if (ImGui::MenuItem("Getting started", nullptr, state_.help.about_open))
        state_.help.about_open = !state_.help.about_open;
      remember_item(state_, "menu:Help/Getting started");
      ImGui::EndMenu();
    }
    remember_item(state_, "menu:Help");
    ImGui::EndMenuBar();
  }
}

void Workbench::draw_status_bar() {
  if (draw_job_status(state_)) {
  } else if (!state_.unavailable.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "file away: %s",
                       state_.unavailable.c_str());
  } else if (!state_.error.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", state_.error.c_str());
  } else if (state_.document && !state_.document->labels_read_only.empty() &&
             state_.notice.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "read-only: %s",
                       state_.document->labels_read_only.c_str());
  } else if (!state_.notice.empty()) {
    ImGui::TextUnformatted(state_.notice.c_str());
  } else if (state_.document && (state_.damaged.count(state_.document->path) > 0 ||
                                 !state_.document->label_problems.empty())) {
    // Damage is named until the user moves on: gaps in the plot are not data.
    const auto found = state_.damaged.find(state_.document->path);
    const std::string& what =
        found != state_.damaged.end() ? found->second : state_.document->label_problems.front();
    ImGui::TextColored(ImVec4(1.0f, 0.65f, 0.2f, 1.0f), "damaged: %s", what.c_str());
    if (ImGui::IsItemHovered() && !state_.document->label_problems.empty()) {
      std::string all;
      for (const std::string& problem : state_.document->label_problems) all += problem + "\n";
      ImGui::SetTooltip("%s", all.c_str());
    }
  } else if (state_.document) {
    ImGui::TextDisabled(
        "%s   %zu labels   space: play/pause   wheel: zoom   drag (skin: right-drag): pan   "
        "double-click: fit",
        state_.document->path.c_str(), state_.document->labels.size());
  } else {
    ImGui::TextDisabled("Tactile Workbench");
  }
}

}  // namespace tactile

namespace tactile {

void Workbench::draw_video_menu() {
  const bool recording = state_.document && !state_.live.connected;
  if (ImGui::BeginMenu("Video", recording)) {
    if (ImGui::MenuItem("Attach video..."))
      state_.file_browser.open({BrowseMode::kOpenFile,
                                "attach video",
                                "Attach video",
                                state_.workspace,
                                {".mp4", ".mkv", ".mov", ".avi", ".webm"},
                                ""});
    remember_item(state_, "menu:Video/Attach video...",
                  "A video of this recording (any file FFmpeg reads), shown under the skin");
    const bool any = has_videos(state_);
    if (ImGui::MenuItem("Propose offset", nullptr, false, any)) propose_video_offset(state_);
    remember_item(state_, "menu:Video/Propose offset",
                  "Correlate the selected video's motion with the skin's activity");
    if (ImGui::MenuItem("Detach selected video", nullptr, false, any))
      detach_video(state_, state_.video.selected);
    remember_item(state_, "menu:Video/Detach selected video");
    ImGui::EndMenu();
  }
  remember_item(state_, "menu:Video");
}

}  // namespace tactile

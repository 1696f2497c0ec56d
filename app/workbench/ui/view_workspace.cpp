// Workspace view: the recordings of the open folder.
#include <algorithm>
#include <filesystem>

#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

void draw_workspace_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("workspace_view", size, false);
  const LiveState& live = state.live;
  if (live.connected) {
    // Live: the stream is what is open; the files it has been recorded into are listed below.
    ImGui::TextColored(ImVec4(0.3f, 0.9f, 0.4f, 1.0f), "live: %s", live.url.c_str());
    if (!live.recording.empty())
      ImGui::TextWrapped("recording into %s", live.recording.c_str());
    else
      ImGui::TextWrapped("not recording: Ctrl+R records into the folder below");
  }
  if (state.workspace.empty()) {
    ImGui::TextDisabled("(no workspace)");
  } else {
    ImGui::TextDisabled("%s", state.workspace.c_str());
    if (state.workspace_files.empty() && !live.connected) ImGui::TextDisabled("(no recordings)");
  }
  ImGuiListClipper clipper;  // thousands of recordings stay cheap to list
  clipper.Begin(static_cast<int>(state.workspace_files.size()));
  while (clipper.Step())
    for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
      const std::string& file = state.workspace_files[static_cast<size_t>(row)];
      const std::string shown = fs::path(file).lexically_relative(state.workspace).string();
      const bool selected = state.document && state.document->path == file;
      const auto damaged = state.damaged.find(file);
      // A damaged recording stays listed, marked, with the reason on hover.
      if (damaged != state.damaged.end())
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
      const std::string label = (damaged != state.damaged.end() ? "! " : "") + shown;
      if (ImGui::Selectable(label.c_str(), selected) && !selected) state.open_request = file;
      if (damaged != state.damaged.end()) ImGui::PopStyleColor();
      remember_item(state, "recording:" + shown);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s%s%s", file.c_str(),
                          damaged != state.damaged.end() ? "\ndamaged: " : "",
                          damaged != state.damaged.end() ? damaged->second.c_str() : "");
    }
  ImGui::EndChild();
}

}  // namespace tactile

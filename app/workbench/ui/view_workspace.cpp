// Workspace view: the recordings of the open folder.
#include <algorithm>
#include <filesystem>

#include "views.h"

namespace tactile {

namespace fs = std::filesystem;

void draw_workspace_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("workspace_view", size, false);
  if (state.workspace.empty()) {
    ImGui::TextDisabled("(no workspace)");
  } else {
    ImGui::TextDisabled("%s", state.workspace.c_str());
    if (state.workspace_files.empty()) ImGui::TextDisabled("(no recordings)");
  }
  ImGuiListClipper clipper;  // thousands of recordings stay cheap to list
  clipper.Begin(static_cast<int>(state.workspace_files.size()));
  while (clipper.Step())
    for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
      const std::string& file = state.workspace_files[static_cast<size_t>(row)];
      const std::string shown = fs::path(file).lexically_relative(state.workspace).string();
      const bool selected = state.document && state.document->path == file;
      if (ImGui::Selectable(shown.c_str(), selected) && !selected) state.open_request = file;
      remember_item(state, "recording:" + shown);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", file.c_str());
    }
  ImGui::EndChild();
}

}  // namespace tactile

#include "workbench.h"

#include <imgui.h>

namespace tactile {

void draw_workbench(WorkbenchState& state) {
  (void)state;
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImGui::GetIO().DisplaySize);
  ImGui::Begin("Tactile Workbench", nullptr, ImGuiWindowFlags_NoDecoration);
  ImGui::TextUnformatted("Tactile Workbench");
  ImGui::End();
}

}  // namespace tactile

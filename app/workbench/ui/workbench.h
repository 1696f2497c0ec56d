#pragma once
// The workbench's main window, drawn with ImGui; shared by the windowed and the
// headless program.

namespace tactile {

struct WorkbenchState {
  bool quit = false;
};

void draw_workbench(WorkbenchState& state);

}  // namespace tactile

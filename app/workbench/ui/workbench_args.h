#pragma once
// Command-line options shared by the windowed and the headless workbench.

#include <optional>
#include <string>

#include "clip.h"
#include "workbench_state.h"

namespace tactile {

struct WorkbenchArgs {
  WorkbenchOptions options;
  std::string screenshot;  // write the window (or --view) to this PNG and exit
  std::string script;      // replay this script, then exit
  bool headless = false;   // render with OSMesa, no window system
  int width = 1600;
  int height = 900;
  int frames = 4;    // frames drawn before a screenshot, so the layout settles
  ClipRequest clip;  // --clip-label: encode a clip of that label (clip.h), then exit
};

// Parses argv; on --help or an error prints and returns the exit code to use.
std::optional<int> parse_workbench_args(int argc, char** argv, WorkbenchArgs& args);

}  // namespace tactile

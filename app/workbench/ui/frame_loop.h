#pragma once
// What the windowed and the headless program both do around each frame: scripted input
// before it, and after it the script's screenshots and states, view exports, the
// --screenshot of a plain run, and when to stop.

#include <functional>
#include <memory>

#include "clip.h"
#include "script.h"
#include "workbench.h"
#include "workbench_args.h"

namespace tactile {

class FrameLoop {
 public:
  // Reads the script when there is one; throws tactile::Error naming it.
  FrameLoop(Workbench& workbench, const WorkbenchArgs& args);
  // Before ImGui::NewFrame: sets scripted input. Returns the seconds to advance by.
  double begin(double wall_seconds);
  // After rendering; `grab` reads the frame. Returns false when the program should end.
  bool end(const std::function<Image()>& grab);
  int exit_code() const { return exit_code_; }

 private:
  Workbench& workbench_;
  const WorkbenchArgs& args_;
  std::unique_ptr<ScriptPlayer> player_;
  std::unique_ptr<ClipRecorder> clip_;
  int frame_ = 0;
  int exit_code_ = 0;
};

}  // namespace tactile

// The workbench rendered off-screen with OSMesa: screenshots and scripts without a
// display, for `make run` on a machine with no X and for `tactile-workbench --headless`.
#include <imgui.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "frame_loop.h"
#include "osmesa_renderer.h"
#include "script.h"
#include "workbench.h"
#include "workbench_args.h"

int main(int argc, char** argv) {
  tactile::WorkbenchArgs args;
  if (auto code = tactile::parse_workbench_args(argc, argv, args)) return *code;
  if (args.screenshot.empty() && args.script.empty() && args.clip.label < 0) {
    std::cerr << "tactile-workbench-headless: --screenshot OUT.png, --script FILE or --clip-label "
                 "ID is required without a display\n";
    return 2;
  }
  try {
    tactile::OffscreenRenderer renderer(args.width, args.height);
    tactile::install_glfw_key_map(ImGui::GetIO());
    tactile::Workbench workbench(args.options);
    if (!workbench.error().empty()) std::cerr << "tactile-workbench: " << workbench.error() << "\n";
    tactile::FrameLoop loop(workbench, args);
    // A script may play or sleep for long; a frame cap keeps a broken one from spinning forever.
    constexpr int kMaxFrames = 10'000'000;
    using Clock = std::chrono::steady_clock;
    Clock::time_point last = Clock::now();
    for (int frame = 0; frame < kMaxFrames; ++frame) {
      renderer.prepare_frame(1.0f / 60.0f);
      // Live, frames come in real time (at most 60 a second), so data arrives between them
      // as it would on a screen; a recording is drawn as fast as it can be.
      if (workbench.state().live.connected) {
        std::this_thread::sleep_until(last + std::chrono::microseconds(16667));
        last = Clock::now();
      }
      const double seconds = loop.begin(frame == 0 ? 0.0 : 1.0 / 60.0);
      ImGui::NewFrame();
      workbench.frame(seconds);
      const tactile::Image image = renderer.render();
      if (!loop.end([&] { return image; })) break;
    }
    return loop.exit_code();
  } catch (const std::exception& error) {
    std::cerr << "tactile-workbench: " << error.what() << "\n";
    return 1;
  }
}

// The workbench rendered off-screen with OSMesa: screenshots without a display, for
// `make run` on a machine with no X and for `tactile-workbench --headless`.
#include <iostream>

#include "osmesa_renderer.h"
#include "workbench.h"
#include "workbench_args.h"

int main(int argc, char** argv) {
  tactile::WorkbenchArgs args;
  if (auto code = tactile::parse_workbench_args(argc, argv, args)) return *code;
  if (args.screenshot.empty()) {
    std::cerr << "tactile-workbench-headless: --screenshot OUT.png is required without a display\n";
    return 2;
  }
  try {
    tactile::OffscreenRenderer renderer(args.width, args.height);
    tactile::Workbench workbench(args.options);
    if (!workbench.error().empty()) std::cerr << "tactile-workbench: " << workbench.error() << "\n";
    tactile::Image image;
    for (int frame = 0; frame < args.frames; ++frame) {
      renderer.new_frame(1.0f / 60.0f);
      workbench.frame(frame == 0 ? 0.0 : 1.0 / 60.0);
      image = renderer.render();
    }
    tactile::write_png(args.screenshot, image);
    std::cout << "wrote " << args.screenshot << "\n";
    return workbench.error().empty() ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << "tactile-workbench: " << error.what() << "\n";
    return 1;
  }
}

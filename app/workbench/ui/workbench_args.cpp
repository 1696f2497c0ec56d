#include "workbench_args.h"

#include <CLI/CLI.hpp>
#include <cstdio>

namespace tactile {

std::optional<int> parse_workbench_args(int argc, char** argv, WorkbenchArgs& args) {
  CLI::App app{"Tactile Workbench: view, replay and label touch recordings from robot skins"};
  app.add_option("path", args.options.open_path, "Recording (.h5) or workspace folder to open");
  app.add_option("--labels", args.options.labels_path,
                 "Label database (default: labels.db beside the recording)");
  app.add_option("--time", args.options.time, "Put the time cursor here (seconds)");
  app.add_flag("--play", args.options.play, "Start replaying at once");
  app.add_option("--screenshot", args.screenshot, "Render the main window to this PNG and exit");
  app.add_flag("--headless", args.headless, "Render off-screen with OSMesa (no display needed)");
  app.add_option("--width", args.width, "Window width in pixels")->check(CLI::Range(320, 8192));
  app.add_option("--height", args.height, "Window height in pixels")->check(CLI::Range(240, 8192));
  app.add_option("--frames", args.frames, "Frames drawn before the screenshot")
      ->check(CLI::Range(1, 1000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  return std::nullopt;
}

}  // namespace tactile

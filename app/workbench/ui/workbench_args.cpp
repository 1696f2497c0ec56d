#include "workbench_args.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "tactile/skins/skin.h"
#include "tactile/text.h"
#include "views.h"

namespace tactile {

std::optional<int> parse_workbench_args(int argc, char** argv, WorkbenchArgs& args) {
  CLI::App app{"Tactile Workbench: view, replay and label touch recordings from robot skins"};
  app.add_option("path", args.options.open_path, "Recording (.h5) or workspace folder to open");
  app.add_option("--labels", args.options.labels_path,
                 "Label database (default: labels.db beside the recording)");
  app.add_option("--time", args.options.time, "Put the time cursor here (seconds)");
  app.add_flag("--play", args.options.play, "Start replaying at once");
  app.add_option("--screenshot", args.screenshot,
                 "Render the window (or --view) to this PNG and exit");
  app.add_option("--script", args.script, "Replay this input script (docs/SCRIPTING.md), then exit")
      ->check(CLI::ExistingFile);
  app.add_option("--view", args.options.only_view, "Draw only this view: " + view_names())
      ->check([](const std::string& name) {
        return find_view(name) ? std::string()
                               : "no view '" + name + "' (views: " + view_names() + ")";
      });
  std::string size;
  app.add_option("--size", size, "Window size WxH in pixels, e.g. 800x600");
  app.add_flag("--headless", args.headless, "Render off-screen with OSMesa (no display needed)");
  app.add_option("--width", args.width, "Window width in pixels")->check(CLI::Range(320, 8192));
  app.add_option("--height", args.height, "Window height in pixels")->check(CLI::Range(240, 8192));
  app.add_option("--frames", args.frames, "Frames drawn before the screenshot")
      ->check(CLI::Range(1, 1000));
  double cache_mb = static_cast<double>(args.options.cache_bytes) / (1 << 20);
  app.add_option("--cache-mb", cache_mb, "Memory for raw-sample chunks of the open recording (MiB)")
      ->check(CLI::Range(1.0, 65536.0));
  app.add_option("--annotator", args.options.annotator,
                 "Name recorded with every label edit (default: the settings', else $USER)");
  app.add_option("--evaluation", args.options.evaluation_path,
                 "Open an evaluation result (`tactile evaluate --out`): its confusion matrix and "
                 "the scatter of its rows")
      ->check(CLI::ExistingFile);
  app.add_option("--model", args.options.model_path,
                 "Open a saved SOM model (`evaluate --save-model`): its region map")
      ->check(CLI::ExistingFile);
  app.add_option("--features", args.options.features_path,
                 "Open a feature table (`tactile features`): its scatter")
      ->check(CLI::ExistingFile);
  app.add_option("--connect", args.options.connect,
                 "Live source: udp://:PORT (loopback; udp://0.0.0.0:PORT for every interface), "
                 "serial:///dev/ttyUSB0?baud=921600, sim://SKIN?rate=X, replay:///FILE.h5?speed=X");
  app.add_option("--camera", args.options.camera,
                 "Live: a camera shown and recorded beside the skin, v4l2:/dev/video0 or an FFmpeg "
                 "input device and its input, e.g. lavfi:testsrc2=size=320x240:rate=30 "
                 "(docs/VIDEO.md)");
  app.add_option("--skin", args.options.skin,
                 "Skin of a udp:// or serial:// source: " + joined(packet_skin_ids()));
  app.add_option("--record", args.options.record_path,
                 "Record the live source into this new file (.h5) from the start");
  app.add_option("--buffer", args.options.buffer_seconds,
                 "Seconds the live buffer holds (default 600)")
      ->check(CLI::Range(1.0, 86400.0));
  app.add_option("--pretrigger", args.options.pretrigger_seconds,
                 "Seconds before Record that a recording starts with (default 5)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--settings", args.options.settings_path,
                 "Settings file (default: ~/.config/tactile-workbench/settings.json)");
  app.add_option("--clip-label", args.clip.label,
                 "Encode a clip of this label (its id) to --clip-out, then exit (`tactile clip`)");
  app.add_option("--clip-out", args.clip.out, "The clip's file (.mp4, .mkv, .avi, .webm)");
  app.add_option("--clip-video", args.clip.video,
                 "The attached video the clip shows (default all)");
  app.add_option("--clip-margin", args.clip.margin,
                 "Seconds before and after the label (default 1)")
      ->check(CLI::Range(0.0, 600.0));
  app.add_option("--clip-rate", args.clip.rate, "Frames per second of the clip (default 30)")
      ->check(CLI::Range(1.0, 120.0));
  try {
    app.parse(argc, argv);
    if (args.clip.label >= 0) {
      if (args.clip.out.empty()) throw CLI::ValidationError("--clip-out", "a clip needs its file");
      if (args.options.open_path.empty())
        throw CLI::ValidationError("--clip-label", "a clip needs the recording it is of");
      args.options.only_view = "clip";
      args.options.clip_video = args.clip.video;
    }
    if (!args.options.connect.empty() && !args.options.open_path.empty())
      throw CLI::ValidationError("--connect",
                                 "opens a live source; give a recording or --connect, not both");
    if (!args.options.camera.empty() && args.options.connect.empty())
      throw CLI::ValidationError("--camera", "films beside a live source: give --connect too");
    if (!args.options.record_path.empty() && args.options.connect.empty())
      throw CLI::ValidationError("--record", "records a live source: give --connect too");
    if (!size.empty()) {
      int width = 0, height = 0;
      char extra = 0;
      if (std::sscanf(size.c_str(), "%dx%d%c", &width, &height, &extra) != 2 || width < 64 ||
          height < 64 || width > 8192 || height > 8192)
        throw CLI::ValidationError("--size",
                                   "expected WxH between 64x64 and 8192x8192, got '" + size + "'");
      args.width = width;
      args.height = height;
    }
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }
  args.options.cache_bytes = static_cast<int64_t>(cache_mb * (1 << 20));
  return std::nullopt;
}

}  // namespace tactile

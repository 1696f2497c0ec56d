#include "frame_loop.h"

#include <cmath>
#include <iostream>

namespace tactile {

FrameLoop::FrameLoop(Workbench& workbench, const WorkbenchArgs& args)
    : workbench_(workbench), args_(args) {
  if (!args.script.empty())
    player_ = std::make_unique<ScriptPlayer>(read_script(args.script), args.script);
  if (args.clip.label >= 0) clip_ = std::make_unique<ClipRecorder>(args.clip);
}

double FrameLoop::begin(double wall_seconds) {
  ++frame_;
  if (clip_) return clip_->before_frame(workbench_);
  return player_ ? player_->before_frame(workbench_) : wall_seconds;
}

bool FrameLoop::end(const std::function<Image()>& grab) {
  std::optional<Image> frame;
  auto image = [&]() -> const Image& {
    if (!frame) frame = grab();
    return *frame;
  };
  if (auto request = workbench_.take_export()) {
    const ScreenRect& area = request->area;
    workbench_.write_export(*request, image().crop(static_cast<int>(std::floor(area.x0)),
                                                   static_cast<int>(std::floor(area.y0)),
                                                   static_cast<int>(std::ceil(area.width())),
                                                   static_cast<int>(std::ceil(area.height()))));
  }
  if (clip_) {
    clip_->after_frame(workbench_, image);
    if (!clip_->done()) return true;
    if (!clip_->error().empty()) {
      std::cerr << "tactile-workbench: " << clip_->error() << "\n";
      exit_code_ = 1;
    } else {
      std::cout << "wrote " << args_.clip.out << ": " << clip_->frames_written() << " frames\n";
    }
    return false;
  }
  if (player_) {
    player_->after_frame(workbench_, image);
    if (player_->failed()) {
      std::cerr << "tactile-workbench: " << player_->error() << "\n";
      exit_code_ = 1;
      return false;
    }
    if (player_->done()) {
      if (!args_.screenshot.empty()) {
        write_png(args_.screenshot, image());
        std::cout << "wrote " << args_.screenshot << "\n";
      }
      return false;
    }
    return !workbench_.quit_requested();
  }
  // A screenshot shows what its view computes: frames go on while a view's job runs.
  if (!args_.screenshot.empty() && frame_ >= args_.frames && !workbench_.jobs_running()) {
    write_png(args_.screenshot, image());
    std::cout << "wrote " << args_.screenshot << "\n";
    if (!workbench_.error().empty()) exit_code_ = 1;
    return false;
  }
  return !workbench_.quit_requested();
}

}  // namespace tactile

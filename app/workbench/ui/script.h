#pragma once
// Scripted input (docs/SCRIPTING.md): a text file of commands replayed frame by frame
// through ImGui's real input path (mouse position and buttons, keys, text), naming
// targets (a taxel, a time, a view, a menu item) rather than pixels. Used by the render
// tests and by users (`tactile-workbench ... --script FILE`), windowed or headless.

#include <imgui.h>

#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "script_parse.h"
#include "tactile/widgets/image.h"
#include "workbench.h"

namespace tactile {

// The key codes of the GLFW backend, so that scripted keys mean the same headless and
// in a window; the headless program installs them as ImGui's key map.
void install_glfw_key_map(ImGuiIO& io);

class ScriptPlayer {
 public:
  ScriptPlayer(std::vector<ScriptStep> steps, std::string where);

  // Before ImGui::NewFrame (after the backend's own new frame): sets this frame's input
  // and carries out commands. Returns the seconds the workbench's clock advances by.
  double before_frame(Workbench& workbench);
  // After the frame is rendered: writes screenshots and states asked for. `grab` reads
  // the rendered frame.
  void after_frame(Workbench& workbench, const std::function<Image()>& grab);

  bool done() const { return steps_.empty() && actions_.empty() && !failed(); }
  bool failed() const { return !error_.empty(); }
  // "script.txt:12: no taxel 999 in the skin view"; "" when none.
  const std::string& error() const { return error_; }

 private:
  using Action = std::function<bool(Workbench&, ImGuiIO&)>;  // true: done, next one
  using Target = std::function<std::optional<ImVec2>(Workbench&, std::string& problem)>;
  // Adds the step's actions, by the expander its form names in script_commands.h.
  void expand(const ScriptStep& step);
  void fail(const ScriptStep& step, const std::string& message);
  void once(std::function<void(Workbench&, ImGuiIO&)> work);  // an action of one frame
  void click_at(Target where, const ScriptStep& step);
  void mouse_frame(std::function<ImVec2()> position, bool down);
  void click_named(const std::string& name, const std::string& missing, const ScriptStep& step);
  void drag(bool taxels, const ScriptStep& step);
  // The two points of a drag, found on the frame it starts; nothing (and `problem`) when a
  // target is not drawn.
  using Ends =
      std::function<std::optional<std::pair<ImVec2, ImVec2>>(Workbench&, std::string& problem)>;
  void drag_between(Ends find, const ScriptStep& step);
  void drag_item(const ScriptStep& step);
  static std::vector<std::string> menu_parts(const std::string& path);  // "File/Open..."
  void open_menus(const std::vector<std::string>& parts, const ScriptStep& step);
  void draw_until(std::function<bool(Workbench&)> finished, const std::string& timeout,
                  const ScriptStep& step);

  // The expanders, one per form of a command (the EXPAND column of script_commands.h).
  void open_path(const ScriptStep& step);
  void move_time(const ScriptStep& step);
  void press_keys(const ScriptStep& step);
  void type_text(const ScriptStep& step);
  void click_taxel(const ScriptStep& step);
  void click_time(const ScriptStep& step);
  void drag_time(const ScriptStep& step);
  void drag_taxels(const ScriptStep& step);
  void click_recording(const ScriptStep& step);
  void click_item(const ScriptStep& step);
  void click_cell(const ScriptStep& step);
  void click_view(const ScriptStep& step);
  void choose_menu(const ScriptStep& step);
  void wait_frames(const ScriptStep& step);
  void wait_training(const ScriptStep& step);
  void wait_jobs(const ScriptStep& step);
  void wait_labels(const ScriptStep& step);
  void wait_video(const ScriptStep& step);
  void wait_results(const ScriptStep& step);
  void play_recording(const ScriptStep& step);
  void sleep_wall_clock(const ScriptStep& step);
  void write_screenshot(const ScriptStep& step);
  void write_state(const ScriptStep& step);
  void inject_fault(const ScriptStep& step);

  std::deque<ScriptStep> steps_;
  std::deque<Action> actions_;
  std::string where_;
  std::string error_;
  std::optional<ScriptStep> current_;
  std::vector<std::pair<std::string, bool>> pending_outputs_;  // path, is screenshot
  std::vector<int> released_keys_;
  double frame_seconds_ = 1.0 / 60.0;
};

}  // namespace tactile

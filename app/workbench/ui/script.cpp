#include "script.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "document.h"
#include "jobs.h"
#include "script_commands.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "video.h"

namespace tactile {

namespace {

using Clock = std::chrono::steady_clock;

// The "in VIEW" suffix of click time / drag time; "signals" by default.
std::string time_view(const ScriptStep& step, size_t index) {
  if (step.words.size() > index + 1 && step.words[index] == "in") return step.words[index + 1];
  return "signals";
}

std::string seconds_with_unit(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", t);
  return text;
}

// Where time t lies on the time axis of `view` as last drawn, in its vertical middle.
std::optional<ImVec2> time_point(Workbench& workbench, const std::string& view, double t,
                                 std::string& problem) {
  const auto& axes = workbench.state().targets.time_axes;
  const auto found = axes.find(view);
  if (found == axes.end()) {
    problem = "no time axis in view '" + view + "'";
    return std::nullopt;
  }
  const TimeAxis& axis = found->second;
  if (t < axis.t0 || t > axis.t1) {
    problem = "time " + seconds_with_unit(t) + " is outside the visible range [" +
              seconds_with_unit(axis.t0) + ", " + seconds_with_unit(axis.t1) + "] of " + view;
    return std::nullopt;
  }
  const float x =
      axis.area.x0 + static_cast<float>((t - axis.t0) / (axis.t1 - axis.t0)) * axis.area.width();
  return ImVec2(std::min(x, axis.area.x1 - 1.0f), 0.5f * (axis.area.y0 + axis.area.y1));
}

ImVec2 centre_of(const ScreenRect& rect) {
  return ImVec2(0.5f * (rect.x0 + rect.x1), 0.5f * (rect.y0 + rect.y1));
}

}  // namespace

void install_glfw_key_map(ImGuiIO& io) {
  io.KeyMap[ImGuiKey_Tab] = kKeyTab;
  io.KeyMap[ImGuiKey_LeftArrow] = kKeyLeft;
  io.KeyMap[ImGuiKey_RightArrow] = kKeyRight;
  io.KeyMap[ImGuiKey_UpArrow] = kKeyUp;
  io.KeyMap[ImGuiKey_DownArrow] = kKeyDown;
  io.KeyMap[ImGuiKey_PageUp] = kKeyPageUp;
  io.KeyMap[ImGuiKey_PageDown] = kKeyPageDown;
  io.KeyMap[ImGuiKey_Home] = kKeyHome;
  io.KeyMap[ImGuiKey_End] = kKeyEnd;
  io.KeyMap[ImGuiKey_Insert] = kKeyInsert;
  io.KeyMap[ImGuiKey_Delete] = kKeyDelete;
  io.KeyMap[ImGuiKey_Backspace] = kKeyBackspace;
  io.KeyMap[ImGuiKey_Space] = kKeySpace;
  io.KeyMap[ImGuiKey_Enter] = kKeyEnter;
  io.KeyMap[ImGuiKey_Escape] = kKeyEscape;
  io.KeyMap[ImGuiKey_KeyPadEnter] = kKeyPadEnter;
  io.KeyMap[ImGuiKey_A] = 'A';
  io.KeyMap[ImGuiKey_C] = 'C';
  io.KeyMap[ImGuiKey_V] = 'V';
  io.KeyMap[ImGuiKey_X] = 'X';
  io.KeyMap[ImGuiKey_Y] = 'Y';
  io.KeyMap[ImGuiKey_Z] = 'Z';
}

//---- Playing

ScriptPlayer::ScriptPlayer(std::vector<ScriptStep> steps, std::string where)
    : steps_(steps.begin(), steps.end()), where_(std::move(where)) {}

void ScriptPlayer::fail(const ScriptStep& step, const std::string& message) {
  if (error_.empty()) error_ = where_ + ":" + std::to_string(step.line) + ": " + message;
  actions_.clear();
  steps_.clear();
}

void ScriptPlayer::expand(const ScriptStep& step) {
#define TACTILE_SCRIPT_EXPANDER(usage, help, fewest, most, check, expander) &ScriptPlayer::expander,
  static constexpr void (ScriptPlayer::*kExpanders[])(const ScriptStep&) = {
      TACTILE_SCRIPT_COMMANDS(TACTILE_SCRIPT_EXPANDER)};
#undef TACTILE_SCRIPT_EXPANDER
  (this->*kExpanders[step.form])(step);
}

void ScriptPlayer::once(std::function<void(Workbench&, ImGuiIO&)> work) {
  actions_.push_back([work](Workbench& workbench, ImGuiIO& io) {
    work(workbench, io);
    return true;
  });
}

// Moves the mouse onto the target, presses, releases, and lets one frame see the release.
void ScriptPlayer::click_at(Target where, const ScriptStep& step) {
  auto position = std::make_shared<ImVec2>();
  actions_.push_back([this, where, step, position](Workbench& workbench, ImGuiIO& io) {
    std::string problem;
    const std::optional<ImVec2> point = where(workbench, problem);
    // Before the first frame nothing has been drawn, so nothing can be found yet: wait for it.
    if (!point && workbench.state().frame < 1) return false;
    if (!point) {
      fail(step, problem);
      return true;
    }
    *position = *point;
    io.MousePos = *point;
    io.MouseDown[0] = false;
    return true;
  });
  mouse_frame([position] { return *position; }, true);
  mouse_frame([position] { return *position; }, false);
  once([](Workbench&, ImGuiIO&) {});
}

// One frame with the mouse at `position()` (known once an earlier frame found the target)
// and its left button `down`.
void ScriptPlayer::mouse_frame(std::function<ImVec2()> position, bool down) {
  actions_.push_back([position, down](Workbench&, ImGuiIO& io) {
    io.MousePos = position();
    io.MouseDown[0] = down;
    return true;
  });
}

// Clicks the centre of an item as last drawn (UiTargets::items); `missing` when there is none.
void ScriptPlayer::click_named(const std::string& name, const std::string& missing,
                               const ScriptStep& step) {
  click_at(
      [name, missing](Workbench& workbench, std::string& problem) -> std::optional<ImVec2> {
        const auto& items = workbench.state().targets.items;
        const auto found = items.find(name);
        if (found == items.end()) {
          problem = missing;
          return std::nullopt;
        }
        return centre_of(found->second);
      },
      step);
}

// From one point to another: times on a time axis, or the centres of two taxels (a rectangle
// over the skin).
void ScriptPlayer::drag(bool taxels, const ScriptStep& step) {
  const double a = std::stod(step.words[1]), b = std::stod(step.words[2]);
  const std::string view = taxels ? "skin" : time_view(step, 3);
  drag_between(
      [a, b, taxels, view](Workbench& workbench,
                           std::string& problem) -> std::optional<std::pair<ImVec2, ImVec2>> {
        auto point = [&](double value) -> std::optional<ImVec2> {
          if (!taxels) return time_point(workbench, view, value, problem);
          const auto& centres = workbench.state().targets.taxels;
          const auto found = centres.find(static_cast<int64_t>(value));
          if (found == centres.end()) {
            problem =
                "no taxel " + std::to_string(static_cast<int64_t>(value)) + " in the skin view";
            return std::nullopt;
          }
          return ImVec2(found->second.first, found->second.second);
        };
        const auto from = point(a);
        const auto to = from ? point(b) : std::nullopt;
        if (!from || !to) return std::nullopt;
        std::pair<ImVec2, ImVec2> ends{*from, *to};
        if (taxels) {
          // A rectangle that holds both centres: corners 3 pixels beyond them (ImGui
          // floors mouse positions to whole pixels).
          auto outward = [](float& low, float& high) {
            const float sign = high >= low ? 1.0f : -1.0f;
            low -= 3.0f * sign;
            high += 3.0f * sign;
          };
          outward(ends.first.x, ends.second.x);
          outward(ends.first.y, ends.second.y);
        }
        return ends;
      },
      step);
}

// Presses where `find` says, moves to its second point in 8 steps, releases.
void ScriptPlayer::drag_between(Ends find, const ScriptStep& step) {
  auto ends = std::make_shared<std::pair<ImVec2, ImVec2>>();
  actions_.push_back([this, step, find, ends](Workbench& workbench, ImGuiIO& io) {
    std::string problem;
    const std::optional<std::pair<ImVec2, ImVec2>> found = find(workbench, problem);
    if (!found && workbench.state().frame < 1) return false;
    if (!found) {
      fail(step, problem);
      return true;
    }
    *ends = *found;
    io.MousePos = ends->first;
    io.MouseDown[0] = false;
    return true;
  });
  mouse_frame([ends] { return ends->first; }, true);
  constexpr int kDragSteps = 8;
  for (int k = 1; k <= kDragSteps; ++k)
    mouse_frame(
        [ends, k] {
          const float f = static_cast<float>(k) / kDragSteps;
          return ImVec2(ends->first.x + f * (ends->second.x - ends->first.x),
                        ends->first.y + f * (ends->second.y - ends->first.y));
        },
        true);
  mouse_frame([ends] { return ends->second; }, false);
  once([](Workbench&, ImGuiIO&) {});
}

// Frames go on being drawn (the window stays responsive) until `finished`; ten minutes at
// most, then the step fails with `timeout`.
void ScriptPlayer::draw_until(std::function<bool(Workbench&)> finished, const std::string& timeout,
                              const ScriptStep& step) {
  auto deadline = std::make_shared<std::optional<Clock::time_point>>();
  actions_.push_back([this, finished, timeout, step, deadline](Workbench& workbench, ImGuiIO&) {
    const auto now = Clock::now();
    if (!*deadline) *deadline = now + std::chrono::minutes(10);
    if (finished(workbench)) return true;
    if (now >= **deadline) {
      fail(step, timeout);
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return false;
  });
}

//---- The commands (script_commands.h), in the order of docs/SCRIPTING.md

void ScriptPlayer::open_path(const ScriptStep& step) {
  once([this, step](Workbench& workbench, ImGuiIO&) {
    workbench.open(step.rest);
    if (!workbench.error().empty()) fail(step, workbench.error());
  });
}

void ScriptPlayer::move_time(const ScriptStep& step) {
  const double t = std::stod(step.words[0]);
  once([t](Workbench& workbench, ImGuiIO&) { workbench.seek(t); });
}

void ScriptPlayer::press_keys(const ScriptStep& step) {
  for (const std::string& word : step.words) {
    const KeyChord chord = parse_chord(word);
    once([chord](Workbench&, ImGuiIO& io) {
      io.KeyCtrl = chord.ctrl;
      io.KeyShift = chord.shift;
      io.KeyAlt = chord.alt;
      io.KeySuper = chord.super;
      io.KeysDown[chord.code] = true;
      if (chord.character && !chord.ctrl && !chord.alt && !chord.super)
        io.AddInputCharacter(chord.character);
    });
    once([chord](Workbench&, ImGuiIO& io) {
      io.KeysDown[chord.code] = false;
      io.KeyCtrl = io.KeyShift = io.KeyAlt = io.KeySuper = false;
    });
  }
}

void ScriptPlayer::type_text(const ScriptStep& step) {
  once([text = step.rest](Workbench&, ImGuiIO& io) { io.AddInputCharactersUTF8(text.c_str()); });
  once([](Workbench&, ImGuiIO&) {});
}

void ScriptPlayer::click_taxel(const ScriptStep& step) {
  const auto id = static_cast<int64_t>(std::stod(step.words[1]));
  click_at(
      [id](Workbench& workbench, std::string& problem) -> std::optional<ImVec2> {
        const UiTargets& targets = workbench.state().targets;
        const auto found = targets.taxels.find(id);
        if (found == targets.taxels.end()) {
          problem = "no taxel " + std::to_string(id) + " in the skin view";
          return std::nullopt;
        }
        const ImVec2 point(found->second.first, found->second.second);
        if (!targets.skin_map.contains(point.x, point.y)) {
          problem = "taxel " + std::to_string(id) + " is outside the visible skin view";
          return std::nullopt;
        }
        return point;
      },
      step);
}

void ScriptPlayer::click_time(const ScriptStep& step) {
  const double t = std::stod(step.words[1]);
  const std::string view = time_view(step, 2);
  click_at([t, view](Workbench& workbench,
                     std::string& problem) { return time_point(workbench, view, t, problem); },
           step);
}

void ScriptPlayer::drag_time(const ScriptStep& step) { drag(false, step); }

void ScriptPlayer::drag_item(const ScriptStep& step) {
  const std::string name = step.words[1];
  std::array<float, 4> at{};
  for (size_t k = 0; k < 4; ++k) at[k] = static_cast<float>(std::stod(step.words[2 + k]));
  drag_between(
      [name, at](Workbench& workbench,
                 std::string& problem) -> std::optional<std::pair<ImVec2, ImVec2>> {
        const auto& items = workbench.state().targets.items;
        const auto found = items.find(name);
        if (found == items.end()) {
          problem = "no item " + name + " drawn";
          return std::nullopt;
        }
        const ScreenRect& box = found->second;
        auto point = [&](float x, float y) {
          return ImVec2(box.x0 + x * box.width(), box.y0 + y * box.height());
        };
        return std::pair{point(at[0], at[1]), point(at[2], at[3])};
      },
      step);
}

void ScriptPlayer::drag_taxels(const ScriptStep& step) { drag(true, step); }

void ScriptPlayer::click_recording(const ScriptStep& step) {
  click_named("recording:" + step.words[1], "no " + step.words[1] + " in the workspace list", step);
}

void ScriptPlayer::click_item(const ScriptStep& step) {
  // The rest of the line after "item": names may hold spaces.
  const std::string name = step.rest.substr(step.rest.find_first_not_of(" \t", 4));
  if (name.starts_with("menu:") && name.find('/') != std::string::npos) {
    // An item of a menu that is not open (`menu:Help/Keys` with the Help menu closed): its
    // menus are opened first, as `menu` does; an open one is clicked as it is.
    actions_.push_back([this, name, step](Workbench& workbench, ImGuiIO&) {
      if (workbench.state().frame < 1) return false;  // nothing drawn yet
      if (workbench.state().targets.items.contains(name)) return true;
      std::deque<Action> rest(actions_.begin() + 1, actions_.end());
      actions_.clear();
      actions_.push_back([](Workbench&, ImGuiIO&) { return true; });  // this one, popped
      open_menus(menu_parts(name.substr(5)), step);
      actions_.insert(actions_.end(), rest.begin(), rest.end());
      return true;
    });
  }
  click_named(name, "no item '" + name + "' on screen", step);
}

void ScriptPlayer::click_cell(const ScriptStep& step) {
  const std::string cell = step.words[1] + "/" + step.words[2];
  click_named("cell:" + cell,
              "no confusion cell " + cell +
                  " on screen (open the Confusion tab; class names as on its axes)",
              step);
}

void ScriptPlayer::click_view(const ScriptStep& step) {
  const std::string view = step.words[0];
  const float fx = std::stof(step.words[1]), fy = std::stof(step.words[2]);
  click_at(
      [view, fx, fy](Workbench& workbench, std::string& problem) -> std::optional<ImVec2> {
        const auto& items = workbench.state().targets.items;
        const auto found = items.find("view:" + view);
        if (found == items.end()) {
          problem = "no view '" + view + "' on screen";
          return std::nullopt;
        }
        const ScreenRect& rect = found->second;
        return ImVec2(rect.x0 + fx * rect.width(), rect.y0 + fy * rect.height());
      },
      step);
}

std::vector<std::string> ScriptPlayer::menu_parts(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  for (std::string part; std::getline(in, part, '/');) parts.push_back(part);
  return parts;
}

// The menus above the last part of `parts`: the bar entry clicked, each submenu hovered.
void ScriptPlayer::open_menus(const std::vector<std::string>& parts, const ScriptStep& step) {
  std::string name = "menu:";
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    name += (k ? "/" : "") + parts[k];
    const std::string missing = "no menu item '" + name.substr(5) + "'";
    if (k > 0) {  // a submenu: hovered, not clicked
      actions_.push_back([this, step, name, missing](Workbench& workbench, ImGuiIO& io) {
        const auto& items = workbench.state().targets.items;
        const auto found = items.find(name);
        if (found == items.end())
          fail(step, missing);
        else
          io.MousePos = centre_of(found->second);
        return true;
      });
      actions_.push_back([](Workbench&, ImGuiIO&) { return true; });
    } else {
      click_named(name, missing, step);
    }
  }
}

// "File/Export view as PNG/Skin": click the bar entry, hover each submenu, click the item.
void ScriptPlayer::choose_menu(const ScriptStep& step) {
  const std::vector<std::string> parts = menu_parts(step.rest);
  open_menus(parts, step);
  std::string name = "menu:";
  for (size_t k = 0; k < parts.size(); ++k) name += (k ? "/" : "") + parts[k];
  click_named(name, "no menu item '" + name.substr(5) + "'", step);
}

void ScriptPlayer::wait_frames(const ScriptStep& step) {
  const int frames = static_cast<int>(std::stod(step.words[0]));
  for (int k = 0; k < frames; ++k) once([](Workbench&, ImGuiIO&) {});
}

void ScriptPlayer::wait_training(const ScriptStep& step) {
  draw_until(
      [this, step](Workbench& workbench) {
        if (find_job(workbench.state(), "training")) return false;
        if (!workbench.error().empty() && workbench.error().starts_with("training failed"))
          fail(step, workbench.error());
        return true;
      },
      "training still running after 10 minutes", step);
}

void ScriptPlayer::wait_jobs(const ScriptStep& step) {
  draw_until([](Workbench& workbench) { return !workbench.jobs_running(); },
             "a view's job still running after 10 minutes", step);
}

void ScriptPlayer::wait_video(const ScriptStep& step) {
  draw_until([](Workbench& workbench) { return videos_caught_up(workbench.state()); },
             "a video does not show the frame at the cursor after 10 minutes", step);
}

void ScriptPlayer::wait_labels(const ScriptStep& step) {
  const size_t wanted = static_cast<size_t>(std::stod(step.words[1]));
  draw_until(
      [wanted](Workbench& workbench) {
        const Document* document = workbench.state().document.get();
        return document && document->labels.size() == wanted;
      },
      "the recording does not show " + step.words[1] + " labels after 10 minutes", step);
}

void ScriptPlayer::wait_results(const ScriptStep& step) {
  const size_t wanted = static_cast<size_t>(std::stod(step.words[1]));
  draw_until(
      [wanted](Workbench& workbench) {
        return workbench.state().analysis.results.rows.size() >= wanted;
      },
      "the results do not hold " + step.words[1] + " rows after 10 minutes", step);
}

void ScriptPlayer::play_recording(const ScriptStep& step) {
  auto remaining = std::make_shared<double>(std::stod(step.words[0]));
  auto started = std::make_shared<bool>(false);
  actions_.push_back([remaining, started, this](Workbench& workbench, ImGuiIO&) {
    PlaybackClock& clock = workbench.state().clock;
    if (!*started) {
      *started = true;
      clock.play();
    }
    if (*remaining <= 1e-12 || !clock.playing()) {
      clock.pause();
      frame_seconds_ = 1.0 / 60.0;
      return true;
    }
    const double recording_step = std::min(*remaining, clock.speed() / 30.0);
    frame_seconds_ = recording_step / clock.speed();
    *remaining -= recording_step;
    return false;
  });
}

void ScriptPlayer::sleep_wall_clock(const ScriptStep& step) {
  const double seconds = std::stod(step.words[0]);
  auto deadline = std::make_shared<std::optional<Clock::time_point>>();
  actions_.push_back([seconds, deadline](Workbench&, ImGuiIO&) {
    const auto now = Clock::now();
    if (!*deadline)
      *deadline =
          now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    if (now >= **deadline) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
    return false;
  });
}

// Written after the frame is rendered (after_frame).
void ScriptPlayer::write_screenshot(const ScriptStep& step) {
  once([this, path = step.rest](Workbench&, ImGuiIO&) {
    pending_outputs_.emplace_back(path, true);
  });
}

void ScriptPlayer::write_state(const ScriptStep& step) {
  once([this, path = step.rest](Workbench&, ImGuiIO&) {
    pending_outputs_.emplace_back(path, false);
  });
}

void ScriptPlayer::inject_fault(const ScriptStep& step) {
  const ReadFault fault = step.words[1] == "hang"   ? ReadFault::kHang
                          : step.words[1] == "fail" ? ReadFault::kFail
                                                    : ReadFault::kNone;
  once([fault](Workbench&, ImGuiIO&) { inject_read_fault(fault); });
}

//---- Frames

double ScriptPlayer::before_frame(Workbench& workbench) {
  ImGuiIO& io = ImGui::GetIO();
  frame_seconds_ = 1.0 / 60.0;
  while (actions_.empty() && !steps_.empty()) {
    current_ = steps_.front();
    steps_.pop_front();
    expand(*current_);
  }
  if (!actions_.empty()) {
    Action action = actions_.front();
    if (action(workbench, io) && !actions_.empty()) actions_.pop_front();
  }
  return frame_seconds_;
}

void ScriptPlayer::after_frame(Workbench& workbench, const std::function<Image()>& grab) {
  for (const auto& [path, screenshot] : pending_outputs_) {
    try {
      if (screenshot) {
        write_png(path, grab());
      } else {
        // Whole or not at all: a test polls for the file while the script goes on (the live
        // test read a state still being written, as empty JSON, under a sanitizer).
        write_file_atomically(path, workbench.state_json().dump(2) + "\n");
      }
    } catch (const std::exception& failure) {
      if (error_.empty()) error_ = where_ + ": " + failure.what();
      steps_.clear();
      actions_.clear();
    }
  }
  pending_outputs_.clear();
}

}  // namespace tactile

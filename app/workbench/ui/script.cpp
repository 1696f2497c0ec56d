#include "script.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "tactile/error.h"

namespace tactile {

namespace {

using Clock = std::chrono::steady_clock;

// The "in VIEW" suffix of click time / drag time; "signals" by default.
std::string time_view(const ScriptStep& step, size_t index) {
  if (step.words.size() > index + 1 && step.words[index] == "in") return step.words[index + 1];
  return "signals";
}

std::string seconds_text(double t) {
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
    problem = "time " + seconds_text(t) + " is outside the visible range [" +
              seconds_text(axis.t0) + ", " + seconds_text(axis.t1) + "] of " + view;
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

// Moves the mouse onto the target, presses, releases, and lets one frame see the release.
void ScriptPlayer::click_at(std::function<std::optional<ImVec2>(Workbench&, std::string&)> where,
                            const ScriptStep& step) {
  auto position = std::make_shared<ImVec2>();
  actions_.push_back([this, where, step, position](Workbench& workbench, ImGuiIO& io) {
    std::string problem;
    const std::optional<ImVec2> point = where(workbench, problem);
    if (!point) {
      fail(step, problem);
      return true;
    }
    *position = *point;
    io.MousePos = *point;
    io.MouseDown[0] = false;
    return true;
  });
  actions_.push_back([position](Workbench&, ImGuiIO& io) {
    io.MousePos = *position;
    io.MouseDown[0] = true;
    return true;
  });
  actions_.push_back([position](Workbench&, ImGuiIO& io) {
    io.MousePos = *position;
    io.MouseDown[0] = false;
    return true;
  });
  actions_.push_back([](Workbench&, ImGuiIO&) { return true; });
}

void ScriptPlayer::expand(const ScriptStep& step) {
  const std::string& command = step.command;
  auto once = [this](std::function<void(Workbench&, ImGuiIO&)> work) {
    actions_.push_back([work](Workbench& workbench, ImGuiIO& io) {
      work(workbench, io);
      return true;
    });
  };
  if (command == "open") {
    once([this, step](Workbench& workbench, ImGuiIO&) {
      workbench.open(step.rest);
      if (!workbench.error().empty()) fail(step, workbench.error());
    });
  } else if (command == "time") {
    const double t = std::stod(step.words[0]);
    once([t](Workbench& workbench, ImGuiIO&) { workbench.seek(t); });
  } else if (command == "wait" && step.words[0] == "jobs") {
    // Frames go on being drawn until no view's job (SOM, scatter) runs; ten minutes at most.
    auto deadline = std::make_shared<std::optional<Clock::time_point>>();
    actions_.push_back([this, step, deadline](Workbench& workbench, ImGuiIO&) {
      const auto now = Clock::now();
      if (!*deadline) *deadline = now + std::chrono::minutes(10);
      if (!workbench.jobs_running()) return true;
      if (now >= **deadline) {
        fail(step, "a view's job still running after 10 minutes");
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return false;
    });
  } else if (command == "wait" && step.words[0] == "training") {
    // Frames go on being drawn (the window stays responsive) until the run ends; ten
    // minutes at most.
    auto deadline = std::make_shared<std::optional<Clock::time_point>>();
    actions_.push_back([this, step, deadline](Workbench& workbench, ImGuiIO&) {
      const auto now = Clock::now();
      if (!*deadline) *deadline = now + std::chrono::minutes(10);
      const auto& job = workbench.state().analysis.job;
      if (!job) {
        if (!workbench.error().empty() && workbench.error().starts_with("training failed"))
          fail(step, workbench.error());
        return true;
      }
      if (now >= **deadline) {
        fail(step, "training still running after 10 minutes");
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return false;
    });
  } else if (command == "wait") {
    const int frames = static_cast<int>(std::stod(step.words[0]));
    for (int k = 0; k < frames; ++k) once([](Workbench&, ImGuiIO&) {});
  } else if (command == "key") {
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
  } else if (command == "type") {
    once([text = step.rest](Workbench&, ImGuiIO& io) { io.AddInputCharactersUTF8(text.c_str()); });
    once([](Workbench&, ImGuiIO&) {});
  } else if (command == "click" && step.words[0] == "taxel") {
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
  } else if (command == "click" && (step.words[0] == "recording" || step.words[0] == "item" ||
                                    (step.words[0] == "cell" && step.words.size() == 3))) {
    const std::string name = step.words[0] == "recording" ? "recording:" + step.words[1]
                             : step.words[0] == "cell" ? "cell:" + step.words[1] + "/" + step.words[2]
                                                       : step.rest.substr(step.rest.find_first_not_of(" \t", 4));
    click_at(
        [name](Workbench& workbench, std::string& problem) -> std::optional<ImVec2> {
          const auto& items = workbench.state().targets.items;
          const auto found = items.find(name);
          if (found == items.end()) {
            problem = name.starts_with("recording:")
                          ? "no " + name.substr(10) + " in the workspace list"
                      : name.starts_with("cell:")
                          ? "no confusion cell " + name.substr(5) +
                                " on screen (open the Confusion tab; class names as on its axes)"
                          : "no item '" + name + "' on screen";
            return std::nullopt;
          }
          return centre_of(found->second);
        },
        step);
  } else if (command == "click" && step.words[0] == "time") {
    const double t = std::stod(step.words[1]);
    const std::string view = time_view(step, 2);
    click_at(
        [t, view](Workbench& workbench, std::string& problem) {
          return time_point(workbench, view, t, problem);
        },
        step);
  } else if (command == "click") {
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
  } else if (command == "drag") {
    // From one point to another: times on a time axis, or the centres of two taxels
    // (a rectangle over the skin).
    const double a = std::stod(step.words[1]), b = std::stod(step.words[2]);
    const bool taxels = step.words[0] == "taxel";
    const std::string view = taxels ? "skin" : time_view(step, 3);
    auto ends = std::make_shared<std::pair<ImVec2, ImVec2>>();
    actions_.push_back([this, step, a, b, taxels, view, ends](Workbench& workbench, ImGuiIO& io) {
      std::string problem;
      auto point = [&](double value) -> std::optional<ImVec2> {
        if (!taxels) return time_point(workbench, view, value, problem);
        const auto& centres = workbench.state().targets.taxels;
        const auto found = centres.find(static_cast<int64_t>(value));
        if (found == centres.end()) {
          problem = "no taxel " + std::to_string(static_cast<int64_t>(value)) + " in the skin view";
          return std::nullopt;
        }
        return ImVec2(found->second.first, found->second.second);
      };
      const auto from = point(a);
      const auto to = from ? point(b) : std::nullopt;
      if (!from || !to) {
        fail(step, problem);
        return true;
      }
      *ends = {*from, *to};
      if (taxels) {
        // A rectangle that holds both centres: corners 3 pixels beyond them (ImGui
        // floors mouse positions to whole pixels).
        auto outward = [](float& a, float& b) {
          const float sign = b >= a ? 1.0f : -1.0f;
          a -= 3.0f * sign;
          b += 3.0f * sign;
        };
        outward(ends->first.x, ends->second.x);
        outward(ends->first.y, ends->second.y);
      }
      io.MousePos = ends->first;
      io.MouseDown[0] = false;
      return true;
    });
    actions_.push_back([ends](Workbench&, ImGuiIO& io) {
      io.MousePos = ends->first;
      io.MouseDown[0] = true;
      return true;
    });
    constexpr int kDragSteps = 8;
    for (int k = 1; k <= kDragSteps; ++k)
      actions_.push_back([ends, k](Workbench&, ImGuiIO& io) {
        const float f = static_cast<float>(k) / kDragSteps;
        io.MousePos = ImVec2(ends->first.x + f * (ends->second.x - ends->first.x),
                             ends->first.y + f * (ends->second.y - ends->first.y));
        io.MouseDown[0] = true;
        return true;
      });
    actions_.push_back([ends](Workbench&, ImGuiIO& io) {
      io.MousePos = ends->second;
      io.MouseDown[0] = false;
      return true;
    });
    actions_.push_back([](Workbench&, ImGuiIO&) { return true; });
  } else if (command == "menu") {
    // "File/Export view as PNG/Skin": click the bar entry, hover each submenu, click the item.
    std::vector<std::string> parts;
    std::stringstream path(step.rest);
    for (std::string part; std::getline(path, part, '/');) parts.push_back(part);
    std::string name = "menu:";
    for (size_t k = 0; k < parts.size(); ++k) {
      name += (k ? "/" : "") + parts[k];
      const bool hover_only = k > 0 && k + 1 < parts.size();
      auto resolve = [name](Workbench& workbench, std::string& problem) -> std::optional<ImVec2> {
        const auto& items = workbench.state().targets.items;
        const auto found = items.find(name);
        if (found == items.end()) {
          problem = "no menu item '" + name.substr(5) + "'";
          return std::nullopt;
        }
        return centre_of(found->second);
      };
      if (hover_only) {
        actions_.push_back([this, step, resolve](Workbench& workbench, ImGuiIO& io) {
          std::string problem;
          const auto point = resolve(workbench, problem);
          if (!point) fail(step, problem);
          else io.MousePos = *point;
          return true;
        });
        actions_.push_back([](Workbench&, ImGuiIO&) { return true; });
      } else {
        click_at(resolve, step);
      }
    }
  } else if (command == "play") {
    const double seconds = std::stod(step.words[0]);
    auto remaining = std::make_shared<double>(seconds);
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
  } else if (command == "sleep") {
    const double seconds = std::stod(step.words[0]);
    auto deadline = std::make_shared<std::optional<Clock::time_point>>();
    actions_.push_back([seconds, deadline](Workbench&, ImGuiIO&) {
      const auto now = Clock::now();
      if (!*deadline)
        *deadline = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
      if (now >= **deadline) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      return false;
    });
  } else if (command == "screenshot" || command == "state") {
    const bool screenshot = command == "screenshot";
    once([this, path = step.rest, screenshot](Workbench&, ImGuiIO&) {
      pending_outputs_.emplace_back(path, screenshot);
    });
  }
}

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
        std::ofstream out(path);
        out << workbench.state_json().dump(2) << "\n";
        if (!out) throw Error(path, "cannot write the state");
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

// Timeline view: transport (play, speed, loop, time), the classes with their keys and
// the marks being made, one lane per tier of labels over the plot's time range (a
// click moves the cursor and selects; right-click a lane's name to hide, collapse or
// move it). The table of labels is a view of its own (view_labels.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "keys.h"
#include "labelling.h"
#include "live.h"
#include "views.h"

namespace tactile {

namespace {

constexpr double kSpeeds[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr float kLaneHeight = 22.0f;
constexpr float kCollapsedHeight = 7.0f;

void draw_transport(WorkbenchState& state) {
  PlaybackClock& clock = state.clock;
  if (ImGui::Button(clock.playing() ? "Pause" : "Play", ImVec2(70, 0))) clock.toggle();
  remember_item(state, "button:play", "Play or pause the recording (Space)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  char speed_text[16];
  std::snprintf(speed_text, sizeof(speed_text), "%gx", clock.speed());
  const bool speeds = ImGui::BeginCombo("##speed", speed_text);
  remember_item(state, "combo:speed", "Playback speed (recording seconds per second)");
  if (speeds) {
    for (double speed : kSpeeds) {
      std::snprintf(speed_text, sizeof(speed_text), "%gx", speed);
      if (ImGui::Selectable(speed_text, speed == clock.speed())) clock.set_speed(speed);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  bool looping = clock.looping();
  if (ImGui::Checkbox("loop", &looping)) clock.set_looping(looping);
  remember_item(state, "checkbox:loop", "Play the recording (or the landed segment) over and over");
  ImGui::SameLine();
  const std::string now = format_seconds(clock.time()) + " / " + format_seconds(clock.end());
  ImGui::SetNextItemWidth(-1);
  float time = static_cast<float>(clock.time());
  if (ImGui::SliderFloat("##time", &time, static_cast<float>(clock.start()),
                         static_cast<float>(clock.end()), now.c_str()))
    clock.seek(time);
  remember_item(state, "slider:time", "The time cursor: drag to move through the recording");
}

}  // namespace

// The lanes in the user's order (hidden ones left out); the operator's own lane is
// always there, empty or not, because that is where new labels go.
std::vector<std::pair<std::string, const LaneIndex*>> shown_lanes(const WorkbenchState& state) {
  static const LaneIndex kEmpty;
  const Lanes& lanes = state.document->lanes;
  std::vector<std::pair<std::string, const LaneIndex*>> all;
  for (size_t k = 0; k < lanes.keys.size(); ++k)
    all.emplace_back(lanes.keys[k].id(), &lanes.lanes[k]);
  const std::string own = state.labelling.active_lane();
  if (std::none_of(all.begin(), all.end(), [&](const auto& lane) { return lane.first == own; }))
    all.emplace_back(own, &kEmpty);
  const std::vector<std::string>& order = state.labelling.lane_order;
  auto rank = [&](const std::string& id) {
    const auto found = std::find(order.begin(), order.end(), id);
    return found == order.end() ? order.size() : static_cast<size_t>(found - order.begin());
  };
  std::stable_sort(all.begin(), all.end(),
                   [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
  std::erase_if(all,
                [&](const auto& lane) { return state.labelling.hidden.count(lane.first) > 0; });
  return all;
}

const LaneIndex* top_lane(const WorkbenchState& state) {
  if (!state.document) return nullptr;
  for (const auto& [id, lane] : shown_lanes(state))
    if (lane->size() > 0) return lane;
  return nullptr;
}

namespace {

std::string lane_title(const std::string& id) {
  if (id == "ground-truth") return "truth";
  const size_t colon = id.find(':');
  std::string title = colon == std::string::npos ? id : id.substr(colon + 1);
  if (title.starts_with("segmenter:")) title = title.substr(10);
  return title;
}

// Moves a lane one place up or down in the user's order.
void move_lane(WorkbenchState& state, const std::vector<std::string>& shown, const std::string& id,
               int step) {
  std::vector<std::string>& order = state.labelling.lane_order;
  for (const std::string& lane : shown)
    if (std::find(order.begin(), order.end(), lane) == order.end()) order.push_back(lane);
  const auto at = std::find(order.begin(), order.end(), id);
  const auto to = at + step;
  if (at == order.end() || to < order.begin() || to >= order.end()) return;
  std::iter_swap(at, to);
}

// The skin's classes with their keys, the marks and who is labelling.
void draw_legend(WorkbenchState& state) {
  const Document& document = *state.document;
  const LabellingState& labelling = state.labelling;
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  // Every class with its key (keys.h: 1-9, 0, Shift+digits; beyond 20 the C picker), wrapped
  // onto as many lines as the panel needs.
  const float right = ImGui::GetWindowContentRegionMax().x + ImGui::GetWindowPos().x;
  const float size = ImGui::GetTextLineHeight();
  for (size_t k = 0; k < document.classes.size(); ++k) {
    const std::string& name = document.classes[k];
    const std::string key = class_key(static_cast<int>(k) + 1);
    const std::string text = key.empty() ? name : key + " " + name;
    const float width = size + 4 + ImGui::CalcTextSize(text.c_str()).x;
    if (k > 0) {
      ImGui::SameLine(0, 10);
      if (ImGui::GetCursorScreenPos().x + width > right) ImGui::NewLine();
    }
    const ImVec2 at = ImGui::GetCursorScreenPos();
    remember_legend(state, "lanes", name, at, size);
    draw.AddRectFilled(at, ImVec2(at.x + size, at.y + size), class_colour(state, name), 2.0f);
    ImGui::Dummy(ImVec2(size, size));
    ImGui::SameLine(0, 4);
    const bool chosen = labelling.pending_class == name;
    ImGui::TextColored(chosen ? ImVec4(1, 1, 1, 1) : ImVec4(0.7f, 0.7f, 0.7f, 1), "%s",
                       text.c_str());
  }
  ImGui::SameLine(0, 20);
  auto mark = [](const std::optional<double>& t) {
    return t ? format_seconds(*t) : std::string("-");
  };
  ImGui::TextDisabled("[ %s  ] %s  %s   %s", mark(labelling.mark_start).c_str(),
                      mark(labelling.mark_end).c_str(),
                      labelling.pending_class.empty() ? "" : labelling.pending_class.c_str(),
                      labelling.annotator.c_str());
}

// In the operator's lane (the last item drawn), a drag from an edge of one of their
// labels moves that edge, committed on release; a drag over empty space sets the
// marks. Dragged times snap to other lanes' boundaries within 6 pixels (key S).
template <typename XOf>
void drag_in_own_lane(WorkbenchState& state, const LaneIndex& lane, double mouse_time,
                      double seconds_per_pixel, const XOf& x_of, ImVec2 lane_min, ImVec2 lane_max) {
  LabellingState::LaneDrag& drag = state.labelling.drag;
  const double grab = 4.0 * seconds_per_pixel;
  if (ImGui::IsItemActivated()) {
    drag = {};
    drag.active = true;
    drag.press_time = drag.time = mouse_time;
    for (size_t index : lane.meeting(mouse_time - grab, mouse_time + grab)) {
      const Label& label = lane.labels()[index];
      if (std::fabs(label.t1 - mouse_time) <= grab)
        drag.label = label.id, drag.start_edge = false;
      else if (std::fabs(label.t0 - mouse_time) <= grab)
        drag.label = label.id, drag.start_edge = true;
    }
  }
  if (!drag.active) return;
  const bool moved = std::fabs(mouse_time - drag.press_time) > 2.0 * seconds_per_pixel;
  if (ImGui::IsItemActive() && moved) {
    drag.time = snapped(state, mouse_time, 6.0 * seconds_per_pixel);
    ImDrawList& draw = *ImGui::GetWindowDrawList();
    const float x = x_of(drag.time);
    draw.AddLine(ImVec2(x, lane_min.y), ImVec2(x, lane_max.y), IM_COL32(255, 255, 255, 255), 2.0f);
    if (drag.label == 0) {
      state.labelling.mark_start = std::min(drag.press_time, drag.time);
      state.labelling.mark_end = std::max(drag.press_time, drag.time);
    }
  }
  if (ImGui::IsItemDeactivated()) {
    if (moved && drag.label != 0)
      for (const Label& label : lane.labels())
        if (label.id == drag.label) {
          state.labelling.move_request = {label.id, drag.start_edge ? drag.time : label.t0,
                                          drag.start_edge ? label.t1 : drag.time};
          break;
        }
    drag = {};
  }
}

// One lane: its labels as blocks over the plot's visible range, merged per pixel when
// dense; a click moves the cursor and selects the label under it.
void draw_lane(WorkbenchState& state, const std::string& id, const LaneIndex& lane, float left,
               float right, const std::vector<std::string>& shown) {
  const double t0 = state.plot.view_t0;
  const double t1 = state.plot.view_t1;
  const bool collapsed = state.labelling.collapsed.count(id) > 0;
  const bool own = id == state.labelling.active_lane();
  const float height = collapsed ? kCollapsedHeight : kLaneHeight;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  // Header: the lane's name, and a menu on right-click.
  ImGui::PushID(id.c_str());
  ImGui::InvisibleButton("header", ImVec2(std::max(1.0f, left - origin.x - 2.0f), height));
  remember_item(state, "lane-header:" + id);
  if (ImGui::BeginPopupContextItem("lane_menu")) {
    if (ImGui::MenuItem("Hide")) state.labelling.hidden.insert(id);
    if (ImGui::MenuItem(collapsed ? "Expand" : "Collapse")) {
      if (collapsed)
        state.labelling.collapsed.erase(id);
      else
        state.labelling.collapsed.insert(id);
    }
    if (ImGui::MenuItem("Move up")) move_lane(state, shown, id, -1);
    if (ImGui::MenuItem("Move down")) move_lane(state, shown, id, +1);
    if (ImGui::MenuItem("Show all lanes")) state.labelling.hidden.clear();
    ImGui::EndPopup();
  }
  if (!collapsed) {
    const std::string title = lane_title(id);
    const ImVec2 extent = ImGui::CalcTextSize(title.c_str());
    remember_box(state, "lane-name:" + id, ImVec2(origin.x + 2.0f, origin.y + 4.0f),
                 ImVec2(origin.x + 2.0f + extent.x, origin.y + 4.0f + extent.y));
    draw.PushClipRect(origin, ImVec2(left - 2.0f, origin.y + height), true);
    draw.AddText(ImVec2(origin.x + 2.0f, origin.y + 4.0f),
                 own ? IM_COL32(255, 200, 120, 255) : IM_COL32(190, 190, 190, 255), title.c_str());
    draw.PopClipRect();
  }
  ImGui::SetCursorScreenPos(ImVec2(left, origin.y));
  ImGui::InvisibleButton("blocks", ImVec2(std::max(1.0f, right - left), height));
  const ImVec2 lane_min(left, origin.y);
  const ImVec2 lane_max(right, origin.y + height);
  state.targets.time_axes["lane:" + id] = {to_rect(lane_min, lane_max), t0, t1};
  if (own) state.targets.time_axes["timeline"] = {to_rect(lane_min, lane_max), t0, t1};
  draw.AddRectFilled(lane_min, lane_max,
                     own ? IM_COL32(40, 38, 34, 255) : IM_COL32(30, 30, 36, 255));
  const int columns = std::max(1, static_cast<int>(right - left));
  const double seconds_per_pixel = (t1 - t0) / columns;
  for (const LaneSpan& span : lane_spans(lane, t0, t1, columns)) {
    const Label& label = lane.labels()[span.label];
    const float x0 = left + static_cast<float>(span.first);
    const float x1 = left + static_cast<float>(span.last);
    const bool selected = std::find(state.selection.labels.begin(), state.selection.labels.end(),
                                    label.id) != state.selection.labels.end();
    const uint32_t colour = class_colour(state, label.class_name, 200);
    draw.AddRectFilled(ImVec2(x0, lane_min.y + 2), ImVec2(x1, lane_max.y - 2), colour, 2.0f);
    if (selected)
      draw.AddRect(ImVec2(x0, lane_min.y + 1), ImVec2(x1, lane_max.y - 1),
                   IM_COL32(255, 255, 255, 255), 2.0f, 0, 2.0f);
    if (!collapsed && x1 - x0 > 16.0f &&
        x1 - x0 > ImGui::CalcTextSize(label.class_name.c_str()).x + 6.0f)
      draw.AddText(ImVec2(x0 + 3.0f, lane_min.y + 4.0f), IM_COL32(240, 240, 240, 255),
                   label.class_name.c_str());
  }
  auto x_of = [&](double t) { return left + static_cast<float>((t - t0) / seconds_per_pixel); };
  if (own && state.labelling.mark_start) {
    // The label being made: from the start mark to the end mark (or the cursor).
    const double end = state.labelling.mark_end.value_or(state.clock.time());
    const float a = std::clamp(x_of(*state.labelling.mark_start), left, right);
    const float b = std::clamp(x_of(end), left, right);
    draw.AddRectFilled(ImVec2(std::min(a, b), lane_min.y), ImVec2(std::max(a, b), lane_max.y),
                       IM_COL32(255, 200, 120, 70));
    draw.AddLine(ImVec2(a, lane_min.y), ImVec2(a, lane_max.y), IM_COL32(255, 200, 120, 255), 2.0f);
    if (state.labelling.mark_end)
      draw.AddLine(ImVec2(b, lane_min.y), ImVec2(b, lane_max.y), IM_COL32(255, 200, 120, 255),
                   2.0f);
  }
  const float cursor_x = x_of(state.clock.time());
  if (cursor_x >= left && cursor_x <= right)
    draw.AddLine(ImVec2(cursor_x, lane_min.y), ImVec2(cursor_x, lane_max.y),
                 IM_COL32(255, 140, 40, 255), 2.0f);
  const double mouse_time = t0 + (ImGui::GetIO().MousePos.x - left) * seconds_per_pixel;
  if (own) drag_in_own_lane(state, lane, mouse_time, seconds_per_pixel, x_of, lane_min, lane_max);
  if (ImGui::IsItemClicked()) {
    state.clock.seek(mouse_time);
    state.selection.labels.clear();
    const int64_t under = lane.at(mouse_time);
    if (under >= 0) state.selection.labels.push_back(lane.labels()[static_cast<size_t>(under)].id);
  }
  ImGui::PopID();
}

void draw_lanes(WorkbenchState& state, float width) {
  draw_legend(state);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  // Aligned under the plot's data area (its value axis takes the left strip, where the
  // lanes' names go).
  // Without the plot (another tab shown), the names' column is as wide as the longest name: 60
  // pixels cut "proximity" to "proximit".
  const auto lanes = shown_lanes(state);
  float names = 60.0f;
  for (const auto& [id, lane] : lanes)
    names = std::max(names, ImGui::CalcTextSize(lane_title(id).c_str()).x + 10.0f);
  const auto axis = state.targets.time_axes.find("signals");
  const bool aligned = axis != state.targets.time_axes.end();
  const float left = aligned ? std::max(axis->second.area.x0, origin.x + names) : origin.x + names;
  const float right = aligned ? axis->second.area.x1 : origin.x + width;
  std::vector<std::string> ids;
  for (const auto& [id, lane] : lanes) ids.push_back(id);
  for (const auto& [id, lane] : lanes) {
    ImGui::SetCursorScreenPos(ImVec2(origin.x, ImGui::GetCursorScreenPos().y));
    draw_lane(state, id, *lane, left, right, ids);
  }
}

}  // namespace

void draw_timeline_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("timeline_view", size, false);
  if (state.live.connected)
    draw_live_bar(state);
  else
    draw_transport(state);
  draw_lanes(state, ImGui::GetContentRegionAvail().x);
  ImGui::EndChild();
}

}  // namespace tactile

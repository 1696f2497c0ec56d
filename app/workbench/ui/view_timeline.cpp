// Timeline view: transport (play, speed, loop, time), a lane of the labels over the
// plot's time range (a click moves the cursor), and the table of labels.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "views.h"

namespace tactile {

namespace {

constexpr double kSpeeds[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr float kLaneHeight = 22.0f;

void draw_transport(WorkbenchState& state) {
  PlaybackClock& clock = state.clock;
  if (ImGui::Button(clock.playing() ? "Pause" : "Play", ImVec2(70, 0))) clock.toggle();
  remember_item(state, "button:play");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  char speed_text[16];
  std::snprintf(speed_text, sizeof(speed_text), "%gx", clock.speed());
  if (ImGui::BeginCombo("##speed", speed_text)) {
    for (double speed : kSpeeds) {
      std::snprintf(speed_text, sizeof(speed_text), "%gx", speed);
      if (ImGui::Selectable(speed_text, speed == clock.speed())) clock.set_speed(speed);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  bool looping = clock.looping();
  if (ImGui::Checkbox("loop", &looping)) clock.set_looping(looping);
  ImGui::SameLine();
  const std::string now = format_seconds(clock.time()) + " / " + format_seconds(clock.end());
  ImGui::SetNextItemWidth(-1);
  float time = static_cast<float>(clock.time());
  if (ImGui::SliderFloat("##time", &time, static_cast<float>(clock.start()),
                         static_cast<float>(clock.end()), now.c_str()))
    clock.seek(time);
}

// The labels as blocks over the plot's visible range; a click moves the cursor and
// selects the label under it.
void draw_label_lane(WorkbenchState& state, float width) {
  const double t0 = state.plot.view_t0;
  const double t1 = state.plot.view_t1;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  // Aligned under the plot's data area (its value axis takes the left strip).
  const auto axis = state.targets.time_axes.find("signals");
  const float left = axis != state.targets.time_axes.end() ? axis->second.area.x0 : origin.x;
  const float right = axis != state.targets.time_axes.end() ? axis->second.area.x1 : origin.x + width;
  ImGui::SetCursorScreenPos(ImVec2(left, origin.y));
  ImGui::InvisibleButton("label_lane", ImVec2(std::max(1.0f, right - left), kLaneHeight));
  const ImVec2 lane_min(left, origin.y);
  const ImVec2 lane_max(right, origin.y + kLaneHeight);
  state.targets.time_axes["timeline"] = {to_rect(lane_min, lane_max), t0, t1};
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  draw.AddRectFilled(lane_min, lane_max, IM_COL32(30, 30, 36, 255));
  const double seconds_per_pixel = (t1 - t0) / std::max(1.0f, right - left);
  const auto& labels = state.document->labels;
  for (const Label& label : labels) {
    if (!(label.t1 > t0 && label.t0 < t1)) continue;
    const float x0 = left + static_cast<float>((std::max(label.t0, t0) - t0) / seconds_per_pixel);
    const float x1 = left + static_cast<float>((std::min(label.t1, t1) - t0) / seconds_per_pixel);
    const bool selected = std::find(state.selection.labels.begin(), state.selection.labels.end(),
                                    label.id) != state.selection.labels.end();
    const uint32_t colour = (class_colour(label.class_name) & 0x00FFFFFFu) | (200u << 24);
    draw.AddRectFilled(ImVec2(x0, lane_min.y + 2), ImVec2(std::max(x1, x0 + 1), lane_max.y - 2),
                       colour, 2.0f);
    if (selected)
      draw.AddRect(ImVec2(x0, lane_min.y + 1), ImVec2(std::max(x1, x0 + 1), lane_max.y - 1),
                   IM_COL32(255, 255, 255, 255), 2.0f, 0, 2.0f);
    if (x1 - x0 > ImGui::CalcTextSize(label.class_name.c_str()).x + 6.0f)
      draw.AddText(ImVec2(x0 + 3.0f, lane_min.y + 4.0f), IM_COL32(240, 240, 240, 255),
                   label.class_name.c_str());
  }
  const float cursor_x = left + static_cast<float>((state.clock.time() - t0) / seconds_per_pixel);
  if (cursor_x >= left && cursor_x <= right)
    draw.AddLine(ImVec2(cursor_x, lane_min.y), ImVec2(cursor_x, lane_max.y),
                 IM_COL32(255, 140, 40, 255), 2.0f);
  if (ImGui::IsItemClicked()) {
    const double t = t0 + (ImGui::GetIO().MousePos.x - left) * seconds_per_pixel;
    state.clock.seek(t);
    state.selection.labels.clear();
    for (const Label& label : labels)
      if (t >= label.t0 && t < label.t1) state.selection.labels.push_back(label.id);
  }
}

void draw_label_table(WorkbenchState& state) {
  const Document& document = *state.document;
  const auto& labels = document.labels;
  if (document.labels_path.empty()) {
    ImGui::TextDisabled("No label database beside this recording.");
    return;
  }
  if (labels.empty()) {
    ImGui::TextDisabled("No labels for this recording in %s.", document.labels_path.c_str());
    return;
  }
  if (!ImGui::BeginTable("label_table", 6,
                         ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                             ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_Resizable))
    return;
  ImGui::TableSetupScrollFreeze(0, 1);
  for (const char* header : {"class", "region", "t0", "t1", "source", "annotator"})
    ImGui::TableSetupColumn(header);
  ImGui::TableHeadersRow();
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(labels.size()));
  while (clipper.Step())
    for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
      const Label& label = labels[static_cast<size_t>(row)];
      const bool selected = std::find(state.selection.labels.begin(), state.selection.labels.end(),
                                      label.id) != state.selection.labels.end();
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::PushID(row);
      if (ImGui::Selectable(label.class_name.c_str(), selected,
                            ImGuiSelectableFlags_SpanAllColumns)) {
        state.clock.seek(label.t0);
        state.selection.labels = {label.id};
      }
      ImGui::PopID();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(label.region.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", label.t0);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", label.t1);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(to_string(label.source));
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(label.annotator.c_str());
    }
  ImGui::EndTable();
}

}  // namespace

void draw_timeline_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("timeline_view", size, false);
  draw_transport(state);
  draw_label_lane(state, ImGui::GetContentRegionAvail().x);
  draw_label_table(state);
  ImGui::EndChild();
}

}  // namespace tactile

// Labels view: the open recording's labels as a table (class, times, lane, region), in the
// sidebar under the workspace, where it has the height for many rows. It follows the
// selection (a label selected in the lanes, by Tab or by U scrolls into view) and, while
// playing, the label under the cursor; a click on a row selects that label and moves the
// cursor to its start.
#include <algorithm>

#include "views.h"

namespace tactile {

namespace {

// The row to bring into view: the selected label when the selection changed, else (while
// playing) the label under the cursor when it changed; -1 for none.
int row_to_follow(WorkbenchState& state, const std::vector<Label>& labels) {
  LabelsViewState& view = state.labels_view;
  const int64_t selected = state.selection.labels.empty() ? -1 : state.selection.labels.front();
  int64_t wanted = -1;
  if (selected != view.followed_selection) {
    view.followed_selection = selected;
    wanted = selected;
  } else if (state.clock.playing()) {
    const double t = state.clock.time();
    int64_t under = -1;
    for (const Label& label : labels)
      if (label.t0 <= t && t < label.t1) {
        under = label.id;
        break;
      }
    if (under != view.followed_cursor) {
      view.followed_cursor = under;
      wanted = under;
    }
  }
  if (wanted < 0) return -1;
  const auto found = std::find_if(labels.begin(), labels.end(), [&](const Label& label) { return label.id == wanted; });
  return found == labels.end() ? -1 : static_cast<int>(found - labels.begin());
}

}  // namespace

void draw_labels_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("labels_view", size, false);
  const Document& document = *state.document;
  const std::vector<Label>& labels = document.labels;
  if (document.labels_path.empty() && state.live.connected) {
    // Before the recording exists, say where its labels will go.
    const std::string folder = state.live.record_folder.empty() ? state.workspace : state.live.record_folder;
    ImGui::TextWrapped("Live, not recording: Ctrl+R records into %s; labels then go to %s/labels.db.",
                       folder.c_str(), folder.c_str());
  } else if (document.labels_path.empty()) {
    ImGui::TextWrapped("No label database beside this recording.");
  } else if (labels.empty()) {
    ImGui::TextWrapped("No labels for this recording in %s yet: [ and ] mark, a digit chooses the class, Enter commits.",
                       document.labels_path.c_str());
  } else if (ImGui::BeginTable("label_table", 5,
                               ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX |
                                   ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_Resizable)) {
    ImGui::TableSetupScrollFreeze(1, 1);
    ImGui::TableSetupColumn("class", ImGuiTableColumnFlags_WidthFixed, 110.0f);
    ImGui::TableSetupColumn("t0", ImGuiTableColumnFlags_WidthFixed, 56.0f);
    ImGui::TableSetupColumn("t1", ImGuiTableColumnFlags_WidthFixed, 56.0f);
    ImGui::TableSetupColumn("lane", ImGuiTableColumnFlags_WidthFixed, 130.0f);
    ImGui::TableSetupColumn("region", ImGuiTableColumnFlags_WidthFixed, 90.0f);
    ImGui::TableHeadersRow();
    const float row_height = ImGui::GetTextLineHeightWithSpacing();
    if (const int row = row_to_follow(state, labels); row >= 0) {
      const float top = ImGui::GetScrollY(), shown = ImGui::GetWindowHeight() - 2.0f * row_height;
      const float y = static_cast<float>(row) * row_height;
      if (y < top || y > top + shown) ImGui::SetScrollY(std::max(0.0f, y - 0.5f * shown));
    }
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(labels.size()), row_height);
    while (clipper.Step())
      for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
        const Label& label = labels[static_cast<size_t>(row)];
        const bool selected =
            std::find(state.selection.labels.begin(), state.selection.labels.end(), label.id) !=
            state.selection.labels.end();
        const bool under_cursor = label.id == state.labels_view.followed_cursor && state.clock.playing();
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::PushID(row);
        if (ImGui::Selectable(label.class_name.c_str(), selected || under_cursor,
                              ImGuiSelectableFlags_SpanAllColumns)) {
          state.clock.seek(label.t0);
          state.selection.labels = {label.id};
        }
        remember_item(state, "label-row:" + std::to_string(label.id));
        ImGui::PopID();
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", label.t0);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", label.t1);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(lane_of(label).title().c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(label.region.c_str());
      }
    ImGui::EndTable();
  }
  ImGui::EndChild();
}

}  // namespace tactile

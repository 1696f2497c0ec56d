// Labels view: the open recording's labels as a table (class, times, lane, a prediction's
// margin, region), in the sidebar under the workspace, where it has the height for many rows.
// A click on a header sorts by that column (`margin`: the least sure prediction first, labels
// without one last; again: reversed; a third time: the recording's order). It follows the
// selection (a label selected in the lanes, by Tab or by U scrolls into view) and, while
// playing, the label under the cursor; a click on a row selects that label and moves the
// cursor to its start.
#include <algorithm>
#include <limits>

#include "tactile/labels/predict.h"
#include "views.h"

namespace tactile {

namespace {

// The margin second: a narrow sidebar shows it without scrolling sideways.
constexpr const char* kLabelColumns[] = {"class", "margin", "t0", "t1", "lane", "region"};
constexpr int kLabelColumnCount = static_cast<int>(std::size(kLabelColumns));

// A prediction's margin (labels of source model, their note); other labels have none and sort
// after every prediction.
double table_margin(const Label& label) {
  return label.source == LabelSource::kModel ? prediction_margin(label)
                                             : std::numeric_limits<double>::infinity();
}

// The rows in the order the header asks for: the recording's order until a header is clicked,
// then by that column, stable. Kept in the state (label_table) for scripts.
std::vector<size_t> sorted_rows(WorkbenchState& state, const std::vector<Label>& labels) {
  std::vector<size_t> rows(labels.size());
  for (size_t k = 0; k < rows.size(); ++k) rows[k] = k;
  WorkbenchState::LabelTableOrder& order = state.label_table;
  order.column.clear();
  order.ascending = true;
  const ImGuiTableSortSpecs* specs = ImGui::TableGetSortSpecs();
  if (specs && specs->SpecsCount > 0) {
    const ImGuiTableColumnSortSpecs& spec = specs->Specs[0];
    order.column = kLabelColumns[spec.ColumnIndex];
    order.ascending = spec.SortDirection != ImGuiSortDirection_Descending;
    const auto less = [&](const Label& a, const Label& b) {
      switch (spec.ColumnIndex) {
        case 0:
          return a.class_name < b.class_name;
        case 1:
          return table_margin(a) < table_margin(b);
        case 2:
          return a.t0 < b.t0;
        case 3:
          return a.t1 < b.t1;
        case 4:
          return lane_of(a).title() < lane_of(b).title();
        default:
          return a.region < b.region;
      }
    };
    std::stable_sort(rows.begin(), rows.end(), [&](size_t a, size_t b) {
      return order.ascending ? less(labels[a], labels[b]) : less(labels[b], labels[a]);
    });
  }
  order.ids.clear();
  for (const size_t row : rows) order.ids.push_back(labels[row].id);
  return rows;
}

// The row to bring into view: the selected label when the selection changed, else (while
// playing) the label under the cursor when it changed; -1 for none.
int row_to_follow(WorkbenchState& state, const std::vector<Label>& labels,
                  const std::vector<size_t>& rows) {
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
  for (size_t k = 0; k < rows.size(); ++k)
    if (labels[rows[k]].id == wanted) return static_cast<int>(k);
  return -1;
}

}  // namespace

void draw_labels_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("labels_view", size, false);
  const Document& document = *state.document;
  const std::vector<Label>& labels = document.labels;
  if (document.labels_path.empty() && state.live.connected) {
    // Before the recording exists, say where its labels will go.
    const std::string folder =
        state.live.record_folder.empty() ? state.workspace : state.live.record_folder;
    ImGui::TextWrapped(
        "Live, not recording: Ctrl+R records into %s; labels then go to %s/labels.db.",
        folder.c_str(), folder.c_str());
  } else if (document.labels_path.empty()) {
    ImGui::TextWrapped("No label database beside this recording.");
  } else if (labels.empty()) {
    ImGui::TextWrapped(
        "No labels for this recording in %s yet: [ and ] mark, a digit chooses the class, Enter "
        "commits.",
        document.labels_path.c_str());
  } else if (ImGui::BeginTable("label_table", kLabelColumnCount,
                               ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                   ImGuiTableFlags_ScrollX | ImGuiTableFlags_BordersInnerV |
                                   ImGuiTableFlags_Resizable | ImGuiTableFlags_Sortable |
                                   ImGuiTableFlags_SortTristate)) {
    ImGui::TableSetupScrollFreeze(1, 1);
    const float widths[] = {100.0f, 48.0f, 56.0f, 56.0f, 130.0f, 90.0f};
    for (int column = 0; column < kLabelColumnCount; ++column)
      ImGui::TableSetupColumn(kLabelColumns[column], ImGuiTableColumnFlags_WidthFixed,
                              widths[column]);
    // The header row by hand, so that a script can click a header (`click item header:margin`).
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    for (int column = 0; column < kLabelColumnCount; ++column) {
      ImGui::TableSetColumnIndex(column);
      ImGui::TableHeader(kLabelColumns[column]);
      remember_item(state, std::string("header:") + kLabelColumns[column]);
    }
    const std::vector<size_t> rows = sorted_rows(state, labels);
    const float row_height = ImGui::GetTextLineHeightWithSpacing();
    if (const int row = row_to_follow(state, labels, rows); row >= 0) {
      const float top = ImGui::GetScrollY(), shown = ImGui::GetWindowHeight() - 2.0f * row_height;
      const float y = static_cast<float>(row) * row_height;
      if (y < top || y > top + shown) ImGui::SetScrollY(std::max(0.0f, y - 0.5f * shown));
    }
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(labels.size()), row_height);
    while (clipper.Step())
      for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
        const Label& label = labels[rows[static_cast<size_t>(row)]];
        const bool selected =
            std::find(state.selection.labels.begin(), state.selection.labels.end(), label.id) !=
            state.selection.labels.end();
        const bool under_cursor =
            label.id == state.labels_view.followed_cursor && state.clock.playing();
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
        if (label.source == LabelSource::kModel) ImGui::Text("%.2f", prediction_margin(label));
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

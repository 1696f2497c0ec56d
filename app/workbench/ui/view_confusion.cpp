// Confusion view: counts and row percentages on a colour scale, class names on both axes,
// hover for the figures; a click on a cell lists its segments (recording, time, region,
// margin and the predicted class's probability: ml::confidence_of), the smallest margin
// first; Enter or a click on one lands on it. N / Shift+N walk the misclassified segments.
#include <algorithm>
#include <cstdio>

#include "confusion.h"
#include "results.h"
#include "tactile/widgets/colormap.h"
#include "views.h"

namespace tactile {

namespace {

std::string class_name(const ml::EvaluationResult& result, int index) {
  return index >= 0 && index < static_cast<int>(result.classes.size())
             ? result.classes[static_cast<size_t>(index)]
             : std::string("unknown");
}

// Dark text on light cells, light text on dark ones.
ImU32 text_on(Colour colour) {
  const float luminance = 0.299f * colour.r + 0.587f * colour.g + 0.114f * colour.b;
  return luminance > 140.0f ? IM_COL32(10, 10, 10, 255) : IM_COL32(240, 240, 240, 255);
}

void draw_matrix(WorkbenchState& state, const ml::EvaluationResult& result, ImVec2 size) {
  const int classes = static_cast<int>(result.classes.size());
  const bool any_unknown =
      result.confusion.cols() > classes && result.confusion.col(classes).sum() > 0;
  const int columns = classes + (any_unknown ? 1 : 0);
  float name_width = 0.0f;
  for (const std::string& name : result.classes)
    name_width = std::max(name_width, ImGui::CalcTextSize(name.c_str()).x);
  name_width += 26.0f;  // a swatch of the class's colour, its name, a gap
  const float header = ImGui::GetTextLineHeight() * 2.4f;
  const float legend = 110.0f;
  const float cell = std::clamp(std::min((size.x - name_width - legend) / std::max(1, columns),
                                         (size.y - header) / std::max(1, classes)),
                                18.0f, 110.0f);
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 grid(origin.x + name_width, origin.y + header);
  // Column names, staggered in two lines when they would collide.
  for (int column = 0; column < columns; ++column) {
    const std::string name =
        column < classes ? result.classes[static_cast<size_t>(column)] : "unknown";
    const ImVec2 text = ImGui::CalcTextSize(name.c_str());
    const float line =
        text.x > cell - 2 && column % 2 == 1 ? 0.0f : ImGui::GetTextLineHeight() * 1.1f;
    draw.AddText(ImVec2(grid.x + column * cell + (cell - text.x) / 2, origin.y + line),
                 IM_COL32(220, 220, 220, 255), name.c_str());
  }
  for (int row = 0; row < classes; ++row) {
    const std::string& name = result.classes[static_cast<size_t>(row)];
    const ImVec2 label(origin.x, grid.y + row * cell + (cell - ImGui::GetTextLineHeight()) / 2);
    const ImVec2 swatch(label.x, label.y + 3);
    draw.AddRectFilled(swatch, ImVec2(swatch.x + 10, swatch.y + 10), class_colour(state, name));
    remember_legend(state, "confusion", name, swatch, 10.0f);
    draw.AddText(ImVec2(label.x + 14, label.y), IM_COL32(220, 220, 220, 255), name.c_str());
    const double total = std::max(1, result.confusion.row(row).sum());
    for (int column = 0; column < columns; ++column) {
      const int count = result.confusion(row, column);
      const float share = static_cast<float>(count / total);
      const ImVec2 low(grid.x + column * cell, grid.y + row * cell);
      const ImVec2 high(low.x + cell - 1, low.y + cell - 1);
      const Colour colour = count == 0 ? Colour{38, 38, 44, 255} : viridis(0.15f + 0.85f * share);
      draw.AddRectFilled(low, high, pack_abgr(colour));
      const int predicted = column < classes ? column : ml::kUnknownClass;
      const bool chosen = state.analysis.confusion.cell_true == row &&
                          state.analysis.confusion.cell_predicted == predicted;
      if (row != column && count > 0)  // wrong cells are framed: they are the ones to click
        draw.AddRect(low, high, IM_COL32(230, 90, 70, 200), 0.0f, 0, 1.5f);
      if (chosen) draw.AddRect(low, high, IM_COL32(255, 255, 255, 255), 0.0f, 0, 3.0f);
      // The count, and below it (when there is room) the share of the row; each centred.
      char count_text[16], share_text[16];
      std::snprintf(count_text, sizeof count_text, "%d", count);
      std::snprintf(share_text, sizeof share_text, "%.0f%%", 100.0 * share);
      const ImU32 ink = count == 0 ? IM_COL32(110, 110, 110, 255) : text_on(colour);
      const float line = ImGui::GetTextLineHeight();
      const bool two_lines = cell >= 2.4f * line;
      const float top = low.y + (cell - (two_lines ? 2 * line : line)) / 2;
      draw.AddText(ImVec2(low.x + (cell - ImGui::CalcTextSize(count_text).x) / 2, top), ink,
                   count_text);
      if (two_lines)
        draw.AddText(ImVec2(low.x + (cell - ImGui::CalcTextSize(share_text).x) / 2, top + line),
                     ink, share_text);
      ImGui::SetCursorScreenPos(low);
      ImGui::PushID(row * 1000 + column);
      if (ImGui::InvisibleButton("cell", ImVec2(cell - 1, cell - 1)))
        select_cell(state, row, predicted);
      ImGui::PopID();
      remember_item(state, "cell:" + name + "/" + class_name(result, predicted));
      if (ImGui::IsItemHovered()) {
        char tip[512];
        std::snprintf(tip, sizeof tip,
                      "true %s, predicted %s\n%d segments, %.1f %% of the row\nrecall %.1f %%",
                      name.c_str(), class_name(result, predicted).c_str(), count, 100.0 * share,
                      100.0 * result.per_class[static_cast<size_t>(row)].recall);
        view_tooltip(state, tip);
      }
    }
  }
  // The colour scale: share of the true class's row.
  const ImVec2 bar(grid.x + columns * cell + 16, grid.y);
  const float bar_height = std::max(40.0f, classes * cell - 1);
  for (int step = 0; step < 32; ++step) {
    const float y = bar.y + bar_height * (1.0f - (step + 1) / 32.0f);
    draw.AddRectFilled(ImVec2(bar.x, y), ImVec2(bar.x + 12, y + bar_height / 32.0f + 1),
                       pack_abgr(viridis(0.15f + 0.85f * (step + 0.5f) / 32.0f)));
  }
  draw.AddText(ImVec2(bar.x + 16, bar.y - 2), IM_COL32(200, 200, 200, 255), "100% of row");
  draw.AddText(ImVec2(bar.x + 16, bar.y + bar_height - ImGui::GetTextLineHeight()),
               IM_COL32(200, 200, 200, 255), "0%");
  ImGui::SetCursorScreenPos(ImVec2(origin.x, grid.y + classes * cell + 4));
  ImGui::Dummy(ImVec2(name_width + columns * cell, 1));
}

void draw_cell_list(WorkbenchState& state, const ml::EvaluationResult& result, ImVec2 size) {
  AnalysisState& analysis = state.analysis;
  if (analysis.confusion.cell_true < 0) {
    ImGui::TextDisabled(
        "Click a cell (framed red: wrong) to list its segments; N walks the mistakes.");
    return;
  }
  ImGui::Text("true %s, predicted %s: %zu segments, least sure first",
              class_name(result, analysis.confusion.cell_true).c_str(),
              class_name(result, analysis.confusion.cell_predicted).c_str(),
              analysis.confusion.cell_rows.size());
  ImGui::BeginChild("cell_list", size, true);
  for (size_t k = 0; k < analysis.confusion.cell_rows.size(); ++k) {
    const ml::RowPrediction& row = result.rows[analysis.confusion.cell_rows[k]];
    char text[256];
    std::snprintf(text, sizeof text, "%s  %s-%s  %s  margin %.2f  probability %.2f##%zu",
                  row.recording.c_str(), format_seconds(row.t0).c_str(),
                  format_seconds(row.t1).c_str(), row.region.c_str(), row.margin, row.score, k);
    const bool selected = static_cast<int>(k) == analysis.confusion.cell_selected;
    if (ImGui::Selectable(text, selected)) {
      analysis.confusion.cell_selected = static_cast<int>(k);
      land_on(state, row);
    }
    if (selected && ImGui::IsWindowAppearing()) ImGui::SetScrollHereY();
    remember_item(state, "segment:" + std::to_string(k));
  }
  ImGui::EndChild();
}

}  // namespace

void draw_confusion_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("confusion_view", size, false);
  const ml::EvaluationResult* result = current_evaluation(state);
  if (!result) {
    ImGui::TextDisabled("No evaluation: train in the Model tab, or open one with --evaluation.");
    ImGui::EndChild();
    return;
  }
  ImGui::Text("%s   %s   accuracy %.1f %%   mean recall %.1f %%", result->classifier.c_str(),
              result->protocol.c_str(), 100.0 * result->accuracy, 100.0 * ml::mean_recall(*result));
  const ImVec2 available = ImGui::GetContentRegionAvail();
  const float list_height = std::min(available.y * 0.38f, 220.0f);
  draw_matrix(state, *result, ImVec2(available.x, available.y - list_height - 30));
  draw_cell_list(state, *result, ImVec2(0, std::max(40.0f, ImGui::GetContentRegionAvail().y - 4)));
  ImGui::EndChild();
}

}  // namespace tactile

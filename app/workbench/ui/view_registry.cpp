// The list of views and what the views share.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <limits>

#include "files.h"
#include "tactile/signal/taxel_values.h"
#include "views.h"

namespace tactile {

namespace {

constexpr ViewSpec kViews[] = {
    {"workspace", "Workspace", false, draw_workspace_view},
    {"info", "Recording", true, draw_info_view},
    {"skin", "Skin", true, draw_skin_panel_view, "somatosensory"},
    {"signals", "Signals", true, draw_signals_view},
    {"timeline", "Timeline", true, draw_timeline_view},
    {"labels", "Labels", true, draw_labels_view},
    {"quality", "Quality", true, draw_quality_view},
    {"model", "Model", true, draw_model_view, "training"},
    {"confusion", "Confusion", false, draw_confusion_view},
    {"scatter", "Scatter", false, draw_scatter_view, "scatter"},
    {"som", "SOM", false, draw_som_view, "som"},
    {"somatosensory", "Somatosensory map", true, draw_somatosensory_view, "somatosensory"},
    {"video", "Video", true, draw_video_view, "video sync"},
    {"clip", "Clip (skin, video, signals, lanes)", true, draw_clip_view},
};

}  // namespace

std::span<const ViewSpec> all_views() { return kViews; }

const ViewSpec* find_view(const std::string& name) {
  for (const ViewSpec& view : kViews)
    if (name == view.name) return &view;
  return nullptr;
}

std::string view_names() {
  std::string names;
  for (const ViewSpec& view : kViews) names += (names.empty() ? "" : ", ") + std::string(view.name);
  return names;
}

std::string job_shown_in(const std::string& kind) {
  for (const ViewSpec& view : kViews) {
    const std::string kinds = std::string(",") + view.jobs + ",";
    if (kinds.find("," + kind + ",") != std::string::npos) return view.name;
  }
  for (const char* dialog_kind : kDialogJobs)
    if (kind == dialog_kind) return "dialog";
  return {};
}

uint32_t class_colour(WorkbenchState& state, const std::string& class_name, int alpha) {
  // Live decisions between touches: grey, and faint, so they do not read as a class.
  if (class_name == kNoTouchClass) return IM_COL32(128, 128, 128, 25);
  // The open recording's vocabulary comes first, in its order.
  ClassColours& colours = state.class_colours;
  if (state.document) {
    const std::vector<std::string>& vocabulary = state.document->classes;
    const std::vector<std::string>& order = colours.order();
    if (order.size() < vocabulary.size() ||
        !std::equal(vocabulary.begin(), vocabulary.end(), order.begin()))
      colours.set_vocabulary(vocabulary);
  }
  return colours.colour(class_name, alpha);
}

void remember_legend(WorkbenchState& state, const std::string& view, const std::string& class_name,
                     ImVec2 at, float size) {
  state.targets.items["legend:" + view + ":" + class_name] =
      to_rect(at, ImVec2(at.x + size, at.y + size));
}

std::string format_seconds(double seconds) {
  char text[32];
  const int minutes = static_cast<int>(seconds / 60.0);
  std::snprintf(text, sizeof(text), "%d:%06.3f", minutes, seconds - minutes * 60.0);
  return text;
}

ScreenRect to_rect(ImVec2 min, ImVec2 max) { return {min.x, min.y, max.x, max.y}; }

void remember_item(WorkbenchState& state, const std::string& name) {
  // The part of the item that is visible: a table row spanning its columns is wider than a
  // narrow sidebar, and the middle of the whole row lay beyond the sidebar's edge, where a
  // click reached the next panel (`click item label-row:ID` did nothing).
  const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
  const ImDrawList& draw = *ImGui::GetWindowDrawList();
  const ImVec2 clip_min = draw.GetClipRectMin(), clip_max = draw.GetClipRectMax();
  const ImVec2 shown_min(std::max(min.x, clip_min.x), std::max(min.y, clip_min.y));
  const ImVec2 shown_max(std::min(max.x, clip_max.x), std::min(max.y, clip_max.y));
  const bool visible = shown_min.x < shown_max.x && shown_min.y < shown_max.y;
  state.targets.items[name] = visible ? to_rect(shown_min, shown_max) : to_rect(min, max);
  state.targets.boxes[name] = to_rect(min, max);
}

void remember_box(WorkbenchState& state, const std::string& name, ImVec2 min, ImVec2 max) {
  state.targets.boxes[name] = to_rect(min, max);
}

bool tooltips_allowed() {
  // Not while the mouse rests where it last clicked: after a click (Train all, a cell) the
  // tooltip of whatever lies under the pointer stood over the view the click opened.
  const ImGuiIO& io = ImGui::GetIO();
  return io.MouseClickedTime[0] <= 0.0 || io.MousePos.x != io.MouseClickedPos[0].x ||
         io.MousePos.y != io.MouseClickedPos[0].y;
}

void view_tooltip(WorkbenchState& state, const std::string& text) {
  if (!tooltips_allowed()) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36.0f);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  state.targets.items["tooltip"] = to_rect(at, ImVec2(at.x + size.x, at.y + size.y));
  ImGui::EndTooltip();
}

void same_line_if_fits(float width) {
  const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
  if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width <= right)
    ImGui::SameLine();
}

void remember_item(WorkbenchState& state, const std::string& name, const std::string& tip) {
  remember_item(state, name);
  state.targets.tips[name] = tip;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) view_tooltip(state, tip);
}

void tooltip(const char* text) {
  if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) || !tooltips_allowed()) return;
  // Wrapped at a reading width: a long tip on one line ran past the window's edge.
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36.0f);
  ImGui::TextUnformatted(text);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

const RestScale& current_rest_scale(WorkbenchState& state, const std::vector<int>& columns) {
  if (state.rest_scale_modality != state.modality) {
    state.rest_scale = rest_scale(state.document->samples(), columns);
    state.rest_scale_modality = state.modality;
  }
  return state.rest_scale;
}

std::vector<float> skin_values_now(WorkbenchState& state, double& value_min, double& value_max) {
  const Document& document = *state.document;
  const SampleSource& source = document.samples();
  const SkinLayout& layout = document.layout;
  const std::vector<int> columns = taxel_columns(layout, source.info().channels, state.modality);
  const std::vector<float> values =
      taxel_values(source.values_at_time(state.clock.time()), columns);
  value_min = 0.0;
  value_max = 1.0;
  if (state.show_raw_values) {
    // The layout's display range belongs to its display modality; others scale to their data.
    value_min = layout.display_min;
    value_max = layout.display_max;
    if (layout.modalities.empty() ||
        layout.modalities[static_cast<size_t>(state.modality)] != layout.display_modality) {
      MinMax extent;
      for (int column : columns)
        if (column >= 0) extent.merge(source.channel_extent(column));
      value_min = extent.empty() ? 0.0 : extent.min;
      value_max = extent.empty() ? 1.0 : extent.max;
    }
    return values;
  }
  const RestScale& scale = current_rest_scale(state, columns);
  value_max = scale.max_change;
  return change_from_rest(values, scale);
}

void plot_moving_channels(WorkbenchState& state) {
  constexpr int kMostChannels = 8;
  const SampleSource& source = state.document->samples();
  state.plotted.assign(static_cast<size_t>(source.channel_count()), 0);
  std::vector<std::pair<float, int>> spread;
  for (int column : taxel_columns(state.document->layout, source.info().channels, state.modality)) {
    if (column < 0) continue;
    const MinMax extent = source.channel_extent(column);
    spread.emplace_back(extent.empty() ? 0.0f : extent.max - extent.min, column);
  }
  if (spread.empty())
    for (int column = 0; column < std::min(kMostChannels, source.channel_count()); ++column)
      spread.emplace_back(0.0f, column);
  std::stable_sort(spread.begin(), spread.end(),
                   [](auto& a, auto& b) { return a.first > b.first; });
  for (size_t k = 0; k < spread.size() && k < static_cast<size_t>(kMostChannels); ++k)
    state.plotted[static_cast<size_t>(spread[k].second)] = 1;
}

}  // namespace tactile

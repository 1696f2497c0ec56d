#pragma once
// The workbench's views, one file each (view_*.cpp). Each draws into the space it is
// given at the current ImGui cursor, reads samples only through the document's
// SampleSource, and changes only the WorkbenchState. The window (workbench.cpp)
// arranges them; `--view NAME` draws one alone, e.g. for a PNG.

#include <imgui.h>

#include <span>
#include <string>

#include "workbench_state.h"

namespace tactile {

struct ViewSpec {
  const char* name;   // for scripts and --view: "skin", "signals", ...
  const char* title;  // shown in tabs and menus
  bool needs_recording;
  void (*draw)(WorkbenchState& state, ImVec2 size);
  // The kinds of job (jobs.h) whose progress and Cancel the view shows, comma-separated; the
  // status bar shows the jobs no view or dialog shows.
  const char* jobs = "";
};

void draw_workspace_view(WorkbenchState& state, ImVec2 size);
void draw_info_view(WorkbenchState& state, ImVec2 size);
void draw_skin_panel_view(WorkbenchState& state, ImVec2 size);
void draw_signals_view(WorkbenchState& state, ImVec2 size);
void draw_timeline_view(WorkbenchState& state, ImVec2 size);
void draw_labels_view(WorkbenchState& state, ImVec2 size);
void draw_quality_view(WorkbenchState& state, ImVec2 size);
void draw_model_view(WorkbenchState& state, ImVec2 size);
void draw_confusion_view(WorkbenchState& state, ImVec2 size);
void draw_scatter_view(WorkbenchState& state, ImVec2 size);
void draw_som_view(WorkbenchState& state, ImVec2 size);
void draw_somatosensory_view(WorkbenchState& state, ImVec2 size);
void draw_video_view(WorkbenchState& state, ImVec2 size);
void draw_clip_view(WorkbenchState& state, ImVec2 size);

// Every view, in menu order.
std::span<const ViewSpec> all_views();
const ViewSpec* find_view(const std::string& name);
// Comma-separated names, for error messages.
std::string view_names();
// The view that shows jobs of this kind (ViewSpec::jobs), "dialog" for a dialog's own
// (kDialogJobs, files.h); "" when the status bar shows them.
std::string job_shown_in(const std::string& kind);

//---- Shared by the views
// The label lanes as the timeline shows them, in the user's order, hidden ones left out
// (the operator's own lane always there); the top one with labels is shaded in the plot.
std::vector<std::pair<std::string, const LaneIndex*>> shown_lanes(const WorkbenchState& state);
const LaneIndex* top_lane(const WorkbenchState& state);
// The colour of a class: its place in the document's vocabulary, else a hash.
// The class's colour in every view (state.class_colours): the open recording's vocabulary
// (else the table's skin's) in its order; "no touch" faint grey, "unknown" neutral grey.
uint32_t class_colour(WorkbenchState& state, const std::string& class_name, int alpha = 255);
// A legend's swatch of a class, as item "legend:VIEW:CLASS" (the state JSON's items), so a
// test can read each view's colour of one class off the screenshot.
void remember_legend(WorkbenchState& state, const std::string& view, const std::string& class_name,
                     ImVec2 at, float size);
std::string format_seconds(double seconds);
// Remembers the last ImGui item's rectangle under `name` for scripts.
void remember_item(WorkbenchState& state, const std::string& name);
// The same, for a control, with the tooltip it shows while hovered (kept in the state JSON's
// `tips`, so a test can hold every control to having one).
void remember_item(WorkbenchState& state, const std::string& name, const std::string& tip);
// A tooltip for the last item while it is hovered.
void tooltip(const char* text);
// An item's whole box (the state's `boxes`), for what is drawn without an item of its own.
void remember_box(WorkbenchState& state, const std::string& name, ImVec2 min, ImVec2 max);
// False while the mouse rests where it last clicked: no tooltip then.
bool tooltips_allowed();
// A tooltip of `text` now (when tooltips_allowed), wrapped at a reading width; its box is the
// item `tooltip` of this frame.
void view_tooltip(WorkbenchState& state, const std::string& text);
// ImGui::SameLine when an item `width` wide still fits on the line, else the next line.
void same_line_if_fits(float width);
ScreenRect to_rect(ImVec2 min, ImVec2 max);
// The rest scale of the current modality (`columns`: its taxel columns), computed once
// per recording and modality.
const RestScale& current_rest_scale(WorkbenchState& state, const std::vector<int>& columns);
// Plots the (at most 8) channels of the current modality that move the most (the first
// channels when the modality has none).
void plot_moving_channels(WorkbenchState& state);
// The skin's values of the current modality at the time cursor, scaled for display:
// fills value_min/value_max.
std::vector<float> skin_values_now(WorkbenchState& state, double& value_min, double& value_max);

}  // namespace tactile

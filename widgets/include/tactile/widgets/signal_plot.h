#pragma once
// SignalPlot: several channels over time, overlaid or in stacked lanes, drawn with
// ImGui draw lists. Each frame asks each channel's SampleSource for one min/max per
// pixel column (4 vertices a column), so a frame costs the same for a minute or a day
// of data; zoomed in to a sample or less per pixel it draws the samples as a line.
//
// Mouse: wheel zooms about the cursor, drag pans, a click sets the time cursor
// (returned to the caller), a double click fits all data.

#include <imgui.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "tactile/signal/sample_source.h"

namespace tactile {

struct PlotChannel {
  std::string name;
  const SampleSource* source = nullptr;  // not owned; null draws nothing
  int channel = 0;                       // channel of the source
  uint32_t colour = 0;                   // IM_COL32; 0 picks plot_colour(index)
};

// A shaded time span [t0, t1), e.g. a label segment, with its class name.
struct PlotSpan {
  double t0 = 0.0;
  double t1 = 0.0;
  uint32_t colour = 0;  // IM_COL32, usually translucent
  std::string text;
};

struct SignalPlotState {
  double view_t0 = 0.0;  // visible time range, seconds
  double view_t1 = 1.0;
  bool fitted = false;   // false: the next frame fits the view to all data
  bool stacked = false;  // one lane per channel instead of all overlaid
};

struct SignalPlotResult {
  std::optional<double> clicked_time;  // set on the frame a click (not a drag) ends
  bool view_changed = false;           // zoomed, panned or fitted this frame
  int vertices = 0;                    // ImGui vertices the plot added this frame
  ImVec2 area_min, area_max;           // the data area on screen
  double value_min = 0.0;              // value range of the data area (overlaid mode)
  double value_max = 1.0;
};

// Draws the plot at the current cursor position of the current window.
SignalPlotResult draw_signal_plot(const char* id, std::span<const PlotChannel> channels,
                                  std::span<const PlotSpan> spans, SignalPlotState& state,
                                  double cursor_time, ImVec2 size);

// Distinct colours for channels (Tableau 10), IM_COL32, cycling.
uint32_t plot_colour(int index);

// Tick step of 1, 2 or 5 times a power of ten giving about `target_ticks` ticks over `range`.
double nice_tick_step(double range, int target_ticks);

}  // namespace tactile

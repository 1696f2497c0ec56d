#include "tactile/widgets/signal_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace tactile {

namespace {

constexpr float kValueAxisWidth = 56.0f;   // room for value tick labels left of the data
constexpr float kTimeTickSpacing = 90.0f;  // pixels between time ticks, about
constexpr float kValueTickSpacing = 40.0f;
constexpr float kDragThreshold = 3.0f;     // pixels a press may move and still be a click
constexpr double kZoomPerWheelStep = 0.8;  // view span factor per wheel notch
constexpr int kLegendRows = 16;

const ImU32 kBackground = IM_COL32(24, 24, 28, 255);
const ImU32 kGrid = IM_COL32(70, 70, 78, 255);
const ImU32 kAxisText = IM_COL32(200, 200, 205, 255);
const ImU32 kCursor = IM_COL32(255, 140, 40, 255);

// One channel's samples as seen through the pixel columns of this frame.
struct ChannelView {
  bool raw = false;             // zoomed in: individual samples, drawn as a line
  std::vector<MinMax> columns;  // decimated: one min/max per pixel column
  std::vector<double> times;    // raw: sample times
  std::vector<float> values;    // raw: sample values (NaN: missing)
  MinMax extent;                // visible value range
};

bool has_data(const PlotChannel& channel) {
  return channel.source && channel.channel >= 0 &&
         channel.channel < channel.source->channel_count() && channel.source->rate_hz() > 0;
}

ChannelView view_channel(const PlotChannel& channel, double t0, double t1, int columns) {
  ChannelView view;
  if (!has_data(channel) || columns <= 0) return view;
  const SampleSource& source = *channel.source;
  const double samples_per_column = (t1 - t0) / columns * source.rate_hz();
  if (samples_per_column <= 1.0) {
    // No more samples than pixels: draw the samples themselves, one beyond each edge
    // so the line runs out of the view rather than stopping short.
    const int64_t count = source.sample_count();
    const int64_t first = std::max<int64_t>(source.first_index_at_or_after(t0) - 1, 0);
    const int64_t last = std::min(source.first_index_at_or_after(t1) + 1, count);
    view.raw = true;
    if (first >= last) return view;
    const int channels[1] = {channel.channel};
    const SampleMatrix samples = source.read(channels, first, last - first);
    for (int64_t index = first; index < last; ++index) {
      const float value = samples(index - first, 0);
      view.times.push_back(source.time_of(index));
      view.values.push_back(value);
      view.extent.add(value);
    }
    return view;
  }
  view.columns = source.minmax_over_time(channel.channel, t0, t1, columns);
  for (const MinMax& column : view.columns) view.extent.merge(column);
  return view;
}

// Value range with a little headroom, never of zero width.
void padded_range(const MinMax& extent, double& low, double& high) {
  if (extent.empty()) {
    low = 0.0;
    high = 1.0;
    return;
  }
  low = extent.min;
  high = extent.max;
  const double pad = high > low ? 0.05 * (high - low) : std::max(0.5, 0.05 * std::abs(low));
  low -= pad;
  high += pad;
}

int decimals_for(double step) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 9);
}

void fit_view(std::span<const PlotChannel> channels, SignalPlotState& state) {
  double t0 = std::numeric_limits<double>::infinity();
  double t1 = -std::numeric_limits<double>::infinity();
  for (const PlotChannel& channel : channels) {
    if (!has_data(channel)) continue;
    t0 = std::min(t0, channel.source->start_time());
    t1 = std::max(t1, channel.source->end_time());
  }
  if (!(t0 < t1)) {
    // No data, or a single instant: a one-second window around it.
    const double centre = std::isfinite(t0) ? t0 : 0.5;
    t0 = centre - 0.5;
    t1 = centre + 0.5;
  }
  state.view_t0 = t0;
  state.view_t1 = t1;
  state.fitted = true;
}

//---- Drawing pieces

struct Lane {
  float top = 0, bottom = 0;
  double low = 0, high = 1;
  float y(double value) const {
    return bottom - static_cast<float>((value - low) / (high - low)) * (bottom - top);
  }
};

void draw_channel(ImDrawList& draw, const ChannelView& view, const Lane& lane, float left,
                  double t0, double seconds_per_pixel, ImU32 colour) {
  if (view.raw) {
    // Runs of present samples as polylines; a missing sample breaks the line.
    std::vector<ImVec2> run;
    const float pixels_per_sample =
        view.times.size() > 1
            ? static_cast<float>((view.times[1] - view.times[0]) / seconds_per_pixel)
            : 0.0f;
    auto flush = [&] {
      if (run.size() >= 2)
        draw.AddPolyline(run.data(), static_cast<int>(run.size()), colour, 0, 1.5f);
      run.clear();
    };
    for (size_t index = 0; index < view.values.size(); ++index) {
      if (std::isnan(view.values[index])) {
        flush();
        continue;
      }
      const ImVec2 point(left + static_cast<float>((view.times[index] - t0) / seconds_per_pixel),
                         lane.y(view.values[index]));
      run.push_back(point);
      // Far enough apart to tell samples apart: mark each one.
      if (pixels_per_sample >= 6.0f) {
        draw.AddRectFilled(ImVec2(point.x - 1.5f, point.y - 1.5f),
                           ImVec2(point.x + 1.5f, point.y + 1.5f), colour);
      }
    }
    flush();
    return;
  }
  // One bar per pixel column from min to max, stretched to reach the previous
  // column's range so a continuous signal is drawn without holes.
  const MinMax* previous = nullptr;
  for (size_t column = 0; column < view.columns.size(); ++column) {
    const MinMax& range = view.columns[column];
    if (range.empty()) {
      previous = nullptr;
      continue;
    }
    double low = range.min, high = range.max;
    if (previous) {
      low = std::min<double>(low, previous->max);
      high = std::max<double>(high, previous->min);
    }
    float y_top = lane.y(high);
    float y_bottom = lane.y(low);
    if (y_bottom - y_top < 1.0f) {
      const float middle = 0.5f * (y_top + y_bottom);
      y_top = middle - 0.5f;
      y_bottom = middle + 0.5f;
    }
    const float x = left + static_cast<float>(column);
    draw.AddRectFilled(ImVec2(x, y_top), ImVec2(x + 1.0f, y_bottom), colour);
    previous = &range;
  }
}

void draw_value_ticks(ImDrawList& draw, const Lane& lane, float left, float right,
                      bool labels_only_at_ends) {
  char text[48];
  if (labels_only_at_ends) {
    for (double value : {lane.low, lane.high}) {
      std::snprintf(text, sizeof text, "%.4g", value);
      const ImVec2 extent = ImGui::CalcTextSize(text);
      const float y = std::clamp(lane.y(value) - 0.5f * extent.y, lane.top, lane.bottom - extent.y);
      draw.AddText(ImVec2(left - extent.x - 4.0f, y), kAxisText, text);
    }
    return;
  }
  const int target = std::max(2, static_cast<int>((lane.bottom - lane.top) / kValueTickSpacing));
  const double step = nice_tick_step(lane.high - lane.low, target);
  for (double value = std::ceil(lane.low / step) * step; value <= lane.high; value += step) {
    const float y = lane.y(value);
    draw.AddLine(ImVec2(left, y), ImVec2(right, y), kGrid);
    std::snprintf(text, sizeof text, "%.*f", decimals_for(step),
                  std::abs(value) < step * 1e-6 ? 0.0 : value);
    const ImVec2 extent = ImGui::CalcTextSize(text);
    draw.AddText(ImVec2(left - extent.x - 4.0f, y - 0.5f * extent.y), kAxisText, text);
  }
}

void draw_time_ticks(ImDrawList& draw, const ImVec2& area_min, const ImVec2& area_max, double t0,
                     double t1) {
  const float width = area_max.x - area_min.x;
  const int target = std::max(2, static_cast<int>(width / kTimeTickSpacing));
  const double step = nice_tick_step(t1 - t0, target);
  const int decimals = decimals_for(step);
  char text[48];
  for (double t = std::ceil(t0 / step) * step; t <= t1; t += step) {
    const float x = area_min.x + static_cast<float>((t - t0) / (t1 - t0)) * width;
    draw.AddLine(ImVec2(x, area_min.y), ImVec2(x, area_max.y), kGrid);
    std::snprintf(text, sizeof text, "%.*f s", decimals, std::abs(t) < step * 1e-6 ? 0.0 : t);
    const ImVec2 extent = ImGui::CalcTextSize(text);
    const float label_x = std::clamp(x - 0.5f * extent.x, area_min.x, area_max.x - extent.x);
    draw.AddText(ImVec2(label_x, area_max.y + 3.0f), kAxisText, text);
  }
}

void draw_legend(ImDrawList& draw, std::span<const PlotChannel> channels,
                 std::span<const ImU32> colours, const ImVec2& area_min, const ImVec2& area_max) {
  const float line = ImGui::GetTextLineHeight();
  const int rows = std::min<int>(static_cast<int>(channels.size()), kLegendRows);
  float width = 0.0f;
  for (int row = 0; row < rows; ++row) {
    width = std::max(width, ImGui::CalcTextSize(channels[row].name.c_str()).x);
  }
  const bool more = static_cast<int>(channels.size()) > rows;
  const float box_width = width + line + 14.0f;
  const float box_height = (rows + (more ? 1 : 0)) * line + 8.0f;
  const ImVec2 box_min(area_max.x - box_width - 6.0f, area_min.y + 6.0f);
  draw.AddRectFilled(box_min, ImVec2(box_min.x + box_width, box_min.y + box_height),
                     IM_COL32(16, 16, 20, 200), 3.0f);
  for (int row = 0; row < rows; ++row) {
    const ImVec2 swatch(box_min.x + 5.0f, box_min.y + 4.0f + row * line);
    draw.AddRectFilled(ImVec2(swatch.x, swatch.y + 3.0f),
                       ImVec2(swatch.x + line - 6.0f, swatch.y + line - 3.0f), colours[row]);
    draw.AddText(ImVec2(swatch.x + line, swatch.y), kAxisText, channels[row].name.c_str());
  }
  if (more) {
    char text[32];
    std::snprintf(text, sizeof text, "+%d more", static_cast<int>(channels.size()) - rows);
    draw.AddText(ImVec2(box_min.x + 5.0f + line, box_min.y + 4.0f + rows * line), kAxisText, text);
  }
}

// A span's class name may run on past its end, over the gap to the next span on its row: the
// tags take two rows, alternating, so a short touch between two others keeps a legible name.
// What still does not fit is shortened with a trailing "." (at least three letters) or left out.
void draw_spans(ImDrawList& draw, std::span<const PlotSpan> spans, const ImVec2& area_min,
                const ImVec2& area_max, double t0, double t1) {
  const float width = area_max.x - area_min.x;
  auto x_of = [&](double t) {
    return area_min.x + static_cast<float>((std::clamp(t, t0, t1) - t0) / (t1 - t0)) * width;
  };
  std::vector<size_t> shown;
  for (size_t k = 0; k < spans.size(); ++k)
    if (spans[k].t1 > t0 && spans[k].t0 < t1) shown.push_back(k);
  std::stable_sort(shown.begin(), shown.end(),
                   [&](size_t a, size_t b) { return spans[a].t0 < spans[b].t0; });
  for (size_t k : shown) {
    const PlotSpan& span = spans[k];
    draw.AddRectFilled(ImVec2(x_of(span.t0), area_min.y), ImVec2(x_of(span.t1), area_max.y),
                       span.colour);
  }
  const float line = ImGui::GetFontSize() + 2.0f;
  for (size_t n = 0; n < shown.size(); ++n) {
    const PlotSpan& span = spans[shown[n]];
    if (span.text.empty()) continue;
    const float x0 = x_of(span.t0);
    const float limit = n + 2 < shown.size() ? x_of(spans[shown[n + 2]].t0) : area_max.x;
    const float room = limit - x0 - 6.0f;
    std::string text = span.text;
    while (text.size() > 4 && ImGui::CalcTextSize(text.c_str()).x > room) {
      text.resize(text.size() - 2);
      while (!text.empty() && text.back() == ' ') text.pop_back();
      text += ".";
    }
    if (ImGui::CalcTextSize(text.c_str()).x > room) continue;
    const float y = area_min.y + 2.0f + static_cast<float>(n % 2) * line;
    draw.AddText(ImVec2(x0 + 3.0f, y), IM_COL32(235, 235, 235, 255), text.c_str());
  }
}

}  // namespace

//---- Public

uint32_t plot_colour(int index) {
  static const ImU32 kTableau[10] = {IM_COL32(31, 119, 180, 255),  IM_COL32(255, 127, 14, 255),
                                     IM_COL32(44, 160, 44, 255),   IM_COL32(214, 39, 40, 255),
                                     IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
                                     IM_COL32(227, 119, 194, 255), IM_COL32(127, 127, 127, 255),
                                     IM_COL32(188, 189, 34, 255),  IM_COL32(23, 190, 207, 255)};
  return kTableau[((index % 10) + 10) % 10];
}

double nice_tick_step(double range, int target_ticks) {
  if (!(range > 0) || !std::isfinite(range) || target_ticks < 1) return 1.0;
  const double raw = range / target_ticks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double multiple : {1.0, 2.0, 5.0}) {
    if (multiple * power >= raw) return multiple * power;
  }
  return 10.0 * power;
}

SignalPlotResult draw_signal_plot(const char* id, std::span<const PlotChannel> channels,
                                  std::span<const PlotSpan> spans, SignalPlotState& state,
                                  double cursor_time, ImVec2 size) {
  SignalPlotResult result;
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const int vertices_before = draw.VtxBuffer.Size;
  ImGui::PushID(id);

  // Toolbar: the lane toggle.
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::Checkbox("Lanes", &state.stacked);
  const float toolbar = ImGui::GetFrameHeightWithSpacing();
  const float time_axis = ImGui::GetTextLineHeight() + 6.0f;
  const ImVec2 area_min(origin.x + kValueAxisWidth, origin.y + toolbar);
  const ImVec2 area_max(origin.x + std::max(size.x, kValueAxisWidth + 16.0f),
                        origin.y + std::max(size.y, toolbar + time_axis + 16.0f) - time_axis);
  result.area_min = area_min;
  result.area_max = area_max;
  const float width = area_max.x - area_min.x;

  //---- Input: zoom, pan, fit, click
  if (!state.fitted || !(state.view_t1 > state.view_t0) || !std::isfinite(state.view_t0) ||
      !std::isfinite(state.view_t1)) {
    fit_view(channels, state);
    result.view_changed = true;
  }
  ImGui::SetCursorScreenPos(area_min);
  ImGui::InvisibleButton("area", ImVec2(width, area_max.y - area_min.y));
  const bool hovered = ImGui::IsItemHovered();
  ImGuiIO& io = ImGui::GetIO();
  const double span = state.view_t1 - state.view_t0;
  const double mouse_time = state.view_t0 + (io.MousePos.x - area_min.x) / width * span;
  if (hovered && io.MouseWheel != 0.0f) {
    const double factor = std::pow(kZoomPerWheelStep, io.MouseWheel);
    // Zooming about the cursor keeps the time under it where it is; a span below a
    // microsecond is no longer a view of sampled data.
    const double new_span = std::max(span * factor, 1e-6);
    const double ratio = new_span / span;
    state.view_t0 = mouse_time - (mouse_time - state.view_t0) * ratio;
    state.view_t1 = state.view_t0 + new_span;
    result.view_changed = true;
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left, kDragThreshold) &&
      io.MouseDelta.x != 0.0f) {
    const double shift = -io.MouseDelta.x / width * (state.view_t1 - state.view_t0);
    state.view_t0 += shift;
    state.view_t1 += shift;
    result.view_changed = true;
  }
  if (hovered && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    fit_view(channels, state);
    result.view_changed = true;
  } else if (ImGui::IsItemDeactivated() &&
             io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < kDragThreshold * kDragThreshold) {
    result.clicked_time = mouse_time;
  }

  //---- Data through the sources
  const double t0 = state.view_t0;
  const double t1 = state.view_t1;
  const int columns = std::max(1, static_cast<int>(std::floor(width)));
  const double seconds_per_pixel = (t1 - t0) / width;
  std::vector<ChannelView> views;
  std::vector<ImU32> colours;
  MinMax overall;
  for (size_t index = 0; index < channels.size(); ++index) {
    views.push_back(view_channel(channels[index], t0, t1, columns));
    colours.push_back(channels[index].colour ? channels[index].colour
                                             : plot_colour(static_cast<int>(index)));
    overall.merge(views.back().extent);
  }

  //---- Drawing
  draw.AddRectFilled(area_min, area_max, kBackground);
  draw_spans(draw, spans, area_min, area_max, t0, t1);
  draw_time_ticks(draw, area_min, area_max, t0, t1);
  const bool stacked = state.stacked && !channels.empty();
  padded_range(overall, result.value_min, result.value_max);
  if (!stacked) {
    draw_value_ticks(draw, Lane{area_min.y, area_max.y, result.value_min, result.value_max},
                     area_min.x, area_max.x, false);
  }
  draw.PushClipRect(area_min, area_max, true);
  const float lane_height = (area_max.y - area_min.y) / std::max<size_t>(channels.size(), 1);
  std::vector<Lane> lanes;
  for (size_t index = 0; index < channels.size(); ++index) {
    Lane lane{area_min.y, area_max.y, result.value_min, result.value_max};
    if (stacked) {
      lane.top = area_min.y + lane_height * static_cast<float>(index);
      lane.bottom = lane.top + lane_height;
      padded_range(views[index].extent, lane.low, lane.high);
      if (index > 0)
        draw.AddLine(ImVec2(area_min.x, lane.top), ImVec2(area_max.x, lane.top), kGrid);
    }
    draw_channel(draw, views[index], lane, area_min.x, t0, seconds_per_pixel, colours[index]);
    if (stacked) {
      draw.AddText(ImVec2(area_min.x + 4.0f, lane.top + 2.0f), colours[index],
                   channels[index].name.c_str());
    }
    lanes.push_back(lane);
  }
  if (cursor_time >= t0 && cursor_time <= t1) {
    // On a pixel centre and 2 px wide, so its core is one solid pixel column.
    const float x =
        std::floor(area_min.x + static_cast<float>((cursor_time - t0) / seconds_per_pixel)) + 0.5f;
    draw.AddLine(ImVec2(x, area_min.y), ImVec2(x, area_max.y), kCursor, 2.0f);
  }
  draw.PopClipRect();
  if (stacked) {
    for (const Lane& lane : lanes) draw_value_ticks(draw, lane, area_min.x, area_max.x, true);
  } else if (!channels.empty()) {
    draw_legend(draw, channels, colours, area_min, area_max);
  }
  draw.AddRect(area_min, area_max, kGrid);

  // Hover read-out: the time and each channel's range under the mouse column.
  if (hovered && !ImGui::IsItemActive() && !channels.empty()) {
    const int column = static_cast<int>(io.MousePos.x - area_min.x);
    ImGui::BeginTooltip();
    ImGui::Text("t = %.*f s", decimals_for(seconds_per_pixel) + 1, mouse_time);
    for (size_t index = 0; index < channels.size() && index < kLegendRows; ++index) {
      const ChannelView& view = views[index];
      MinMax under;
      if (!view.raw && column >= 0 && column < static_cast<int>(view.columns.size())) {
        under = view.columns[column];
      } else if (view.raw && !view.times.empty()) {
        // Nearest sample to the mouse.
        const auto nearest =
            std::min_element(view.times.begin(), view.times.end(), [&](double a, double b) {
              return std::abs(a - mouse_time) < std::abs(b - mouse_time);
            });
        under.add(view.values[nearest - view.times.begin()]);
      }
      if (under.empty()) {
        ImGui::TextColored(ImColor(colours[index]), "%s: no data", channels[index].name.c_str());
      } else if (under.min == under.max) {
        ImGui::TextColored(ImColor(colours[index]), "%s: %.5g", channels[index].name.c_str(),
                           under.min);
      } else {
        ImGui::TextColored(ImColor(colours[index]), "%s: %.5g .. %.5g",
                           channels[index].name.c_str(), under.min, under.max);
      }
    }
    ImGui::EndTooltip();
  }

  // Leave the layout cursor below the whole plot.
  ImGui::SetCursorScreenPos(origin);
  ImGui::Dummy(ImVec2(area_max.x - origin.x, area_max.y + time_axis - origin.y));
  ImGui::PopID();
  result.vertices = draw.VtxBuffer.Size - vertices_before;
  return result;
}

}  // namespace tactile

// Signals view: the plotted channels over the visible time range, labels shaded.
#include <algorithm>

#include "views.h"

namespace tactile {

namespace {

// A channel as the plot's legend names it: its recorded name, and its taxel's name when that
// says more (a grid's ch94 is r3c14, a fur cell's f017 is r1c01). Recordings keep the names.
std::string legend_name(const SkinLayout& layout, const std::string& channel) {
  const int index = layout.channel_index(channel);
  if (index < 0) return channel;
  for (const Taxel& taxel : layout.taxels)
    if (std::find(taxel.channels.begin(), taxel.channels.end(), index) != taxel.channels.end())
      return channel.find(taxel.name) == std::string::npos ? channel + " " + taxel.name : channel;
  return channel;
}

}  // namespace

void draw_signals_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("signals_view", size, false);
  const Document& document = *state.document;
  const SampleSource& source = document.samples();
  std::vector<PlotChannel> channels;
  for (int column = 0; column < source.channel_count(); ++column) {
    if (!state.plotted[static_cast<size_t>(column)]) continue;
    PlotChannel channel;
    channel.name =
        legend_name(document.layout, source.info().channels[static_cast<size_t>(column)]);
    channel.source = &source;
    channel.channel = column;
    channel.colour = plot_colour(static_cast<int>(channels.size()));
    channels.push_back(std::move(channel));
  }
  // The labels of the top lane shown (the user orders the lanes), looked up by time,
  // so 100,000 labels cost what 100 do.
  std::vector<PlotSpan> spans;
  const double t0 = state.plot.view_t0, t1 = state.plot.view_t1;
  const int columns = std::max(1, static_cast<int>(ImGui::GetContentRegionAvail().x));
  // Labels narrower than a few pixels would paint the signals over in stripes: the plot
  // shades them only when the view shows each one (the lanes below show them anyway).
  if (const LaneIndex* lane = top_lane(state);
      lane && lane->count_meeting(t0, t1, static_cast<size_t>(columns / 8)) <=
                  static_cast<size_t>(columns / 8))
    for (const LaneSpan& span : lane_spans(*lane, t0, t1, columns)) {
      const Label& label = lane->labels()[span.label];
      spans.push_back({std::max(label.t0, t0), std::min(label.t1, t1),
                       class_colour(state, label.class_name, 70), label.class_name});
    }
  // Live: where packets were lost, marked (the lines break there too).
  if (state.live.connected)
    for (const auto& [first, end] : static_cast<const LiveSampleSource&>(source).gaps()) {
      const double g0 = source.time_of(first), g1 = source.time_of(end);
      if (g1 >= t0 && g0 <= t1)
        spans.push_back({std::max(g0, t0), std::min(g1, t1), IM_COL32(230, 60, 50, 70), "lost"});
    }
  const SignalPlotResult result = draw_signal_plot(
      "signals", channels, spans, state.plot, state.clock.time(), ImGui::GetContentRegionAvail());
  state.targets.time_axes["signals"] = {to_rect(result.area_min, result.area_max),
                                        state.plot.view_t0, state.plot.view_t1};
  if (result.clicked_time) state.clock.seek(*result.clicked_time);
  // Live, a zoom or pan of the user's stops following the newest sample (F follows again).
  if (result.view_changed && state.live.connected && ImGui::IsWindowHovered())
    state.live.follow = false;
  ImGui::EndChild();
}

}  // namespace tactile

// Signals view: the plotted channels over the visible time range, labels shaded.
#include "views.h"

namespace tactile {

void draw_signals_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("signals_view", size, false);
  const Document& document = *state.document;
  const SampleSource& source = document.samples();
  std::vector<PlotChannel> channels;
  for (int column = 0; column < source.channel_count(); ++column) {
    if (!state.plotted[static_cast<size_t>(column)]) continue;
    PlotChannel channel;
    channel.name = source.info().channels[static_cast<size_t>(column)];
    channel.source = &source;
    channel.channel = column;
    channel.colour = plot_colour(static_cast<int>(channels.size()));
    channels.push_back(std::move(channel));
  }
  std::vector<PlotSpan> spans;
  for (const Label& label : document.labels)
    spans.push_back({label.t0, label.t1, class_colour(label.class_name), label.class_name});
  const SignalPlotResult result = draw_signal_plot(
      "signals", channels, spans, state.plot, state.clock.time(), ImGui::GetContentRegionAvail());
  state.targets.time_axes["signals"] = {to_rect(result.area_min, result.area_max),
                                        state.plot.view_t0, state.plot.view_t1};
  if (result.clicked_time) state.clock.seek(*result.clicked_time);
  ImGui::EndChild();
}

}  // namespace tactile

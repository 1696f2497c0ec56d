// Recording view: metadata, streams and the channel list.
#include <algorithm>
#include <cstdio>

#include "views.h"

namespace tactile {

namespace {

void metadata_row(const char* key, const std::string& value) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextDisabled("%s", key);
  ImGui::TableNextColumn();
  // Long values (per-channel calibration lists) are cut; the tooltip has them whole.
  constexpr size_t kShown = 48;
  if (value.size() <= kShown) {
    ImGui::TextWrapped("%s", value.c_str());
    return;
  }
  ImGui::TextWrapped("%s...", value.substr(0, kShown).c_str());
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
    ImGui::TextUnformatted(value.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

}  // namespace

void draw_info_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("info_view", size, false);
  const Document& document = *state.document;
  const SampleSource& source = document.samples();
  const SourceInfo& info = source.info();
  ImGui::Text("%s", info.recording_id.c_str());
  if (ImGui::BeginTable("metadata", 2)) {
    ImGui::TableSetupColumn("key", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
    metadata_row("layout", document.layout.name.empty() ? info.layout_id : document.layout.name);
    char text[160];
    std::snprintf(text, sizeof(text), "%g Hz, %d channels, %s", info.rate_hz,
                  source.channel_count(), format_seconds(source.duration()).c_str());
    metadata_row("stream", info.stream + ": " + text);
    for (const auto& [key, value] : info.metadata) metadata_row(key.c_str(), value);
    ImGui::EndTable();
  }
  if (document.streams.size() > 1) {
    ImGui::Separator();
    for (const std::string& stream : document.streams)
      if (ImGui::RadioButton(stream.c_str(), stream == info.stream) && stream != info.stream)
        state.stream_request = stream;
  }
  ImGui::Separator();
  if (ImGui::SmallButton("none")) std::fill(state.plotted.begin(), state.plotted.end(), 0);
  remember_item(state, "button:plot none",
                "Plot no channel (then click taxels or tick channels below)");
  ImGui::SameLine();
  ImGui::TextDisabled("click a taxel to add its channel");
  ImGui::BeginChild("channels");
  ImGuiListClipper clipper;  // thousands of channels stay cheap to list
  clipper.Begin(source.channel_count());
  while (clipper.Step())
    for (int column = clipper.DisplayStart; column < clipper.DisplayEnd; ++column) {
      bool shown = state.plotted[static_cast<size_t>(column)] != 0;
      if (ImGui::Checkbox(info.channels[static_cast<size_t>(column)].c_str(), &shown))
        state.plotted[static_cast<size_t>(column)] = shown;
      remember_item(state, "checkbox:channel:" + info.channels[static_cast<size_t>(column)],
                    "Plot this channel in the Signals view");
    }
  ImGui::EndChild();
  ImGui::EndChild();
}

}  // namespace tactile

#include "workbench.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "tactile/error.h"
#include "tactile/layout/taxel_values.h"
#include "tactile/widgets/skin_view.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

constexpr float kSidebarWidth = 250.0f;
constexpr int kMaxDefaultPlotChannels = 8;
constexpr double kSpeeds[] = {0.25, 0.5, 1.0, 2.0, 4.0};

// Tableau 10: distinct hues for up to ten plotted channels, then repeated.
constexpr uint32_t kChannelColours[] = {IM_COL32(31, 119, 180, 255),  IM_COL32(255, 127, 14, 255),
                                        IM_COL32(44, 160, 44, 255),   IM_COL32(214, 39, 40, 255),
                                        IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
                                        IM_COL32(227, 119, 194, 255), IM_COL32(127, 127, 127, 255),
                                        IM_COL32(188, 189, 34, 255),  IM_COL32(23, 190, 207, 255)};

uint32_t class_colour(const std::string& class_name) {
  const size_t hash = std::hash<std::string>{}(class_name);
  const uint32_t base = kChannelColours[hash % std::size(kChannelColours)];
  return (base & 0x00FFFFFFu) | (70u << 24);  // translucent, so signals show through
}

std::string format_seconds(double seconds) {
  char text[32];
  const int minutes = static_cast<int>(seconds / 60.0);
  std::snprintf(text, sizeof(text), "%d:%06.3f", minutes, seconds - minutes * 60.0);
  return text;
}

}  // namespace

Workbench::Workbench(const WorkbenchOptions& options) : options_(options) {
  if (options_.open_path.empty()) return;
  std::error_code error;
  if (fs::is_directory(options_.open_path, error)) {
    set_workspace(options_.open_path);
    if (!workspace_files_.empty()) open(workspace_files_.front());
  } else {
    open(options_.open_path);
  }
  if (document_ && options_.time) clock_.seek(*options_.time);
  if (document_ && options_.play) clock_.play();
}

void Workbench::set_workspace(const std::string& folder) {
  workspace_ = folder;
  workspace_files_.clear();
  std::error_code error;
  for (fs::recursive_directory_iterator it(folder, error), end; !error && it != end;
       it.increment(error))
    if (it->path().extension() == ".h5") workspace_files_.push_back(it->path().string());
  std::sort(workspace_files_.begin(), workspace_files_.end());
}

void Workbench::open(const std::string& path) {
  try {
    document_ = open_document(path, options_.labels_path);
    error_.clear();
  } catch (const std::exception& failure) {
    error_ = failure.what();
    return;
  }
  if (workspace_.empty()) set_workspace(fs::path(path).parent_path().string());
  clock_.pause();
  clock_.set_range(0.0, document_->recording.duration());
  choose_default_view();
}

// Shows the skin's display modality, plots the channels of that modality that move the
// most, and puts the cursor inside the first labelled touch so the skin is lit on opening.
void Workbench::choose_default_view() {
  const Document& document = *document_;
  const Stream& stream = document.stream();
  modality_ = std::max(0, document.layout.modality_index(document.layout.display_modality));
  rest_scale_modality_ = -1;
  skin_zoom_ = SkinViewZoom{};
  plotted_.assign(static_cast<size_t>(stream.channel_count()), 0);
  const std::vector<int> columns = taxel_columns(document.layout, stream.channels, modality_);
  std::vector<std::pair<float, int>> spread;
  for (int column : columns) {
    if (column < 0 || stream.sample_count() == 0) continue;
    const auto values = stream.samples.col(column);
    spread.emplace_back(values.maxCoeff() - values.minCoeff(), column);
  }
  if (spread.empty())
    for (int column = 0; column < std::min<int>(kMaxDefaultPlotChannels, stream.channel_count());
         ++column)
      spread.emplace_back(0.0f, column);
  std::stable_sort(spread.begin(), spread.end(),
                   [](auto& a, auto& b) { return a.first > b.first; });
  for (size_t k = 0; k < spread.size() && k < kMaxDefaultPlotChannels; ++k)
    plotted_[spread[k].second] = 1;
  plot_state_ = SignalPlotState{};
  plot_state_.view_t0 = 0.0;
  plot_state_.view_t1 = std::max(1e-3, document.recording.duration());
  plot_state_.fitted = true;
  if (document.labels.empty()) {
    clock_.seek(0.0);
    return;
  }
  // The instant of the first labelled touch where the skin changes most from rest.
  const Label& first = document.labels.front();
  const RestScale scale = rest_scale(stream, columns);
  const int64_t start = stream.index_at(first.t0);
  const int64_t end = stream.index_at(first.t1);
  int64_t best = (start + end) / 2;
  double best_change = -1.0;
  for (int64_t sample = start; sample <= end; ++sample) {
    double change = 0.0;
    for (size_t k = 0; k < columns.size(); ++k)
      if (columns[k] >= 0 && std::isfinite(scale.rest[k]))
        change += std::abs(stream.samples(sample, columns[k]) - scale.rest[k]);
    if (change > best_change) best_change = change, best = sample;
  }
  clock_.seek(stream.time_of(best));
}

void Workbench::toggle_taxel_channels(int64_t taxel_id) {
  const Taxel* taxel = document_->layout.find_taxel(taxel_id);
  if (!taxel || modality_ >= static_cast<int>(taxel->channels.size())) return;
  const int channel = taxel->channels[modality_];
  if (channel < 0) return;
  const std::string& name = document_->layout.channels[channel].name;
  const auto& names = document_->stream().channels;
  const auto found = std::find(names.begin(), names.end(), name);
  if (found != names.end()) {
    char& flag = plotted_[static_cast<size_t>(found - names.begin())];
    flag = !flag;
  }
}

//---------------------------------------------------------------------------------------------
void Workbench::frame(double seconds) {
  clock_.advance(seconds);
  if (!ImGui::GetIO().WantTextInput &&
      ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Space), false))
    clock_.toggle();

  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->WorkPos);
  ImGui::SetNextWindowSize(viewport->WorkSize);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_MenuBar |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus |
                                 ImGuiWindowFlags_NoSavedSettings;
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::Begin("Tactile Workbench", nullptr, flags);
  ImGui::PopStyleVar();
  draw_menu_bar();

  const ImVec2 area = ImGui::GetContentRegionAvail();
  const float status_height = ImGui::GetFrameHeightWithSpacing();
  const float main_height = area.y - status_height;
  draw_sidebar(kSidebarWidth, main_height);
  ImGui::SameLine();
  ImGui::BeginGroup();
  const float right_width = area.x - kSidebarWidth - ImGui::GetStyle().ItemSpacing.x;
  if (document_) {
    const float transport_height = ImGui::GetFrameHeightWithSpacing();
    const float labels_height = std::max(90.0f, main_height * 0.22f);
    const float views_height =
        main_height - transport_height - labels_height - ImGui::GetStyle().ItemSpacing.y * 2;
    const float skin_width = std::floor(right_width * 0.42f);
    draw_skin_panel(skin_width, views_height);
    ImGui::SameLine();
    draw_plot_panel(right_width - skin_width - ImGui::GetStyle().ItemSpacing.x, views_height);
    draw_transport(right_width);
    draw_labels_panel(right_width, labels_height);
  } else {
    ImGui::BeginChild("welcome", ImVec2(right_width, main_height), true);
    ImGui::TextUnformatted("No recording open.");
    ImGui::TextUnformatted("File > Open... (Ctrl+O), or pick one from the workspace on the left.");
    ImGui::TextUnformatted("Make one with: tactile simulate --demo DIR");
    ImGui::EndChild();
  }
  ImGui::EndGroup();
  draw_status_bar();
  ImGui::End();

  if (auto chosen = file_browser_.draw()) open(*chosen);
}

void Workbench::draw_menu_bar() {
  const ImGuiIO& io = ImGui::GetIO();
  // ImGui 1.86 indexes keys by the backend's native codes; GLFW's letter keys are their ASCII.
  const bool open_shortcut = io.KeyCtrl && ImGui::IsKeyPressed('O', false);
  if (ImGui::BeginMenuBar()) {
    if (ImGui::BeginMenu("File")) {
      if (ImGui::MenuItem("Open...", "Ctrl+O"))
        file_browser_.open(workspace_.empty() ? "." : workspace_, {".h5"});
      if (ImGui::MenuItem("Quit", "Ctrl+Q")) quit_ = true;
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
      ImGui::MenuItem("Stacked lanes", nullptr, &plot_state_.stacked);
      if (ImGui::MenuItem("Fit time axis", nullptr, false, document_ != nullptr)) {
        plot_state_.view_t0 = 0.0;
        plot_state_.view_t1 = std::max(1e-3, document_->recording.duration());
      }
      ImGui::EndMenu();
    }
    ImGui::EndMenuBar();
  }
  if (open_shortcut) file_browser_.open(workspace_.empty() ? "." : workspace_, {".h5"});
  if (io.KeyCtrl && ImGui::IsKeyPressed('Q', false)) quit_ = true;
}

//---------------------------------------------------------------------------------------------
void Workbench::draw_sidebar(float width, float height) {
  ImGui::BeginChild("sidebar", ImVec2(width, height), true);
  if (ImGui::CollapsingHeader("Workspace", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (workspace_files_.empty()) ImGui::TextDisabled("(no recordings)");
    ImGui::BeginChild("files",
                      ImVec2(0, std::min(height * 0.45f, 22.0f * (workspace_files_.size() + 1))));
    for (const std::string& file : workspace_files_) {
      const std::string shown = fs::relative(file, workspace_).string();
      const bool selected = document_ && document_->path == file;
      if (ImGui::Selectable(shown.c_str(), selected) && !selected) open(file);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", file.c_str());
    }
    ImGui::EndChild();
  }
  if (document_ && ImGui::CollapsingHeader("Recording", ImGuiTreeNodeFlags_DefaultOpen)) {
    const Recording& recording = document_->recording;
    ImGui::Text("%s", recording.id.c_str());
    if (ImGui::BeginTable("metadata", 2)) {
      ImGui::TableSetupColumn("key", ImGuiTableColumnFlags_WidthFixed);
      ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
      auto row = [](const char* key, const std::string& value) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextDisabled("%s", key);
        ImGui::TableNextColumn();
        // Long values (per-channel calibration lists) are cut; the tooltip has them whole.
        constexpr size_t kShown = 48;
        if (value.size() <= kShown) {
          ImGui::TextWrapped("%s", value.c_str());
        } else {
          ImGui::TextWrapped("%s...", value.substr(0, kShown).c_str());
          if (ImGui::IsItemHovered()) {
            ImGui::BeginTooltip();
            ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
            ImGui::TextUnformatted(value.c_str());
            ImGui::PopTextWrapPos();
            ImGui::EndTooltip();
          }
        }
      };
      row("layout", document_->layout.name.empty() ? recording.layout_id : document_->layout.name);
      for (const auto& [key, value] : recording.metadata) row(key.c_str(), value);
      ImGui::EndTable();
    }
    ImGui::Separator();
    for (size_t k = 0; k < recording.streams.size(); ++k) {
      const Stream& stream = recording.streams[k];
      char text[160];
      std::snprintf(text, sizeof(text), "%s  %g Hz  %lld ch  %s", stream.name.c_str(),
                    stream.rate_hz, static_cast<long long>(stream.channel_count()),
                    format_seconds(stream.duration()).c_str());
      if (ImGui::RadioButton(text, document_->stream_index == static_cast<int>(k))) {
        select_stream(*document_, static_cast<int>(k));
        choose_default_view();
      }
    }
  }
  if (document_ && ImGui::CollapsingHeader("Channels")) {
    const Stream& stream = document_->stream();
    if (ImGui::SmallButton("none")) std::fill(plotted_.begin(), plotted_.end(), 0);
    ImGui::SameLine();
    ImGui::TextDisabled("click a taxel to add its channel");
    ImGuiListClipper clipper;  // thousands of channels stay cheap to list
    clipper.Begin(static_cast<int>(stream.channel_count()));
    while (clipper.Step())
      for (int column = clipper.DisplayStart; column < clipper.DisplayEnd; ++column) {
        bool shown = plotted_[column] != 0;
        if (ImGui::Checkbox(stream.channels[column].c_str(), &shown)) plotted_[column] = shown;
      }
  }
  ImGui::EndChild();
}

void Workbench::draw_skin_panel(float width, float height) {
  ImGui::BeginChild("skin", ImVec2(width, height), true);
  const SkinLayout& layout = document_->layout;
  ImGui::SetNextItemWidth(140);
  const char* current = layout.modalities.empty() ? "" : layout.modalities[modality_].c_str();
  if (ImGui::BeginCombo("modality", current)) {
    for (int k = 0; k < static_cast<int>(layout.modalities.size()); ++k)
      if (ImGui::Selectable(layout.modalities[k].c_str(), k == modality_)) modality_ = k;
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::Checkbox("raw values", &show_raw_values_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Off: each taxel's change from its rest level (median), scaled to the\n"
        "recording's touches. On: raw values in the layout's display range.");
  const Stream& stream = document_->stream();
  const std::vector<int> columns = taxel_columns(layout, stream.channels, modality_);
  std::vector<float> values = taxel_values(stream, columns, stream.index_at(clock_.time()));
  double value_min = 0.0;
  double value_max = 1.0;
  std::string legend = current;
  if (show_raw_values_) {
    // The layout's display range belongs to its display modality; others scale to their data.
    value_min = layout.display_min;
    value_max = layout.display_max;
    if (layout.modalities.empty() || layout.modalities[modality_] != layout.display_modality) {
      value_min = std::numeric_limits<double>::max();
      value_max = std::numeric_limits<double>::lowest();
      for (int column : columns) {
        if (column < 0 || stream.sample_count() == 0) continue;
        value_min = std::min<double>(value_min, stream.samples.col(column).minCoeff());
        value_max = std::max<double>(value_max, stream.samples.col(column).maxCoeff());
      }
      if (value_min > value_max) value_min = 0.0, value_max = 1.0;
    }
  } else {
    if (rest_scale_modality_ != modality_) {
      rest_scale_ = rest_scale(stream, columns);
      rest_scale_modality_ = modality_;
    }
    values = change_from_rest(values, rest_scale_);
    value_max = rest_scale_.max_change;
  }
  SkinViewStyle style;
  style.modality_label = legend;
  style.zoom = &skin_zoom_;
  const ImVec2 size = ImGui::GetContentRegionAvail();
  const SkinViewResult result =
      draw_skin_view("skin_view", layout, values, value_min, value_max, size, style);
  if (result.clicked_taxel >= 0) toggle_taxel_channels(result.clicked_taxel);
  ImGui::EndChild();
}

void Workbench::draw_plot_panel(float width, float height) {
  ImGui::BeginChild("plot", ImVec2(width, height), true);
  const Stream& stream = document_->stream();
  std::vector<PlotChannel> channels;
  for (int64_t column = 0; column < stream.channel_count(); ++column) {
    if (!plotted_[column]) continue;
    PlotChannel channel;
    channel.name = stream.channels[column];
    channel.pyramid = &document_->pyramids[column];
    channel.rate_hz = stream.rate_hz;
    channel.start_time = stream.start_time;
    channel.colour = kChannelColours[channels.size() % std::size(kChannelColours)];
    channels.push_back(std::move(channel));
  }
  std::vector<PlotSpan> spans;
  for (const Label& label : document_->labels)
    spans.push_back({label.t0, label.t1, class_colour(label.class_name), label.class_name});
  const SignalPlotResult result = draw_signal_plot("signals", channels, spans, plot_state_,
                                                   clock_.time(), ImGui::GetContentRegionAvail());
  if (result.clicked_time) clock_.seek(*result.clicked_time);
  ImGui::EndChild();
}

void Workbench::draw_transport(float width) {
  ImGui::BeginChild("transport", ImVec2(width, ImGui::GetFrameHeight()), false);
  if (ImGui::Button(clock_.playing() ? "Pause" : "Play", ImVec2(70, 0))) clock_.toggle();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  char speed_text[16];
  std::snprintf(speed_text, sizeof(speed_text), "%gx", clock_.speed());
  if (ImGui::BeginCombo("##speed", speed_text)) {
    for (double speed : kSpeeds) {
      std::snprintf(speed_text, sizeof(speed_text), "%gx", speed);
      if (ImGui::Selectable(speed_text, speed == clock_.speed())) clock_.set_speed(speed);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  bool looping = clock_.looping();
  if (ImGui::Checkbox("loop", &looping)) clock_.set_looping(looping);
  ImGui::SameLine();
  const std::string now = format_seconds(clock_.time()) + " / " + format_seconds(clock_.end());
  ImGui::SetNextItemWidth(-1);
  float time = static_cast<float>(clock_.time());
  if (ImGui::SliderFloat("##time", &time, static_cast<float>(clock_.start()),
                         static_cast<float>(clock_.end()), now.c_str()))
    clock_.seek(time);
  ImGui::EndChild();
}

void Workbench::draw_labels_panel(float width, float height) {
  ImGui::BeginChild("labels", ImVec2(width, height), true);
  const auto& labels = document_->labels;
  if (document_->labels_path.empty()) {
    ImGui::TextDisabled("No label database beside this recording.");
  } else if (labels.empty()) {
    ImGui::TextDisabled("No labels for this recording in %s.", document_->labels_path.c_str());
  } else if (ImGui::BeginTable("label_table", 6,
                               ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                                   ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_Resizable)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* header : {"class", "region", "t0", "t1", "source", "annotator"})
      ImGui::TableSetupColumn(header);
    ImGui::TableHeadersRow();
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(labels.size()));
    while (clipper.Step())
      for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
        const Label& label = labels[row];
        const bool current = clock_.time() >= label.t0 && clock_.time() < label.t1;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::PushID(row);
        if (ImGui::Selectable(label.class_name.c_str(), current,
                              ImGuiSelectableFlags_SpanAllColumns))
          clock_.seek(label.t0);
        ImGui::PopID();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(label.region.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", label.t0);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f", label.t1);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(to_string(label.source));
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(label.annotator.c_str());
      }
    ImGui::EndTable();
  }
  ImGui::EndChild();
}

void Workbench::draw_status_bar() {
  if (!error_.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error_.c_str());
  } else if (document_) {
    ImGui::TextDisabled(
        "%s   %zu labels   space: play/pause   wheel: zoom   drag (skin: right-drag): pan   "
        "double-click: fit",
        document_->path.c_str(), document_->labels.size());
  } else {
    ImGui::TextDisabled("Tactile Workbench");
  }
}

}  // namespace tactile

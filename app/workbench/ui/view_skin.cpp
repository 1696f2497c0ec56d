// Skin view: the layout lit by each taxel's value at the time cursor; a click on a taxel
// selects it (shift: adds to the selection) and toggles its channel in the plot.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <map>

#include "jobs.h"
#include "results.h"
#include "table_maps.h"
#include "tactile/labels/region.h"
#include "views.h"

namespace tactile {

namespace {

void toggle_taxel_channel(WorkbenchState& state, int64_t taxel_id) {
  const Document& document = *state.document;
  const Taxel* taxel = document.layout.find_taxel(taxel_id);
  if (!taxel || state.modality >= static_cast<int>(taxel->channels.size())) return;
  const int channel = taxel->channels[static_cast<size_t>(state.modality)];
  if (channel < 0) return;
  const int column = document.samples().channel_index(document.layout.channels[channel].name);
  if (column >= 0) state.plotted[static_cast<size_t>(column)] ^= 1;
}

void select_taxel(WorkbenchState& state, int64_t taxel_id, bool add) {
  auto& taxels = state.selection.taxels;
  if (!add) taxels.clear();
  const auto found = std::find(taxels.begin(), taxels.end(), taxel_id);
  if (found == taxels.end())
    taxels.push_back(taxel_id);
  else if (add)
    taxels.erase(found);
}

// A left-drag over the skin draws a rectangle; on release the taxels whose centres it
// holds are selected (Shift: added) — the region of the next label.
void select_in_rectangle(WorkbenchState& state, const SkinLayout& layout,
                         const SkinViewResult& result, ImVec2 origin, ImVec2 size) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 start = io.MouseClickedPos[0];
  const bool started_here = start.x >= origin.x && start.x < origin.x + size.x &&
                            start.y >= origin.y && start.y < origin.y + size.y;
  if (!started_here || io.MouseDragMaxDistanceSqr[0] < 36.0f) return;
  const ImVec2 now = io.MousePos;
  const ImVec2 low(std::min(start.x, now.x), std::min(start.y, now.y));
  const ImVec2 high(std::max(start.x, now.x), std::max(start.y, now.y));
  if (ImGui::IsMouseDown(0)) {
    ImDrawList& draw = *ImGui::GetWindowDrawList();
    draw.AddRectFilled(low, high, IM_COL32(255, 140, 40, 40));
    draw.AddRect(low, high, IM_COL32(255, 140, 40, 255));
    return;
  }
  if (!ImGui::IsMouseReleased(0)) return;
  if (!io.KeyShift) state.selection.taxels.clear();
  for (const Taxel& taxel : layout.taxels) {
    const ImVec2 centre = result.transform.apply(taxel.position);
    if (centre.x >= low.x && centre.x <= high.x && centre.y >= low.y && centre.y <= high.y &&
        std::find(state.selection.taxels.begin(), state.selection.taxels.end(), taxel.id) ==
            state.selection.taxels.end())
      state.selection.taxels.push_back(taxel.id);
  }
}

// The layout's body regions, for colouring the somatosensory map: the groups of the first of
// these kinds that holds every taxel (else of the kind that holds the most), each a colour of
// the categorical palette (the classes' palette).
SkinViewCategories body_regions(const SkinLayout& layout) {
  static const char* const kRegionKinds[] = {"body-part", "location", "region",
                                             "zone",      "side",     "layer"};
  std::map<int64_t, size_t> index_of;
  for (size_t index = 0; index < layout.taxels.size(); ++index)
    index_of.emplace(layout.taxels[index].id, index);
  const auto regions_of_kind = [&](const std::string& kind) {
    SkinViewCategories regions;
    regions.of_taxel.assign(layout.taxels.size(), -1);
    for (const Group& group : layout.groups) {
      if (group.kind != kind) continue;
      const int category = static_cast<int>(regions.names.size());
      regions.names.push_back(group.name.empty() ? group.id : group.name);
      regions.colours.push_back(distinct_palette_colour(regions.names.size() - 1));
      for (int64_t id : group.taxels) {
        const auto found = index_of.find(id);
        if (found != index_of.end() && regions.of_taxel[found->second] < 0)
          regions.of_taxel[found->second] = category;
      }
    }
    return regions;
  };
  SkinViewCategories best;
  long best_held = 0;
  for (const char* kind : kRegionKinds) {
    SkinViewCategories regions = regions_of_kind(kind);
    const long held = std::count_if(regions.of_taxel.begin(), regions.of_taxel.end(),
                                    [](int category) { return category >= 0; });
    if (held > best_held) best = std::move(regions), best_held = held;
    if (best_held == static_cast<long>(layout.taxels.size())) break;
  }
  return best;
}

// The skin as the view draws it this frame (state.skin_drawing), made again when the layout,
// the map or, for a strip, the number of columns that fill the panel changes.
const SkinLayout& skin_drawing_of(WorkbenchState& state, const SkinLayout& layout, bool on_map,
                                  ImVec2 available) {
  WorkbenchState::SkinDrawing& drawing = state.skin_drawing;
  const bool strip = !on_map && layout.id.rfind("strip:", 0) == 0;
  const int64_t columns = strip ? strip_columns_to_fit(static_cast<int64_t>(layout.taxels.size()),
                                                       std::max(available.x - 16.0f, 1.0f),
                                                       std::max(available.y - 16.0f, 1.0f))
                                : 0;
  std::string key = state.document->path + "|" + layout.id + "|" + std::to_string(columns);
  if (on_map) {
    const SomatosensoryMap& map = *state.analysis.somatosensory.map;
    key += "|map " + state.analysis.somatosensory.key + " " + map.source + " " +
           std::to_string(map.samples);
  }
  if (drawing.key != key) {
    drawing = {};
    drawing.key = key;
    drawing.columns = columns;
    if (strip) drawing.rows = strip_in_rows(layout, columns);
    // The somatosensory map's dots keep their size: their neighbours are wherever MDS put them.
    if (!on_map)
      drawing.neighbour_distances = nearest_taxel_distances(drawing.rows ? *drawing.rows : layout);
    drawing.regions = body_regions(state.document->layout);
  }
  return drawing.rows ? *drawing.rows : layout;
}

}  // namespace

void draw_skin_panel_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("skin_panel", size, false);
  const SkinLayout& layout = state.document->layout;
  // Each caption before its box, so that it reads as that box's.
  const auto caption = [](const char* text) {
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(text);
    ImGui::SameLine(0.0f, 4.0f);
  };
  caption("modality");
  ImGui::SetNextItemWidth(100);
  const char* current = layout.modalities.empty()
                            ? ""
                            : layout.modalities[static_cast<size_t>(state.modality)].c_str();
  const bool modalities = ImGui::BeginCombo("##modality", current);
  remember_item(state, "combo:modality",
                "Which of the skin's senses colours the taxels and is plotted");
  if (modalities) {
    for (int k = 0; k < static_cast<int>(layout.modalities.size()); ++k)
      if (ImGui::Selectable(layout.modalities[static_cast<size_t>(k)].c_str(), k == state.modality))
        state.modality = k;
    ImGui::EndCombo();
  }
  ImGui::SameLine(0.0f, 12.0f);
  // The region a new label gets: choose a body part (or click taxels on the skin).
  caption("region");
  ImGui::SetNextItemWidth(90);
  const std::string region = region_of_taxels(layout, state.selection.taxels);
  const bool regions = ImGui::BeginCombo("##region", region.c_str());
  remember_item(
      state, "region",
      "The body part the next label is given (or select taxels on the skin; all: none chosen)");
  if (regions) {
    if (ImGui::Selectable("all", region == "all")) state.selection.taxels.clear();
    for (const Group& group : layout.groups) {
      const std::string name = group.name.empty() ? group.id : group.name + " (" + group.id + ")";
      if (ImGui::Selectable(name.c_str(), region == group.id))
        state.selection.taxels = group.taxels;
      remember_item(state, "region:" + group.id);
    }
    ImGui::EndCombo();
  }
  // A narrow panel wraps its tool row rather than hiding the last tools past its edge.
  const auto same_line_if_room = [](float width) {
    ImGui::SameLine();
    if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
  };
  same_line_if_room(ImGui::GetFrameHeight() + ImGui::CalcTextSize("raw values").x + 12.0f);
  ImGui::Checkbox("raw values", &state.show_raw_values);
  remember_item(
      state, "checkbox:raw values",
      "Colour taxels by their raw values instead of their change from rest beyond the noise");
  same_line_if_room(120.0f);
  // The body as built, or the somatosensory map: taxels placed by how they are touched together.
  ImGui::SetNextItemWidth(120);
  AnalysisState& analysis = state.analysis;
  const char* shown = !analysis.somatosensory.shown   ? "body map"
                      : analysis.somatosensory.corpus ? "somatosensory (all)"
                                                      : "somatosensory";
  const bool maps = ImGui::BeginCombo("##map", shown);
  remember_item(
      state, "map",
      "body map: the skin as built\nsomatosensory: taxels placed by MDS of their correlation\n"
      "distances -ln|R| over this recording (Robovie paper); cached beside it");
  if (maps) {
    if (ImGui::Selectable("body map", !analysis.somatosensory.shown))
      analysis.somatosensory.shown = false;
    remember_item(state, "map:body");
    if (ImGui::Selectable("somatosensory: this recording",
                          analysis.somatosensory.shown && !analysis.somatosensory.corpus))
      analysis.somatosensory.shown = true, analysis.somatosensory.corpus = false;
    remember_item(state, "map:somatosensory");
    if (ImGui::Selectable("somatosensory: every recording of the skin",
                          analysis.somatosensory.shown && analysis.somatosensory.corpus))
      analysis.somatosensory.shown = true, analysis.somatosensory.corpus = true;
    remember_item(state, "map:somatosensory-corpus");
    ImGui::EndCombo();
  }
  double value_min = 0.0, value_max = 1.0;
  const std::vector<float> values = skin_values_now(state, value_min, value_max);
  state.targets.skin_scale = {value_min, value_max};
  SkinViewStyle style;
  style.modality_label = current;
  style.values_are_change = !state.show_raw_values;
  style.zoom = &state.skin_zoom;
  // The selected taxels, and the region of the selected label (a label on "all"
  // outlines nothing).
  std::vector<int64_t> outlined = state.selection.taxels;
  if (!state.selection.labels.empty())
    for (const Label& label : state.document->labels)
      if (label.id == state.selection.labels.front() && label.region != "all")
        for (int64_t taxel : taxels_of_region(layout, label.region)) outlined.push_back(taxel);
  // The segment landed on from a classifier view: its region outlined, both classes named.
  const auto& landed = state.analysis.confusion.landed;
  const bool landed_here = landed && landed->recording == state.document->recording_id();
  if (landed_here && landed->region != "all" && !landed->region.empty())
    for (int64_t taxel : taxels_of_region(layout, landed->region)) outlined.push_back(taxel);
  // A view of `outlined`: taken once it has stopped growing (taken before the landed region
  // was added, it pointed into the freed buffer; found by ASan in the landing test).
  style.selected_taxels = outlined;
  const SkinLayout* drawn = &layout;
  const bool on_map = state.analysis.somatosensory.shown && ensure_somatosensory(state);
  if (on_map) {
    if (!state.analysis.somatosensory.layout ||
        state.analysis.somatosensory.layout->id != layout.id)
      state.analysis.somatosensory.layout =
          layout_on_map(layout, *state.analysis.somatosensory.map);
    // Robovie's 274 dots were 5 pixels across in the default window's panel, too small to tell
    // their colours apart.
    style.min_taxel_pixels = 8.0f;
    drawn = &*state.analysis.somatosensory.layout;
    style.show_group_names = false;
    const SomatosensoryMap& map = *state.analysis.somatosensory.map;
    const SomatosensoryState& somatosensory = state.analysis.somatosensory;
    // In plain words, wrapped at the panel's edge; the method's terms in the tooltip.
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped(
        "Taxels placed by how alike their signals are (MDS of correlations, %lld samples of %s); "
        "colour: body region, white ring: touched now.",
        static_cast<long long>(map.samples), map.source.c_str());
    ImGui::PopStyleColor();
    remember_item(state, "somatosensory:caption");
    if (ImGui::IsItemHovered()) {
      char tip[512];
      std::snprintf(tip, sizeof tip,
                    "%zu taxels placed by classical MDS of the distances -ln|R| between their "
                    "signals\n(R: Pearson correlation over %s).\nShare of the distances no flat "
                    "map can hold (negative eigenvalues): %.2f",
                    map.taxels.size(), map.source.c_str(), map.negative_eigenvalue_ratio);
      view_tooltip(state, tip);
    }
    if (const std::optional<MapBodyAgreement>& agreement = somatosensory.agreement) {
      ImGui::TextColored(ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled),
                         "%d nearest on the map: %.0f %% on the same body part (random: %.0f %%); "
                         "map vs body distance, rank correlation %.2f",
                         agreement->neighbours, 100.0 * agreement->same_part_share,
                         100.0 * agreement->chance_share, agreement->rank_correlation);
      std::vector<std::pair<double, std::string>> parts;
      for (const auto& [part, share] : agreement->part_share) parts.emplace_back(share, part);
      std::sort(parts.rbegin(), parts.rend());
      std::string by_part;
      for (const auto& [share, part] : parts)
        by_part += (by_part.empty() ? "" : ", ") + part + " " +
                   std::to_string(static_cast<int>(std::lround(100.0 * share))) + " %";
      remember_item(state, "somatosensory:agreement",
                    "How far the map keeps the body (Robovie's Figs. 7 and 12 gather the films "
                    "of a body part): the share of each taxel's nearest neighbours on the map "
                    "that lie on its body part, and Spearman's correlation of map and body-map "
                    "distances. By body part: " +
                        by_part);
    }
  } else if (state.analysis.somatosensory.shown) {
    // Computing: the body map meanwhile, the job's progress above it.
    draw_job(state, find_job(state, "somatosensory"), nullptr, "somatosensory map");
  }
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 available = ImGui::GetContentRegionAvail();
  drawn = &skin_drawing_of(state, *drawn, on_map, available);
  style.neighbour_distances = state.skin_drawing.neighbour_distances;
  if (on_map) style.categories = &state.skin_drawing.regions;
  const SkinViewResult result =
      draw_skin_view("skin_view", *drawn, values, value_min, value_max, available, style);
  if (landed_here) {
    const ml::EvaluationResult* evaluation = current_evaluation(state);
    const auto name = [&](int k) {
      return evaluation && k >= 0 && k < static_cast<int>(evaluation->classes.size())
                 ? evaluation->classes[static_cast<size_t>(k)]
                 : std::string("unknown");
    };
    const std::string text = "true " + name(landed->truth) + "   predicted " +
                             name(landed->predicted) + "   (" + landed->region + ")";
    ImDrawList& draw = *ImGui::GetWindowDrawList();
    const ImVec2 at(origin.x + 8, origin.y + 6);
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    const bool wrong = landed->truth != landed->predicted;
    draw.AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + extent.x + 4, at.y + extent.y + 2),
                       wrong ? IM_COL32(120, 30, 25, 255) : IM_COL32(25, 90, 40, 255), 3.0f);
    draw.AddText(at, IM_COL32(255, 255, 255, 255), text.c_str());
  }
  if (!state.live.model_path.empty() && state.live.shown) {
    // Live: the newest decision, large, in its class's colour.
    const OnlineDecision& decision = *state.live.shown;
    char text[160];
    std::snprintf(text, sizeof text, "%s%s  %.0f%%", decision.class_name.c_str(),
                  decision.final ? "" : "...", 100.0 * decision.score);
    ImDrawList& draw = *ImGui::GetWindowDrawList();
    ImFont* font = ImGui::GetFont();
    float text_size = std::min(48.0f, std::max(16.0f, available.y / 10.0f));
    ImVec2 extent = font->CalcTextSizeA(text_size, FLT_MAX, 0.0f, text);
    if (extent.x > available.x - 24.0f) {  // smaller rather than cut off
      text_size *= (available.x - 24.0f) / extent.x;
      extent = font->CalcTextSizeA(text_size, FLT_MAX, 0.0f, text);
    }
    const ImVec2 at(origin.x + (available.x - extent.x) * 0.5f,
                    origin.y + available.y - extent.y - 10.0f);
    const uint32_t colour = decision.class_name == kNoTouchClass
                                ? IM_COL32(90, 90, 90, 230)
                                : class_colour(state, decision.class_name, 230);
    // (an unfinished touch is marked "...": its final answer comes when it ends)
    draw.AddRectFilled(ImVec2(at.x - 10, at.y - 4),
                       ImVec2(at.x + extent.x + 10, at.y + extent.y + 4), colour, 6.0f);
    draw.AddText(font, text_size, at, IM_COL32(255, 255, 255, 255), text);
  }
  state.targets.skin_map = to_rect(origin, ImVec2(origin.x + available.x, origin.y + available.y));
  for (size_t index = 0; index < drawn->taxels.size(); ++index) {
    const Taxel& taxel = drawn->taxels[index];
    const ImVec2 centre = result.transform.apply(taxel.position);
    state.targets.taxels[taxel.id] = {centre.x, centre.y};
    if (index < result.taxels.size())
      state.targets.taxel_boxes[taxel.id] =
          to_rect(result.taxels[index].min, result.taxels[index].max);
  }
  state.targets.touched_taxels = result.touched_taxels;
  for (const SkinViewLabel& name : result.names)
    state.targets.skin_names.emplace_back(name.id, to_rect(name.box.min, name.box.max));
  for (const SkinViewLabel& entry : result.legend)
    remember_legend(state, "somatosensory", entry.id, entry.box.min,
                    entry.box.max.x - entry.box.min.x);
  if (result.clicked_taxel >= 0) {
    select_taxel(state, result.clicked_taxel, ImGui::GetIO().KeyShift);
    toggle_taxel_channel(state, result.clicked_taxel);
  }
  select_in_rectangle(state, *drawn, result, origin, available);
  ImGui::EndChild();
}

void draw_somatosensory_view(WorkbenchState& state, ImVec2 size) {
  const bool was = state.analysis.somatosensory.shown;
  state.analysis.somatosensory.shown = true;
  draw_skin_panel_view(state, size);
  state.analysis.somatosensory.shown = was;
}

}  // namespace tactile

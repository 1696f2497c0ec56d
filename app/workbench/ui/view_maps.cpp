// The feature scatter (the table on its first two principal components, coloured by
// class, misclassified rows ringed; a click goes to the segment) and the SOM region map
// (flux paper Fig. 9: each neuron coloured by its class, the rows' winners marked,
// U-matrix shading on request; a click on a neuron lists its segments).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "confusion.h"
#include "jobs.h"
#include "results.h"
#include "table_maps.h"
#include "tactile/widgets/signal_plot.h"
#include "views.h"

namespace tactile {

namespace {

// The table's classes in the display order of the skin's vocabulary, as the lanes list them.
void draw_legend(WorkbenchState& state, const char* view, std::vector<std::string> classes,
                 ImVec2 at) {
  for (const std::string& name : classes) class_colour(state, name);  // places every class
  const std::vector<std::string>& order = state.class_colours.order();
  const auto place = [&order](const std::string& name) {
    return std::find(order.begin(), order.end(), name);
  };
  std::stable_sort(classes.begin(), classes.end(),
                   [&](const std::string& a, const std::string& b) { return place(a) < place(b); });
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const float line = ImGui::GetTextLineHeightWithSpacing();
  for (size_t k = 0; k < classes.size(); ++k) {
    const ImVec2 row(at.x, at.y + line * static_cast<float>(k));
    draw.AddRectFilled(ImVec2(row.x, row.y + 3), ImVec2(row.x + 10, row.y + 13),
                       class_colour(state, classes[k]));
    remember_legend(state, view, classes[k], ImVec2(row.x, row.y + 3), 10.0f);
    draw.AddText(ImVec2(row.x + 14, row.y), IM_COL32(220, 220, 220, 255), classes[k].c_str());
    const ImVec2 text = ImGui::CalcTextSize(classes[k].c_str());
    remember_box(state, std::string("legend-row:") + view + ":" + classes[k], row,
                 ImVec2(row.x + 14 + text.x, row.y + text.y));
  }
}

// The legend's width: its longest class name's, up to 45 % of the view (130 pixels cut names
// of Robovie's scenario stages off).
float legend_width_for(const std::vector<std::string>& classes, float available) {
  float widest = 0.0f;
  for (const std::string& name : classes)
    widest = std::max(widest, ImGui::CalcTextSize(name.c_str()).x);
  return std::min(std::max(100.0f, widest + 14.0f + 16.0f), 0.45f * available);
}

// The prediction of a dataset row in the current evaluation, for landing on it.
std::optional<ml::RowPrediction> prediction_of(const WorkbenchState& state, int64_t row) {
  const std::vector<RowOutcome> outcomes = row_outcomes(state);
  if (row >= 0 && row < static_cast<int64_t>(outcomes.size()) &&
      outcomes[static_cast<size_t>(row)].prediction)
    return *outcomes[static_cast<size_t>(row)].prediction;
  const Dataset& dataset = *state.analysis.results.dataset;
  ml::RowPrediction prediction = ml::row_place(dataset, row);
  const std::vector<std::string> classes = dataset.class_names();
  const auto truth =
      std::find(classes.begin(), classes.end(), dataset.classes[static_cast<size_t>(row)]);
  prediction.truth = prediction.predicted = static_cast<int>(truth - classes.begin());
  return prediction;
}

}  // namespace

void draw_scatter_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("scatter_view", size, false);
  AnalysisState& analysis = state.analysis;
  if (!analysis.results.dataset || !ensure_scatter(state)) {
    if (!draw_job(state, find_job(state, "scatter"), &analysis.scatter.held, "scatter"))
      ImGui::TextDisabled("No feature table: train in the Model tab, or open one with --features.");
    ImGui::EndChild();
    return;
  }
  const Dataset& dataset = *analysis.results.dataset;
  const std::vector<std::string> classes = dataset.class_names();
  const std::vector<RowOutcome> outcomes = row_outcomes(state);
  int64_t wrong = 0;
  for (const RowOutcome& outcome : outcomes)
    wrong += outcome.tested && outcome.truth != outcome.predicted;
  ImGui::TextWrapped(
      "PCA of %lld rows x %lld features: PC1-PC2 explain %.0f %%   %lld misclassified (ringed)",
      static_cast<long long>(dataset.rows()), static_cast<long long>(dataset.features.cols()),
      100.0 * analysis.scatter.explained, static_cast<long long>(wrong));
  remember_box(state, "text:scatter-header", ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 available = ImGui::GetContentRegionAvail();
  const float legend_width = legend_width_for(classes, available.x);
  const ImVec2 plot(std::max(50.0f, available.x - legend_width), std::max(50.0f, available.y));
  ImGui::InvisibleButton("scatter", plot);
  remember_item(state, "scatter");
  const bool clicked = ImGui::IsItemClicked();
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  draw.AddRectFilled(origin, ImVec2(origin.x + plot.x, origin.y + plot.y),
                     IM_COL32(22, 22, 26, 255));
  const Eigen::MatrixXd& xy = analysis.scatter.points;
  const double x0 = xy.col(0).minCoeff(), x1 = xy.col(0).maxCoeff();
  const double y0 = xy.col(1).minCoeff(), y1 = xy.col(1).maxCoeff();
  const float margin = 14.0f;
  const auto to_screen = [&](Eigen::Index row) {
    const double u = x1 > x0 ? (xy(row, 0) - x0) / (x1 - x0) : 0.5;
    const double v = y1 > y0 ? (xy(row, 1) - y0) / (y1 - y0) : 0.5;
    return ImVec2(origin.x + margin + static_cast<float>(u) * (plot.x - 2 * margin),
                  origin.y + plot.y - margin - static_cast<float>(v) * (plot.y - 2 * margin));
  };
  draw.AddText(ImVec2(origin.x + plot.x - 40, origin.y + plot.y - 18), IM_COL32(150, 150, 150, 255),
               "PC1");
  draw.AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(150, 150, 150, 255), "PC2");
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  Eigen::Index nearest = -1;
  float nearest_distance = 10.0f * 10.0f;
  for (Eigen::Index row = 0; row < xy.rows(); ++row) {
    const ImVec2 point = to_screen(row);
    draw.AddCircleFilled(point, 3.5f,
                         class_colour(state, dataset.classes[static_cast<size_t>(row)], 220));
    const RowOutcome& outcome = outcomes[static_cast<size_t>(row)];
    if (outcome.tested && outcome.truth != outcome.predicted)
      draw.AddCircle(point, 7.0f, IM_COL32(255, 80, 60, 255), 0, 1.8f);
    const float dx = point.x - mouse.x, dy = point.y - mouse.y;
    if (dx * dx + dy * dy < nearest_distance) nearest_distance = dx * dx + dy * dy, nearest = row;
    state.targets.items["point:" + std::to_string(row)] = {point.x - 3, point.y - 3, point.x + 4,
                                                           point.y + 4};
  }
  if (nearest >= 0 && ImGui::IsItemHovered()) {
    const ImVec2 point = to_screen(nearest);
    draw.AddCircle(point, 9.0f, IM_COL32(255, 255, 255, 255), 0, 1.5f);
    const auto row = static_cast<size_t>(nearest);
    const RowOutcome& outcome = outcomes[row];
    const ml::EvaluationResult* result = current_evaluation(state);
    std::string predicted = "-";
    if (outcome.tested && result)
      predicted = outcome.predicted >= 0 ? result->classes[static_cast<size_t>(outcome.predicted)]
                                         : "unknown";
    view_tooltip(state, dataset.recordings[row] + "  segment " +
                            std::to_string(dataset.segment_ids[row]) + "\nclass " +
                            dataset.classes[row] + ", predicted " + predicted +
                            "\nclick: go to the segment");
    if (clicked)
      if (auto prediction = prediction_of(state, nearest)) land_on(state, *prediction);
  }
  draw_legend(state, "scatter", classes, ImVec2(origin.x + plot.x + 10, origin.y));
  ImGui::EndChild();
}

void draw_som_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("som_view", size, false);
  AnalysisState& analysis = state.analysis;
  if (!ensure_som(state)) {
    if (!draw_job(state, find_job(state, "som"), &analysis.som.held, "SOM map"))
      ImGui::TextDisabled(
          "No SOM: train (the map is fitted on the feature table), or open --model.");
    ImGui::EndChild();
    return;
  }
  const ml::SomMap& map = analysis.som.model->map();
  const std::vector<std::string>& classes = analysis.som.classes;
  // The check box first and the words wrapped after it: at the end of the line it ran off a
  // narrow view.
  ImGui::Checkbox("U-matrix", &analysis.som.u_matrix);
  remember_item(state, "U-matrix",
                "Shade each neuron by its distance to its neighbours: dark valleys are clusters");
  ImGui::SameLine();
  ImGui::TextWrapped("SOM %d x %d: neurons coloured by their class, each row a dot on its winner",
                     map.rows, map.columns);
  if (analysis.som.quality)
    ImGui::TextDisabled("quantisation error %.3g, topographic error %.0f %%",
                        analysis.som.quality->quantisation_error,
                        100.0 * analysis.som.quality->topographic_error);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 available = ImGui::GetContentRegionAvail();
  const float legend_width = legend_width_for(classes, available.x);
  const float list_height = analysis.som.neuron >= 0 ? std::min(140.0f, available.y * 0.3f) : 0.0f;
  const float cell = std::max(8.0f, std::min((available.x - legend_width) / map.columns,
                                             (available.y - list_height - 8) / map.rows));
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  // U-matrix: each neuron's mean weight distance to its grid neighbours, once per map (a
  // neuron of a wide table has tens of thousands of weights).
  if (analysis.som.spread_for != analysis.som.model.get()) {
    analysis.som.spread = ml::som_u_matrix(map);
    analysis.som.spread_for = analysis.som.model.get();
  }
  const std::vector<double>& spread = analysis.som.spread;
  const double spread_max =
      std::max(1e-12, spread.empty() ? 0.0 : *std::max_element(spread.begin(), spread.end()));
  const std::vector<RowOutcome> outcomes = row_outcomes(state);
  for (int y = 0; y < map.rows; ++y)
    for (int x = 0; x < map.columns; ++x) {
      const int k = y * map.columns + x;
      const ImVec2 low(origin.x + x * cell, origin.y + y * cell);
      const ImVec2 high(low.x + cell - 2, low.y + cell - 2);
      const int owner = map.neuron_class[static_cast<size_t>(k)];
      ImU32 fill = owner >= 0 && owner < static_cast<int>(classes.size())
                       ? class_colour(state, classes[static_cast<size_t>(owner)], 200)
                       : IM_COL32(60, 60, 60, 255);
      draw.AddRectFilled(low, high, fill, 3.0f);
      if (analysis.som.u_matrix) {  // dark where the map folds: the borders between regions
        const auto shade = static_cast<int>(200.0 * spread[static_cast<size_t>(k)] / spread_max);
        draw.AddRectFilled(low, high, IM_COL32(0, 0, 0, shade), 3.0f);
      }
      if (analysis.som.neuron == k)
        draw.AddRect(low, high, IM_COL32(255, 255, 255, 255), 3.0f, 0, 3.0f);
      ImGui::SetCursorScreenPos(low);
      ImGui::PushID(k);
      if (ImGui::InvisibleButton("neuron", ImVec2(cell - 2, cell - 2))) analysis.som.neuron = k;
      ImGui::PopID();
      remember_item(state, "neuron:" + std::to_string(k));
      if (ImGui::IsItemHovered()) {
        char tip[256];
        std::snprintf(tip, sizeof tip, "neuron %d (%d, %d): %s, %d training wins", k, x, y,
                      owner >= 0 ? classes[static_cast<size_t>(owner)].c_str() : "unlabelled",
                      k < static_cast<int>(map.hits.size()) ? map.hits[static_cast<size_t>(k)] : 0);
        view_tooltip(state, tip);
      }
    }
  // The rows' winners: a dot per row in its true class's colour, spread inside the neuron,
  // ringed red when the evaluation got it wrong.
  std::vector<int> placed(static_cast<size_t>(map.rows * map.columns), 0);
  for (size_t row = 0; row < analysis.som.winners.size(); ++row) {
    const int k = analysis.som.winners[row];
    const int n = placed[static_cast<size_t>(k)]++;
    const float angle = 2.399963f * static_cast<float>(n);  // golden angle: a sunflower spiral
    const float radius = std::min(cell * 0.38f, 3.6f * std::sqrt(static_cast<float>(n)));
    const ImVec2 centre(origin.x + (k % map.columns + 0.5f) * cell - 1 + radius * std::cos(angle),
                        origin.y + (k / map.columns + 0.5f) * cell - 1 + radius * std::sin(angle));
    draw.AddCircleFilled(centre, 3.8f, class_colour(state, analysis.results.dataset->classes[row]));
    draw.AddCircle(centre, 3.8f, IM_COL32(255, 255, 255, 220));
    if (row < outcomes.size() && outcomes[row].tested &&
        outcomes[row].truth != outcomes[row].predicted)
      draw.AddCircle(centre, 6.5f, IM_COL32(255, 60, 40, 255), 0, 2.0f);
  }
  draw_legend(state, "som", classes, ImVec2(origin.x + map.columns * cell + 10, origin.y));
  ImGui::SetCursorScreenPos(ImVec2(origin.x, origin.y + map.rows * cell + 4));
  if (analysis.som.neuron >= 0 && analysis.results.dataset) {
    ImGui::Text("neuron %d wins:", analysis.som.neuron);
    ImGui::BeginChild("neuron_rows", ImVec2(0, list_height), true);
    const Dataset& dataset = *analysis.results.dataset;
    for (size_t row = 0; row < analysis.som.winners.size(); ++row) {
      if (analysis.som.winners[row] != analysis.som.neuron) continue;
      const std::string text = dataset.recordings[row] + "  segment " +
                               std::to_string(dataset.segment_ids[row]) + "  " +
                               dataset.classes[row] + "##" + std::to_string(row);
      if (ImGui::Selectable(text.c_str()))
        if (auto prediction = prediction_of(state, static_cast<int64_t>(row)))
          land_on(state, *prediction);
    }
    ImGui::EndChild();
  }
  ImGui::EndChild();
}

}  // namespace tactile

// Model panel: choose features, segments, classifier and protocol; Run or Train all in
// the background (progress, Cancel); the results as a sortable table whose selected row
// the confusion, scatter and SOM views show.
#include <algorithm>
#include <numeric>

#include "jobs.h"
#include "model_panel.h"
#include "results.h"
#include "tactile/features/feature_extractor.h"
#include "views.h"

namespace tactile {

namespace {

void draw_choices(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  const std::string own = state.document ? default_pipeline(state.document->layout.id) : "generic";
  const std::string shown =
      analysis.panel.pipeline.empty() ? own + " (the skin's own)" : analysis.panel.pipeline;
  ImGui::SetNextItemWidth(180);
  const bool features = ImGui::BeginCombo("features", shown.c_str());
  remember_item(state, "features",
                "The feature set computed from each segment (each paper's own, or generic)");
  if (features) {
    if (ImGui::Selectable((own + " (the skin's own)").c_str(), analysis.panel.pipeline.empty()))
      analysis.panel.pipeline.clear();
    for (const std::string& name : feature_pipelines()) {
      if (ImGui::Selectable(name.c_str(), analysis.panel.pipeline == name))
        analysis.panel.pipeline = name;
      remember_item(state, "pipeline:" + name);
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::InputTextWithHint("##pipeline-params", "parameters", analysis.panel.pipeline_params.data(),
                           analysis.panel.pipeline_params.size());
  remember_item(state, "input:pipeline-params",
                "The feature set's parameters, key=value,... (tactile features --describe NAME "
                "lists them); e.g. share=0.5 for grid on people's touches (docs/FEATURES.md)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(130);
  const bool segments = ImGui::BeginCombo("segments", to_string(analysis.panel.segments));
  remember_item(state, "combo:segments",
                "Which labels are the segments to learn from and their classes");
  if (segments) {
    for (LabelSource source : {LabelSource::kGroundTruth, LabelSource::kManual,
                               LabelSource::kSegmenter, LabelSource::kModel})
      if (ImGui::Selectable(to_string(source), analysis.panel.segments == source))
        analysis.panel.segments = source;
    ImGui::EndCombo();
  }
  ImGui::SetNextItemWidth(180);
  ImGui::InputText("classifier", analysis.panel.classifier.data(),
                   analysis.panel.classifier.size());
  remember_item(
      state, "classifier",
      "A classifier specification (name[:key=value,...]); the list beside has every preset");
  ImGui::SameLine();
  const bool presets = ImGui::BeginCombo("##presets", "", ImGuiComboFlags_NoPreview);
  remember_item(state, "combo:presets", "Every classifier preset, with what it is");
  if (presets) {
    for (const ml::ClassifierEntry& entry : ml::classifier_catalog()) {
      if (ImGui::Selectable(entry.name.c_str())) {
        analysis.panel.classifier.fill('\0');
        std::copy_n(entry.name.begin(),
                    std::min(entry.name.size(), analysis.panel.classifier.size() - 1),
                    analysis.panel.classifier.begin());
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", entry.description.c_str());
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::InputText("protocol", analysis.panel.protocol.data(), analysis.panel.protocol.size());
  remember_item(state, "input:protocol",
                "How rows are split for testing: kfold:K[xR] | loo | loso | holdout:FxR | "
                "split:TRAIN_QUERY/TEST_QUERY");
}

void draw_run_controls(WorkbenchState& state) {
  AnalysisState& analysis = state.analysis;
  AnyJob* training = running_job(state, "training");
  const bool running = training != nullptr;
  ImGui::BeginDisabled(running || !state.document);
  if (ImGui::Button("Run")) start_training(state, analysis.panel.classifier.data());
  remember_item(state, "button:Run",
                "Evaluate the classifier in the box and fit it on every row (Predict uses it)");
  ImGui::SameLine();
  if (ImGui::Button("Train all")) start_training(state, "all");
  remember_item(state, "button:Train all",
                "Evaluate every preset on this skin's labels and show the best");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(running || !can_predict(state));
  if (ImGui::Button("Predict")) predict_open_recording(state);
  ImGui::EndDisabled();
  remember_item(
      state, "button:Predict",
      can_predict(state)
          ? "Predict this recording's segments with the classifier of the row shown (fitted "
            "on every row first when it has no model yet): the prediction lane; U goes to "
            "the least sure, Y confirms, a digit corrects"
          : "Run one classifier or Train all first: a model predicts this recording");
  if (running) {
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) training->cancel();
    remember_item(state, "button:Cancel", "Stop the training run");
    ImGui::SameLine();
    draw_job_progress(*training);
  }
}

void draw_results_table(WorkbenchState& state, float height) {
  AnalysisState& analysis = state.analysis;
  if (analysis.results.rows.empty()) {
    ImGui::TextDisabled(
        "No results yet: Run one classifier, or Train all to compare every preset.");
    return;
  }
  ImGui::Text("%s", analysis.results.from.c_str());
  const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_RowBg |
                                ImGuiTableFlags_BordersOuter | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_Resizable;
  // The classifier's column as wide as its longest name ("coarse-gaussian-svm" was cut when the
  // four columns shared the width); the numbers share the rest. A table keeps the widths of its
  // first frame, and Train all's results arrive one by one: a longer name makes it afresh.
  float names = ImGui::CalcTextSize("classifier").x;
  for (const ml::PresetOutcome& outcome : analysis.results.rows)
    names = std::max(names, ImGui::CalcTextSize(outcome.classifier.c_str()).x);
  analysis.results.name_width = std::max(analysis.results.name_width, names);
  const std::string table_id =
      "results##" + std::to_string(static_cast<int>(analysis.results.name_width));
  if (!ImGui::BeginTable(table_id.c_str(), 4, flags, ImVec2(0, height))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("classifier", ImGuiTableColumnFlags_WidthFixed,
                          analysis.results.name_width + 8.0f);
  ImGui::TableSetupColumn(
      "accuracy", ImGuiTableColumnFlags_DefaultSort | ImGuiTableColumnFlags_PreferSortDescending);
  ImGui::TableSetupColumn("mean recall", ImGuiTableColumnFlags_PreferSortDescending);
  ImGui::TableSetupColumn("time (s)");
  ImGui::TableHeadersRow();
  if (ImGuiTableSortSpecs* specs = ImGui::TableGetSortSpecs(); specs && specs->SpecsCount > 0) {
    analysis.results.sort_column = specs->Specs[0].ColumnIndex;
    analysis.results.sort_ascending = specs->Specs[0].SortDirection == ImGuiSortDirection_Ascending;
  }
  const auto key = [&](const ml::PresetOutcome& outcome) -> double {
    if (!outcome.result) return -1.0;
    switch (analysis.results.sort_column) {
      case 2:
        return ml::mean_recall(*outcome.result);
      case 3:
        return outcome.result->seconds;
      default:
        return outcome.result->accuracy;
    }
  };
  std::vector<size_t> order(analysis.results.rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const ml::PresetOutcome& x = analysis.results.rows[a];
    const ml::PresetOutcome& y = analysis.results.rows[b];
    if (analysis.results.sort_column == 0)
      return analysis.results.sort_ascending ? x.classifier < y.classifier
                                             : x.classifier > y.classifier;
    if (x.result.has_value() != y.result.has_value()) return x.result.has_value();
    return analysis.results.sort_ascending ? key(x) < key(y) : key(x) > key(y);
  });
  for (size_t index : order) {
    const ml::PresetOutcome& outcome = analysis.results.rows[index];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const bool selected = static_cast<int>(index) == analysis.results.current;
    const ImVec2 at = ImGui::GetCursorScreenPos();
    remember_box(
        state, "result-cell:" + outcome.classifier, at,
        ImVec2(at.x + ImGui::GetContentRegionAvail().x, at.y + ImGui::GetTextLineHeight()));
    const ImVec2 extent = ImGui::CalcTextSize(outcome.classifier.c_str());
    remember_box(state, "result-name:" + outcome.classifier, at,
                 ImVec2(at.x + extent.x, at.y + extent.y));
    if (ImGui::Selectable(outcome.classifier.c_str(), selected,
                          ImGuiSelectableFlags_SpanAllColumns) &&
        outcome.result)
      choose_result(state, static_cast<int>(index));
    remember_item(state, "result:" + outcome.classifier);
    if (!outcome.result) {
      ImGui::TableNextColumn();
      ImGui::TextDisabled("skipped");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", outcome.skipped.c_str());
      continue;
    }
    ImGui::TableNextColumn();
    ImGui::Text("%.1f %%", 100.0 * outcome.result->accuracy);
    ImGui::TableNextColumn();
    ImGui::Text("%.1f %%", 100.0 * ml::mean_recall(*outcome.result));
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", outcome.result->seconds);
  }
  ImGui::EndTable();
}

}  // namespace

void draw_model_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("model_view", size, false);
  draw_choices(state);
  draw_run_controls(state);
  ImGui::Separator();
  draw_results_table(state, std::max(80.0f, ImGui::GetContentRegionAvail().y));
  ImGui::EndChild();
}

}  // namespace tactile

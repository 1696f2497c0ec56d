// Quality view: the open recording's label issues (overlaps in a lane and region,
// implausible durations, segmenter events without a label, classes outside the
// vocabulary) and the agreement of two lanes (kappa over time, segment F1 at IoU 0.5,
// the disagreements; and B's segments scored as touches against A's, frame F1 and one-to-one
// event F1 with the touches split and merged, as `tactile segment --score`); a click on an
// issue or a disagreement moves the cursor there.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tactile/labels/agreement.h"
#include "tactile/labels/quality.h"
#include "tactile/segment/scoring.h"
#include "views.h"

namespace tactile {

namespace {

// Moves the cursor (and the plot, when the place is outside it) to [t0, t1).
void go_to(WorkbenchState& state, double t0, double t1, int64_t label) {
  state.clock.seek(t0);
  if (t0 < state.plot.view_t0 || t1 > state.plot.view_t1) {
    const double span = std::max(state.plot.view_t1 - state.plot.view_t0, (t1 - t0) * 3);
    state.plot.view_t0 = (t0 + t1) / 2 - span / 2;
    state.plot.view_t1 = state.plot.view_t0 + span;
  }
  state.selection.labels.clear();
  if (label != 0) state.selection.labels.push_back(label);
}

bool lane_combo(WorkbenchState& state, const char* name, const Lanes& lanes, int& chosen) {
  const std::string current = chosen >= 0 && chosen < static_cast<int>(lanes.keys.size())
                                  ? lanes.keys[static_cast<size_t>(chosen)].title()
                                  : "-";
  bool changed = false;
  ImGui::SetNextItemWidth(120);
  const bool open = ImGui::BeginCombo(name, current.c_str());
  remember_item(state, std::string("combo:") + name,
                "One of the two lanes whose agreement is measured");
  if (open) {
    for (size_t k = 0; k < lanes.keys.size(); ++k)
      if (ImGui::Selectable(lanes.keys[k].title().c_str(), static_cast<int>(k) == chosen)) {
        chosen = static_cast<int>(k);
        changed = true;
      }
    ImGui::EndCombo();
  }
  return changed;
}

}  // namespace

void draw_quality_view(WorkbenchState& state, ImVec2 size) {
  ImGui::BeginChild("quality_view", size, false);
  const Document& document = *state.document;
  WorkbenchState::QualityCache& cache = state.quality;
  const Lanes& lanes = document.lanes;
  int& a = state.quality_lanes.first;
  int& b = state.quality_lanes.second;
  if (a < 0 || a >= static_cast<int>(lanes.keys.size())) a = 0;
  if (b < 0 || b >= static_cast<int>(lanes.keys.size())) b = 1;
  if (cache.document != &document || cache.labels_version != document.labels_version ||
      cache.lanes != state.quality_lanes) {
    QualityOptions options;
    options.vocabulary = {document.classes.begin(), document.classes.end()};
    // The open recording's labels against its samples (a live buffer is no recording's span).
    if (!state.live.connected) {
      const SourceInfo& info = document.samples().info();
      const bool regular = document.samples().timestamps() == nullptr && info.rate_hz > 0.0;
      options.spans[info.recording_id] = {document.samples().start_time(),
                                          document.samples().end_time(),
                                          regular ? 1.0 / info.rate_hz : 0.0};
    }
    cache.issues = check_labels(document.labels, options);
    cache.agreement = {};
    cache.touches = {};
    if (lanes.keys.size() >= 2) {
      const SourceInfo& info = document.samples().info();
      const std::map<std::string, RecordingTiming> timing = {
          {info.recording_id,
           {document.samples().start_time(), document.samples().end_time(), info.rate_hz}}};
      cache.agreement = compute_agreement(lanes.lanes[static_cast<size_t>(a)].labels(),
                                          lanes.lanes[static_cast<size_t>(b)].labels(), timing);
      const auto frames = static_cast<int64_t>(std::llround(
          (document.samples().end_time() - document.samples().start_time()) * info.rate_hz));
      cache.touches = score_touches(lanes.lanes[static_cast<size_t>(b)].labels(),
                                    lanes.lanes[static_cast<size_t>(a)].labels(),
                                    document.samples().start_time(), info.rate_hz, frames);
    }
    cache.document = &document;
    cache.labels_version = document.labels_version;
    cache.lanes = state.quality_lanes;
  }
  const std::vector<LabelIssue>& issues = cache.issues;
  ImGui::Text("%zu issue%s", issues.size(), issues.size() == 1 ? "" : "s");
  remember_item(state, "quality:issues");
  for (size_t k = 0; k < issues.size() && k < 200; ++k) {
    const LabelIssue& issue = issues[k];
    ImGui::PushID(static_cast<int>(k));
    char text[96];
    std::snprintf(text, sizeof(text), "%s %s", format_seconds(issue.t0).c_str(),
                  issue.kind.c_str());
    if (ImGui::Selectable(text)) go_to(state, issue.t0, issue.t1, issue.label);
    remember_item(state, "quality:issue:" + std::to_string(k));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", issue.what.c_str());
    ImGui::PopID();
  }
  ImGui::Separator();
  // Agreement of two lanes: the first two by default (ground truth and an annotator).
  if (lanes.keys.size() < 2) {
    ImGui::TextDisabled("Agreement needs two lanes.");
    ImGui::EndChild();
    return;
  }
  lane_combo(state, "A##agreement_a", lanes, a);
  lane_combo(state, "B##agreement_b", lanes, b);
  const Agreement& agreement = cache.agreement;
  ImGui::Text("kappa %.3f   F1 %.3f", agreement.kappa, agreement.f1);
  ImGui::TextDisabled("P %.2f R %.2f, %lld matched", agreement.precision, agreement.recall,
                      static_cast<long long>(agreement.matched));
  // B's segments as touches against A's (a segmenter's lane against labelled touches).
  const TouchScore& touches = cache.touches;
  ImGui::Text("touches F1 %.3f / %.3f", touches.frames.f1(), touches.events.f1());
  remember_item(state, "quality:touches",
                "B's segments scored against A's touches: frame F1 / one-to-one event F1 "
                "(docs/SEGMENTERS.md)");
  ImGui::TextDisabled("%lld of %lld found, %lld extra", static_cast<long long>(touches.events.hits),
                      static_cast<long long>(touches.touches),
                      static_cast<long long>(touches.events.false_alarms));
  ImGui::TextDisabled("%lld split, %lld merged", static_cast<long long>(touches.split),
                      static_cast<long long>(touches.merged));
  for (size_t k = 0; k < agreement.disagreements.size() && k < 200; ++k) {
    const Disagreement& d = agreement.disagreements[k];
    ImGui::PushID(1000 + static_cast<int>(k));
    char text[128];
    if (d.kind == "class")
      std::snprintf(text, sizeof(text), "%s %s/%s", format_seconds(d.t0).c_str(), d.a_class.c_str(),
                    d.b_class.c_str());
    else
      std::snprintf(text, sizeof(text), "%s only %s: %s", format_seconds(d.t0).c_str(),
                    d.kind == "missed" ? "A" : "B",
                    (d.kind == "missed" ? d.a_class : d.b_class).c_str());
    if (ImGui::Selectable(text)) go_to(state, d.t0, d.t1, 0);
    remember_item(state, "quality:disagreement:" + std::to_string(k));
    ImGui::PopID();
  }
  ImGui::EndChild();
}

}  // namespace tactile

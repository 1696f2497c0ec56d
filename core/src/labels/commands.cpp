#include "tactile/labels/commands.h"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace tactile {

Label adopted_label(const Label& label, const std::string& class_name,
                    const std::string& annotator) {
  Label adopted = label;
  adopted.id = 0;
  adopted.class_name = class_name;
  adopted.annotator = annotator;
  adopted.source = LabelSource::kManual;
  adopted.confidence = 1.0;
  adopted.note.clear();
  if (label.source == LabelSource::kModel)
    adopted.note = (class_name == label.class_name ? "confirmed model: " : "corrected model: ") +
                   label.class_name;
  return adopted;
}

LabelEdit adopt_edit(const Label& label, const std::string& class_name,
                     const std::string& annotator) {
  LabelEdit edit;
  edit.add = {adopted_label(label, class_name, annotator)};
  return edit;
}

LabelEdit add_edit(Label label) {
  LabelEdit edit;
  edit.add = {std::move(label)};
  return edit;
}

LabelEdit remove_edit(const Label& label) {
  LabelEdit edit;
  edit.remove = {ref_of(label)};
  return edit;
}

LabelEdit reject_edit(const Label& suggestion) {
  LabelEdit edit;
  edit.reject = {ref_of(suggestion)};
  return edit;
}

LabelEdit class_edit(Label label, const std::string& class_name) {
  label.class_name = class_name;
  LabelEdit edit;
  edit.update = {std::move(label)};
  return edit;
}

LabelEdit bounds_edit(Label label, double t0, double t1) {
  label.t0 = t0;
  label.t1 = t1;
  LabelEdit edit;
  edit.update = {std::move(label)};
  return edit;
}

namespace {

// The labels the filter finds replaced by `labels`, in one edit.
LabelEdit replacing_import(const LabelStore& store, const LabelFilter& previous,
                           const std::vector<Label>& labels) {
  LabelEdit edit;
  for (const Label& label : store.list(previous)) edit.remove.push_back(ref_of(label));
  edit.add = labels;
  return edit;
}

}  // namespace

LabelEdit ground_truth_import(const LabelStore& store, const std::string& recording,
                              const std::vector<Label>& labels) {
  LabelFilter previous;
  previous.recording = recording;
  previous.source = LabelSource::kGroundTruth;
  return replacing_import(store, previous, labels);
}

LabelEdit annotator_import(const LabelStore& store, const std::string& recording,
                           const std::string& annotator, const std::vector<Label>& labels) {
  LabelFilter previous;
  previous.recording = recording;
  previous.annotator = annotator;
  previous.source = LabelSource::kManual;
  return replacing_import(store, previous, labels);
}

EditSummary summarize_edit(const std::vector<JournalEntry>& rows) {
  EditSummary edit;
  bool spanned = false;
  for (const JournalEntry& row : rows) {
    if (edit.time.empty()) edit.time = row.time, edit.first_sequence = row.sequence;
    const bool before = !row.before_json.empty(), after = !row.after_json.empty();
    if (!before && after)
      ++edit.added;
    else if (before && !after)
      ++edit.removed, edit.rejected += row.action == "reject";
    else
      ++edit.changed;
    for (const std::string* text : {&row.before_json, &row.after_json}) {
      if (text->empty()) continue;
      const nlohmann::json label = nlohmann::json::parse(*text, nullptr, false);
      if (!label.is_object()) continue;
      if (label.contains("annotator") && label["annotator"].is_string()) {
        const std::string lane = label["annotator"];
        if (std::find(edit.lanes.begin(), edit.lanes.end(), lane) == edit.lanes.end())
          edit.lanes.push_back(lane);
      }
      if (label.contains("t0") && label["t0"].is_number() && label.contains("t1") &&
          label["t1"].is_number()) {
        const double t0 = label["t0"], t1 = label["t1"];
        edit.t0 = spanned ? std::min(edit.t0, t0) : t0;
        edit.t1 = spanned ? std::max(edit.t1, t1) : t1;
        spanned = true;
      }
    }
  }
  return edit;
}

std::string describe_edit(const EditSummary& edit) {
  const int labels = edit.added + edit.removed + edit.changed;
  if (edit.rejected > 0 && edit.rejected == labels)
    return "the rejection of " + std::to_string(labels) +
           (labels == 1 ? " suggestion" : " suggestions");
  // A run stores suggestions (and drops the lane's earlier ones); a rejection is said above.
  const bool segmenter =
      edit.lanes.size() == 1 && edit.lanes.front().starts_with("segmenter:") && edit.changed == 0;
  std::string what;
  for (const auto& [n, verb] :
       {std::pair{edit.added, "added"}, {edit.removed, "removed"}, {edit.changed, "changed"}})
    if (n > 0) what += (what.empty() ? "" : " and ") + std::string(verb) + " " + std::to_string(n);
  what += segmenter ? (labels == 1 ? " suggestion" : " suggestions")
                    : (labels == 1 ? " label" : " labels");
  if (segmenter) return edit.lanes.front().substr(10) + "'s segmenter run, which " + what;
  std::string lanes;
  for (const std::string& lane : edit.lanes) lanes += (lanes.empty() ? "" : ", ") + lane;
  return "an edit of " + (lanes.empty() ? std::string("the labels") : lanes) + ", which " + what;
}

}  // namespace tactile

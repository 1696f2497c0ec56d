#include "tactile/labels/commands.h"

namespace tactile {

Label adopted_label(const Label& label, const std::string& class_name, const std::string& annotator) {
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

LabelEdit adopt_edit(const Label& label, const std::string& class_name, const std::string& annotator) {
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

}  // namespace tactile

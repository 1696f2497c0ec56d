#pragma once
// The label commands: every change a user makes to the labels is one LabelEdit (label_store.h),
// written by LabelStore::apply under the person who made it as one journal batch, so that
// undo(that person) takes back exactly that action, whatever lanes it touched, also after a
// restart, and redo puts it back. The workbench's keys, menus and scripts and the command line
// build their edits here (and in suggestions.h, predict.h), so each policy is written once.
//
//   commit a label      add_edit(label)
//   change its class    class_edit(label, class)     a dragged edge: bounds_edit(label, t0, t1)
//   delete              remove_edit(label)
//   accept / confirm    adopt_edit(suggestion or prediction, class, annotator)
//   reject              reject_edit(suggestion)
//   segmenter run       segmenter_run(...).edit          (suggestions.h)
//   predict             prediction_edit(...)             (predict.h)
//   import              ground_truth_import(...), annotator_import(...) (--annotator)

#include <string>
#include <vector>

#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

// A suggestion (a segmenter's label) accepted, or a prediction confirmed or corrected: a label
// of `annotator`'s own lane with its bounds and region, class `class_name`, confidence 1. A
// prediction's copy notes what the model said ("confirmed model: tap", "corrected model: tap").
Label adopted_label(const Label& label, const std::string& class_name,
                    const std::string& annotator);
LabelEdit adopt_edit(const Label& label, const std::string& class_name,
                     const std::string& annotator);

// One label added, removed, or rejected (a suggestion: removed and its span remembered). A
// removal or rejection, like a change below, names the label as its editor last read it (id and
// revision): the store refuses it when someone else changed the label since.
LabelEdit add_edit(Label label);
LabelEdit remove_edit(const Label& label);
LabelEdit reject_edit(const Label& suggestion);

// A changed copy of `label` as an edit of it: its class, or its bounds (a dragged edge).
LabelEdit class_edit(Label label, const std::string& class_name);
LabelEdit bounds_edit(Label label, double t0, double t1);

// What an edit did (or an undo or redo of it), read from its journal rows: labels added,
// removed (or rejected) and changed; whose lanes they were in ("segmenter:threshold", "ana"),
// the span of the recording they cover (t0 > t1 when the rows name no times), and when the
// edit was written (its first row).
struct EditSummary {
  int added = 0, removed = 0, changed = 0;
  int rejected = 0;  // of `removed`: suggestions rejected
  std::vector<std::string> lanes;
  double t0 = 1.0, t1 = 0.0;
  int64_t first_sequence = 0;
  std::string time;
};
EditSummary summarize_edit(const std::vector<JournalEntry>& rows);
// "threshold's segmenter run, which added 12 suggestions", "an edit of ana, which added 1
// label": the edit an undo takes back (or a redo puts back), in words.
std::string describe_edit(const EditSummary& edit);

// Imported ground truth of one recording: the recording's earlier ground truth removed, the
// imported labels added, as one edit (importing the same file again replaces, never doubles).
LabelEdit ground_truth_import(const LabelStore& store, const std::string& recording,
                              const std::vector<Label>& labels);
// The same for one annotator's lane: `annotator`'s earlier labels of the recording (their own,
// kManual) removed and the imported labels added, as one edit.
LabelEdit annotator_import(const LabelStore& store, const std::string& recording,
                           const std::string& annotator, const std::vector<Label>& labels);

}  // namespace tactile

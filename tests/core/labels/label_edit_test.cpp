// LabelStore::apply and the label policies the command line and the workbench share: a
// segmenter run and a prediction are each one edit, which one undo takes back exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>
#include <vector>

#include "label_store_fixture.h"
#include "tactile/error.h"
#include "tactile/labels/commands.h"
#include "tactile/labels/predict.h"
#include "tactile/labels/suggestions.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

using Row = std::tuple<std::string, double, double, std::string, std::string, std::string,
                       std::string, double, std::string>;

// The whole label table, ids and times aside, in a fixed order.
std::vector<Row> table(const LabelStore& store) {
  std::vector<Row> rows;
  for (const Label& label : store.list())
    rows.emplace_back(label.recording, label.t0, label.t1, label.region, label.class_name,
                      label.annotator, to_string(label.source), label.confidence, label.note);
  std::sort(rows.begin(), rows.end());
  return rows;
}

// Labels of one recording whose spans overlap another label of the same lane.
int overlaps(const LabelStore& store) {
  const std::vector<Label> labels = store.list();
  int found = 0;
  for (size_t i = 0; i < labels.size(); ++i)
    for (size_t j = i + 1; j < labels.size(); ++j)
      found += labels[i].recording == labels[j].recording &&
               labels[i].annotator == labels[j].annotator && labels[i].t0 < labels[j].t1 &&
               labels[j].t0 < labels[i].t1;
  return found;
}

// `count` suggestions of segmenter METHOD, 1 s long every 2 s from `offset`, of no class (as a
// segmenter that only finds contacts gives them) unless one is named.
std::vector<Label> suggestions(const std::string& method, int count, double offset = 0.0,
                               const std::string& class_name = "") {
  std::vector<Label> labels;
  for (int k = 0; k < count; ++k) {
    Label label;
    label.recording = "r1";
    label.t0 = offset + 2.0 * k;
    label.t1 = label.t0 + 1.0;
    label.annotator = "segmenter:" + method;
    label.source = LabelSource::kSegmenter;
    label.class_name = class_name;
    labels.push_back(label);
  }
  return labels;
}

TEST_F(LabelStoreTest, AnEditIsOneBatchThatOneUndoTakesBackAndRedoBringsBack) {
  LabelStore store(path_);
  const int64_t kept = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const int64_t changed = store.add(make_label("r1", 2.0, 3.0, "pat"));
  const int64_t gone = store.add(make_label("r1", 4.0, 5.0, "pat"));
  const std::vector<Row> before = table(store);

  LabelEdit edit;
  edit.remove = {{gone, 1}};
  Label update = *store.get(changed);
  update.class_name = "slap";
  edit.update = {update};
  edit.add = {make_label("r1", 6.0, 7.0, "poke", "segmenter:threshold"),
              make_label("r2", 0.0, 1.0, "rub", "model")};
  const std::vector<int64_t> ids = store.apply(edit, "ana");
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_FALSE(store.get(gone));
  EXPECT_EQ(store.get(changed)->class_name, "slap");
  EXPECT_EQ(store.get(ids[0])->annotator, "segmenter:threshold");  // the label keeps its own
  const std::vector<Row> after = table(store);

  // Every journal row of the edit is the editor's, in one batch.
  const std::vector<JournalEntry> journal = store.journal(4);
  ASSERT_EQ(journal.size(), 4u);
  for (const JournalEntry& entry : journal) {
    EXPECT_EQ(entry.annotator, "ana");
    EXPECT_EQ(entry.batch, journal.front().batch);
  }

  store.add(make_label("r1", 9.0, 10.0, "pat", "bo"));  // another annotator's edit on top
  ASSERT_TRUE(store.undo("ana"));
  std::vector<Row> undone = table(store);
  std::erase_if(undone, [](const Row& row) { return std::get<5>(row) == "bo"; });
  EXPECT_EQ(undone, before);
  EXPECT_TRUE(store.get(kept));
  ASSERT_TRUE(store.redo("ana"));
  std::vector<Row> redone = table(store);
  std::erase_if(redone, [](const Row& row) { return std::get<5>(row) == "bo"; });
  EXPECT_EQ(redone, after);
}

TEST_F(LabelStoreTest, AnEditWithABadPartChangesNothing) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const std::vector<Row> before = table(store);
  const int64_t journal_rows = static_cast<int64_t>(store.journal(-1).size());

  LabelEdit missing;
  missing.remove = {{id, 1}, {id + 100, 1}};
  missing.add = {make_label("r1", 2.0, 3.0, "poke")};
  try {
    store.apply(missing, "ana");
    FAIL() << "removing a label that does not exist must throw";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no such label to remove"), std::string::npos)
        << error.what();
  }
  LabelEdit invalid;
  invalid.remove = {{id, 1}};
  invalid.add = {make_label("r1", 3.0, 2.0, "poke")};  // ends before it starts
  EXPECT_THROW(store.apply(invalid, "ana"), Error);

  EXPECT_EQ(table(store), before);
  EXPECT_EQ(static_cast<int64_t>(store.journal(-1).size()), journal_rows);
  EXPECT_TRUE(store.apply(LabelEdit{}, "ana").empty());
}

// The workbench's `G`, `A R` on one suggestion, `G` again, Ctrl+Z: the lane is as it was
// before the second run (it held both runs' suggestions, stacked, before runs were edits).
TEST_F(LabelStoreTest, UndoOfASegmenterRerunRestoresTheLaneBeforeIt) {
  LabelStore store(path_);
  const SegmenterRun first = segmenter_run(store, "r1", "adaptive", suggestions("adaptive", 50));
  store.apply(first.edit, "ana");
  const std::vector<Label> lane = store.list();
  ASSERT_EQ(lane.size(), 50u);
  store.reject(ref_of(lane[6]), "ana");
  const std::vector<Row> before = table(store);

  const SegmenterRun second = segmenter_run(store, "r1", "adaptive", suggestions("adaptive", 50));
  EXPECT_EQ(second.replaced, 49u);
  EXPECT_EQ(second.rejected, 1u);  // the rejected span stays out
  store.apply(second.edit, "ana");
  EXPECT_EQ(store.count("r1"), 49);
  EXPECT_EQ(overlaps(store), 0);

  ASSERT_TRUE(store.undo("ana"));
  EXPECT_EQ(table(store), before);
  EXPECT_EQ(overlaps(store), 0);
  ASSERT_TRUE(store.undo("ana"));  // the rejection
  ASSERT_TRUE(store.undo("ana"));  // the first run
  EXPECT_EQ(store.count("r1"), 0);
  EXPECT_FALSE(store.undo("ana"));
}

// `[ ] 2 Enter` (the operator's label), `G`, Ctrl+Z: the run goes, the label stays.
TEST_F(LabelStoreTest, UndoAfterASegmenterRunTakesBackTheRunNotTheLabelBeforeIt) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.5, 1.5, "poke", "ana"));
  const std::vector<Row> before = table(store);
  store.apply(segmenter_run(store, "r1", "threshold", suggestions("threshold", 5)).edit, "ana");
  EXPECT_EQ(store.count("r1"), 6);
  ASSERT_TRUE(store.undo("ana"));
  EXPECT_EQ(table(store), before);
}

TEST_F(LabelStoreTest, NextUndoIsTheRunThatUndoTakesBackAndItsSummarySaysSo) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.5, 1.5, "poke", "ana"));
  store.apply(segmenter_run(store, "r1", "threshold", suggestions("threshold", 5)).edit, "ana");
  const EditSummary next = summarize_edit(store.next_undo("ana"));
  EXPECT_EQ(next.added, 5);
  EXPECT_EQ(next.removed, 0);
  EXPECT_EQ(next.lanes, std::vector<std::string>{"segmenter:threshold"});
  EXPECT_LE(next.t0, next.t1);
  EXPECT_EQ(describe_edit(next), "threshold's segmenter run, which added 5 suggestions");
  const int64_t before = store.last_sequence();
  ASSERT_TRUE(store.undo("ana"));
  const EditSummary undone = summarize_edit(store.journal_after(before));
  EXPECT_EQ(undone.removed, 5);
  EXPECT_DOUBLE_EQ(undone.t0, next.t0);
  EXPECT_DOUBLE_EQ(undone.t1, next.t1);
  // Then the label before it.
  EXPECT_EQ(describe_edit(summarize_edit(store.next_undo("ana"))),
            "an edit of ana, which added 1 label");
}

TEST_F(LabelStoreTest, ASegmenterRunNamesUnknownClassesAndKeepsOtherMethodsAndLanes) {
  LabelStore store(path_);
  store.add_many(suggestions("threshold", 3, 0.0, kUnknownClass));
  store.add(make_label("r1", 0.0, 1.0, "pat", "ana"));
  store.add_many(suggestions("adaptive", 2, 0.0, kUnknownClass));
  store.add_many(suggestions("adaptive", 2, 100.0, kUnknownClass));

  const SegmenterRun kept = segmenter_run(store, "r1", "adaptive", suggestions("adaptive", 4),
                                          /*replace=*/false);
  EXPECT_TRUE(kept.edit.remove.empty());
  const SegmenterRun run = segmenter_run(store, "r1", "adaptive", suggestions("adaptive", 4));
  EXPECT_EQ(run.annotator, "segmenter:adaptive");
  EXPECT_EQ(run.replaced, 4u);
  for (const LabelRef& seen : run.edit.remove)
    EXPECT_EQ(store.get(seen.id)->annotator, "segmenter:adaptive");
  for (const Label& label : run.edit.add) EXPECT_EQ(label.class_name, kUnknownClass);
  store.apply(run.edit, "ana");
  LabelFilter threshold;
  threshold.annotator = "segmenter:threshold";
  EXPECT_EQ(store.list(threshold).size(), 3u);
  EXPECT_EQ(store.count("r1"), 3 + 1 + 4);
}

TEST_F(LabelStoreTest, APredictionReplacesTheModelLaneOfItsRecordingOnly) {
  LabelStore store(path_);
  auto prediction = [](const std::string& recording, double t0, const std::string& class_name) {
    Label label = make_label(recording, t0, t0 + 1.0, class_name, kModelAnnotator);
    label.source = LabelSource::kModel;
    return label;
  };
  store.add_many(
      {prediction("r1", 0.0, "pat"), prediction("r1", 2.0, "pat"), prediction("r2", 0.0, "rub")});
  store.add(make_label("r1", 0.0, 1.0, "poke", "ana"));
  const std::vector<Row> before = table(store);

  size_t replaced = 0;
  const LabelEdit edit = prediction_edit(store, "r1", {prediction("r1", 0.0, "slap")}, &replaced);
  EXPECT_EQ(replaced, 2u);
  store.apply(edit, "ana");
  LabelFilter model;
  model.source = LabelSource::kModel;
  model.recording = "r1";
  ASSERT_EQ(store.list(model).size(), 1u);
  EXPECT_EQ(store.list(model)[0].class_name, "slap");
  model.recording = "r2";
  EXPECT_EQ(store.list(model).size(), 1u);
  ASSERT_TRUE(store.undo("ana"));
  EXPECT_EQ(table(store), before);
}

TEST(SegmentsToPredict, AreTheSuggestionsElseTheGroundTruthElseNone) {
  Label truth, suggestion, manual;
  truth.source = LabelSource::kGroundTruth;
  suggestion.source = LabelSource::kSegmenter;
  manual.source = LabelSource::kManual;
  EXPECT_EQ(segments_to_predict({truth, suggestion, manual, suggestion}).size(), 2u);
  const std::vector<Label> from_truth = segments_to_predict({manual, truth});
  ASSERT_EQ(from_truth.size(), 1u);
  EXPECT_EQ(from_truth[0].source, LabelSource::kGroundTruth);
  EXPECT_TRUE(segments_to_predict({manual}).empty());
}

}  // namespace
}  // namespace tactile

namespace tactile {
namespace {

// A reject is an edit too: its undo brings the suggestion back and forgets its span (a rerun
// suggests it again), its redo removes it and remembers the span again.
TEST_F(LabelStoreTest, ARejectsUndoForgetsTheRejectionAndItsRedoRemembersIt) {
  LabelStore store(path_);
  store.apply(segmenter_run(store, "r1", "threshold", suggestions("threshold", 3)).edit, "ana");
  const std::vector<Row> before = table(store);
  const int64_t second = store.list()[1].id;
  LabelEdit edit;
  edit.reject = {{second, 1}};
  store.apply(edit, "ana");
  EXPECT_FALSE(store.get(second));
  ASSERT_EQ(store.rejections("r1").size(), 1u);
  EXPECT_EQ(store.journal(1)[0].action, "reject");
  const SegmenterRun rerun = segmenter_run(store, "r1", "threshold", suggestions("threshold", 3));
  EXPECT_EQ(rerun.rejected, 1u);

  ASSERT_TRUE(store.undo("ana"));
  EXPECT_EQ(table(store), before);
  EXPECT_TRUE(store.rejections("r1").empty());
  EXPECT_EQ(segmenter_run(store, "r1", "threshold", suggestions("threshold", 3)).rejected, 0u);

  ASSERT_TRUE(store.redo("ana"));
  EXPECT_FALSE(store.get(second));
  EXPECT_EQ(store.rejections("r1").size(), 1u);
  EXPECT_TRUE(store.check().empty());
  // Not a suggestion: refused, nothing changed.
  const int64_t own = store.add(make_label("r1", 20.0, 21.0, "pat"));
  edit.reject = {{own, 1}};
  EXPECT_THROW(store.apply(edit, "ana"), Error);
  EXPECT_TRUE(store.get(own));
}

// The commands' policies: an adopted suggestion or prediction, an imported ground truth.
TEST_F(LabelStoreTest, AnAdoptedLabelIsTheOperatorsWithTheModelsAnswerInItsNote) {
  Label prediction = make_label("r1", 1.0, 2.0, "tap", "model");
  prediction.id = 7;
  prediction.source = LabelSource::kModel;
  prediction.confidence = 0.4;
  const Label confirmed = adopted_label(prediction, "tap", "ana");
  EXPECT_EQ(confirmed.id, 0);
  EXPECT_EQ(confirmed.source, LabelSource::kManual);
  EXPECT_EQ(confirmed.annotator, "ana");
  EXPECT_EQ(confirmed.confidence, 1.0);
  EXPECT_EQ(confirmed.note, "confirmed model: tap");
  EXPECT_EQ(adopted_label(prediction, "slap", "ana").note, "corrected model: tap");
  Label suggestion = make_label("r1", 1.0, 2.0, "unknown", "segmenter:adaptive");
  suggestion.source = LabelSource::kSegmenter;
  suggestion.note = "quiet";
  const Label accepted = adopted_label(suggestion, "pat", "ana");
  EXPECT_EQ(accepted.class_name, "pat");
  EXPECT_EQ(accepted.note, "");
  EXPECT_EQ(accepted.t0, 1.0);
  EXPECT_EQ(accepted.region, suggestion.region);
}

TEST_F(LabelStoreTest, AnImportReplacesTheRecordingsGroundTruthAsOneEdit) {
  LabelStore store(path_);
  Label truth = make_label("r1", 0.0, 1.0, "pat", "simulator");
  truth.source = LabelSource::kGroundTruth;
  store.add(truth);
  Label other = truth;
  other.recording = "r2";
  store.add(other);
  const std::vector<Row> before = table(store);
  truth.t0 = 5.0, truth.t1 = 6.0;
  store.apply(ground_truth_import(store, "r1", {truth, truth}), "import");
  LabelFilter r1;
  r1.recording = "r1";
  ASSERT_EQ(store.list(r1).size(), 2u);
  EXPECT_EQ(store.list(r1)[0].t0, 5.0);
  ASSERT_TRUE(store.undo("import"));
  EXPECT_EQ(table(store), before);
}

}  // namespace
}  // namespace tactile

// LabelStore: undo, redo and the journal of who did what.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "label_store_fixture.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {
namespace {

TEST_F(LabelStoreTest, UndoOfInsertRemovesItAndRedoBringsBackTheSameId) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const Label added = *store.get(id);
  ASSERT_TRUE(store.undo());
  EXPECT_FALSE(store.get(id));
  ASSERT_TRUE(store.redo());
  const std::optional<Label> back = store.get(id);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->class_name, "pat");
  EXPECT_EQ(back->created, added.created);
  EXPECT_FALSE(store.redo());
}

TEST_F(LabelStoreTest, UndoOfDeleteRestoresTheSameIdAndLaterIdsDoNotReuseIt) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.0, 1.0, "pat"));
  Label newest = make_label("r1", 1.0, 2.0, "poke");
  newest.note = "keep me";
  const int64_t id = store.add(newest);
  store.remove({id, 1}, "bo");
  // The highest id was freed: a fresh add must not take it, or undo could not restore it.
  const int64_t fresh = store.add(make_label("r1", 3.0, 4.0, "rub"));
  EXPECT_GT(fresh, id);
  ASSERT_TRUE(store.undo());  // the add of `fresh`
  ASSERT_TRUE(store.undo());  // the delete
  const std::optional<Label> restored = store.get(id);
  ASSERT_TRUE(restored);
  EXPECT_EQ(restored->note, "keep me");
  EXPECT_EQ(restored->class_name, "poke");
  EXPECT_FALSE(store.get(fresh));
}

TEST_F(LabelStoreTest, UndoOfUpdateRestoresThePreviousFields) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat"));
  Label changed = *store.get(id);
  changed.class_name = "slap";
  changed.t0 = 0.25;
  store.update(changed);
  ASSERT_TRUE(store.undo());
  EXPECT_EQ(store.get(id)->class_name, "pat");
  EXPECT_DOUBLE_EQ(store.get(id)->t0, 0.0);
  ASSERT_TRUE(store.redo());
  EXPECT_EQ(store.get(id)->class_name, "slap");
  EXPECT_DOUBLE_EQ(store.get(id)->t0, 0.25);
}

TEST_F(LabelStoreTest, UndoWalksBackAndRedoForwardInStackOrder) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat"));
  for (const char* name : {"poke", "punch"}) {
    Label changed = *store.get(id);
    changed.class_name = name;
    store.update(changed);
  }
  ASSERT_TRUE(store.undo());
  ASSERT_TRUE(store.undo());
  EXPECT_EQ(store.get(id)->class_name, "pat");
  ASSERT_TRUE(store.redo());
  EXPECT_EQ(store.get(id)->class_name, "poke");
  ASSERT_TRUE(store.redo());
  EXPECT_EQ(store.get(id)->class_name, "punch");
  EXPECT_FALSE(store.redo());
  ASSERT_TRUE(store.undo());
  ASSERT_TRUE(store.undo());
  ASSERT_TRUE(store.undo());
  EXPECT_FALSE(store.get(id));
  EXPECT_FALSE(store.undo());
}

TEST_F(LabelStoreTest, NewEditClearsTheRedoChain) {
  LabelStore store(path_);
  const int64_t first = store.add(make_label("r1", 0.0, 1.0, "pat"));
  ASSERT_TRUE(store.undo());
  const int64_t second = store.add(make_label("r1", 2.0, 3.0, "poke"));
  EXPECT_FALSE(store.redo());
  EXPECT_FALSE(store.get(first));
  EXPECT_TRUE(store.get(second));
  // The cleared edit stays undone: undo now reverts the new edit, then finds nothing.
  ASSERT_TRUE(store.undo());
  EXPECT_FALSE(store.undo());
  EXPECT_EQ(store.count(), 0);
}

TEST_F(LabelStoreTest, PerAnnotatorUndoRevertsOnlyThatAnnotatorsEdits) {
  LabelStore store(path_);
  const int64_t ana = store.add(make_label("r1", 0.0, 1.0, "pat", "ana"));
  const int64_t bo = store.add(make_label("r1", 1.0, 2.0, "poke", "bo"));
  ASSERT_TRUE(store.undo("ana"));
  EXPECT_FALSE(store.get(ana));
  EXPECT_TRUE(store.get(bo));
  EXPECT_FALSE(store.undo("ana"));
  EXPECT_FALSE(store.redo("bo"));
  ASSERT_TRUE(store.redo("ana"));
  EXPECT_TRUE(store.get(ana));
  EXPECT_FALSE(store.undo("carla"));
}

TEST_F(LabelStoreTest, PerAnnotatorUndoRefusesToOverwriteAnotherAnnotatorsLaterEdit) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat", "ana"));
  Label corrected = *store.get(id);
  corrected.class_name = "slap";
  corrected.annotator = "bo";
  store.update(corrected);
  try {
    store.undo("ana");
    FAIL() << "undoing ana's insert would silently drop bo's correction";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_ + " label " + std::to_string(id));
  }
  // The refused undo changed nothing and journalled nothing.
  EXPECT_EQ(store.get(id)->class_name, "slap");
  EXPECT_EQ(store.journal().size(), 2u);
  ASSERT_TRUE(store.undo("bo"));
  ASSERT_TRUE(store.undo("ana"));
  EXPECT_FALSE(store.get(id));
}

TEST_F(LabelStoreTest, JournalRecordsWhoDidWhatNewestFirst) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat", "ana"));
  Label changed = *store.get(id);
  changed.class_name = "slap";
  changed.annotator = "bo";
  store.update(changed);
  store.remove({id, 2}, "carla");
  ASSERT_TRUE(store.undo("carla"));

  const std::vector<JournalEntry> journal = store.journal();
  ASSERT_EQ(journal.size(), 4u);
  std::vector<std::string> actions, annotators;
  for (const JournalEntry& entry : journal) {
    actions.push_back(entry.action);
    annotators.push_back(entry.annotator);
    EXPECT_EQ(entry.label_id, id);
    EXPECT_EQ(entry.time.size(), 24u);
  }
  EXPECT_EQ(actions, (std::vector<std::string>{"undo", "delete", "update", "insert"}));
  EXPECT_EQ(annotators, (std::vector<std::string>{"carla", "carla", "bo", "ana"}));
  EXPECT_GT(journal[0].sequence, journal[1].sequence);
  EXPECT_TRUE(journal[1].undone);
  EXPECT_FALSE(journal[2].undone);

  const JournalEntry& insert = journal[3];
  EXPECT_EQ(insert.before_json, "");
  EXPECT_EQ(nlohmann::json::parse(insert.after_json).at("class"), "pat");
  const JournalEntry& update = journal[2];
  EXPECT_EQ(nlohmann::json::parse(update.before_json).at("class"), "pat");
  EXPECT_EQ(nlohmann::json::parse(update.after_json).at("class"), "slap");
  const JournalEntry& undo = journal[0];
  EXPECT_EQ(undo.before_json, "");
  EXPECT_EQ(nlohmann::json::parse(undo.after_json).at("annotator"), "bo");
  EXPECT_EQ(store.journal(2).size(), 2u);
  EXPECT_EQ(store.journal(2)[0].sequence, journal[0].sequence);
}

TEST_F(LabelStoreTest, UndoOfABatchRevertsEveryLabelOfIt) {
  LabelStore store(path_);
  const int64_t kept = store.add(make_label("r1", 0.0, 1.0, "pat"));
  store.add_many({make_label("r1", 1.0, 2.0, "poke"), make_label("r1", 2.0, 3.0, "rub")});
  ASSERT_TRUE(store.undo());
  EXPECT_EQ(store.count(), 1);
  EXPECT_TRUE(store.get(kept));
  ASSERT_TRUE(store.redo());
  EXPECT_EQ(store.count(), 3);
}

TEST_F(LabelStoreTest, UndoHistorySurvivesReopening) {
  int64_t id = 0;
  {
    LabelStore store(path_);
    id = store.add(make_label("r1", 0.0, 1.0, "pat"));
    store.remove({id, 1});
  }
  LabelStore reopened(path_);
  ASSERT_TRUE(reopened.undo());
  EXPECT_TRUE(reopened.get(id));
}

}  // namespace
}  // namespace tactile

// Two writers of one label store (two LabelStore objects on one file, as two workbenches or a
// workbench and `tactile segment` are): each sees the other's commits through the change check,
// an edit of a label the other changed or removed meanwhile is refused whole naming the label
// and the other annotator, undo never takes back the other's work, and the store verifies
// afterwards. Also the upgrade of a schema 3 store to schema 4.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <memory>
#include <string>

#include "label_store_fixture.h"
#include "tactile/labels/commands.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/verify/verify.h"
#include "test_paths.h"

namespace tactile {
namespace {

class TwoWriters : public LabelStoreTest {
 protected:
  void SetUp() override {
    LabelStoreTest::SetUp();
    ana_ = std::make_unique<LabelStore>(path_);
    bob_ = std::make_unique<LabelStore>(path_);
    id_ = ana_->apply(add_edit(make_label("r1", 12.3, 12.85, "pat", "ana")), "ana").front();
  }
  // What the refused edit says, and that it is an EditConflict about `id` by `other`.
  template <typename Edit>
  std::string refusal(Edit&& edit, int64_t id, const std::string& other) {
    try {
      edit();
    } catch (const EditConflict& conflict) {
      EXPECT_EQ(conflict.label_id(), id);
      EXPECT_EQ(conflict.annotator(), other);
      return conflict.message();
    }
    ADD_FAILURE() << "the edit was not refused";
    return {};
  }
  void expect_sound() {
    EXPECT_TRUE(ana_->check().empty());
    EXPECT_TRUE(verify_label_store(path_).empty());
  }

  std::unique_ptr<LabelStore> ana_, bob_;
  int64_t id_ = 0;
};

TEST_F(TwoWriters, ANewLabelGetsRevisionOneAndEveryChangeTheNext) {
  EXPECT_EQ(bob_->get(id_)->revision, 1);
  const Label seen = *bob_->get(id_);
  bob_->apply(class_edit(seen, "tap"), "bob");
  EXPECT_EQ(ana_->get(id_)->revision, 2);
  ASSERT_TRUE(bob_->undo("bob"));
  EXPECT_EQ(ana_->get(id_)->revision, 3);  // the values come back, the revision moves on
  EXPECT_EQ(ana_->get(id_)->class_name, "pat");
  expect_sound();
}

TEST_F(TwoWriters, EachSeesTheOthersCommitThroughTheChangeCheck) {
  const int64_t before = bob_->change_count();
  EXPECT_EQ(bob_->change_count(), before);  // nothing committed: no change
  const int64_t sequence = bob_->last_sequence();
  ana_->apply(add_edit(make_label("r1", 1.0, 2.0, "tap", "ana")), "ana");
  EXPECT_NE(bob_->change_count(), before);
  const std::vector<JournalEntry> news = bob_->journal_after(sequence);
  ASSERT_EQ(news.size(), 1u);
  EXPECT_EQ(news[0].annotator, "ana");
  EXPECT_EQ(news[0].action, "insert");
  EXPECT_EQ(bob_->count("r1"), 2);
  // A writer's own commits do not show as someone else's.
  const int64_t own = ana_->change_count();
  ana_->apply(add_edit(make_label("r1", 3.0, 4.0, "tap", "ana")), "ana");
  EXPECT_EQ(ana_->change_count(), own);
}

TEST_F(TwoWriters, AnUpdateOfALabelTheOtherChangedIsRefusedNamingLabelAndAnnotator) {
  const Label ana_saw = *ana_->get(id_);
  const Label bob_saw = *bob_->get(id_);
  bob_->apply(class_edit(bob_saw, "tap"), "bob");
  const std::string message =
      refusal([&] { ana_->apply(bounds_edit(ana_saw, 12.0, 13.0), "ana"); }, id_, "bob");
  EXPECT_EQ(message,
            "label " + std::to_string(id_) +
                " (tap, 12.30-12.85 s) was changed by bob meanwhile; your edit was not saved");
  // Nothing lost: bob's change stands, ana's is not applied.
  const Label now = *ana_->get(id_);
  EXPECT_EQ(now.class_name, "tap");
  EXPECT_DOUBLE_EQ(now.t0, 12.3);
  // Read again, ana's edit goes through.
  ana_->apply(bounds_edit(now, 12.0, 13.0), "ana");
  EXPECT_EQ(bob_->get(id_)->t0, 12.0);
  EXPECT_EQ(bob_->get(id_)->class_name, "tap");
  expect_sound();
}

TEST_F(TwoWriters, AnUpdateOfALabelTheOtherRemovedIsRefused) {
  const Label ana_saw = *ana_->get(id_);
  bob_->apply(remove_edit(*bob_->get(id_)), "bob");
  const std::string message =
      refusal([&] { ana_->apply(class_edit(ana_saw, "tap"), "ana"); }, id_, "bob");
  EXPECT_NE(
      message.find("label " + std::to_string(id_) + " (pat, 12.30-12.85 s) was removed by bob"),
      std::string::npos)
      << message;
  EXPECT_FALSE(ana_->get(id_));  // not brought back by the refused update
  expect_sound();
}

TEST_F(TwoWriters, ARemovalOfALabelTheOtherChangedIsRefused) {
  const Label ana_saw = *ana_->get(id_);
  bob_->apply(class_edit(*bob_->get(id_), "tap"), "bob");
  const std::string message =
      refusal([&] { ana_->apply(remove_edit(ana_saw), "ana"); }, id_, "bob");
  EXPECT_NE(message.find("was changed by bob meanwhile"), std::string::npos) << message;
  EXPECT_EQ(bob_->get(id_)->class_name, "tap");  // bob's change is not removed unseen
  expect_sound();
}

TEST_F(TwoWriters, AnEditWithOneStaleLabelIsRefusedWhole) {
  const int64_t other = ana_->add(make_label("r1", 20.0, 21.0, "tap", "ana"));
  const Label first = *ana_->get(id_);
  const Label second = *ana_->get(other);
  bob_->apply(class_edit(*bob_->get(other), "stroke"), "bob");
  LabelEdit edit = class_edit(first, "poke");
  edit.update.push_back(second);
  edit.update.back().note = "mine";
  edit.add = {make_label("r1", 30.0, 31.0, "pat", "ana")};
  const size_t journal_rows = ana_->journal(-1).size();
  refusal([&] { ana_->apply(edit, "ana"); }, other, "bob");
  EXPECT_EQ(ana_->get(id_)->class_name, "pat");  // the label nobody else touched is unchanged too
  EXPECT_EQ(ana_->count("r1"), 2);               // and the addition did not happen
  EXPECT_EQ(ana_->journal(-1).size(), journal_rows);
  expect_sound();
}

TEST_F(TwoWriters, AnEditThatStatesNoRevisionIsRefused) {
  Label unseen = *ana_->get(id_);
  unseen.revision = 0;
  unseen.class_name = "tap";
  try {
    ana_->update(unseen);
    FAIL() << "an update without a revision must be refused";
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("states no revision"), std::string::npos) << error.what();
  }
  EXPECT_EQ(ana_->get(id_)->class_name, "pat");
}

TEST_F(TwoWriters, UndoNeverUndoesTheOtherAnnotatorsWork) {
  // ana changes her label; bob then corrects it. Ana's undo would drop bob's correction.
  ana_->apply(class_edit(*ana_->get(id_), "tap"), "ana");
  bob_->apply(bounds_edit(*bob_->get(id_), 12.0, 13.0), "bob");
  const size_t journal_rows = ana_->journal(-1).size();
  const std::string message = refusal([&] { ana_->undo("ana"); }, id_, "bob");
  EXPECT_NE(message.find("label " + std::to_string(id_) +
                         " (tap, 12.00-13.00 s) was changed by bob "
                         "meanwhile"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("nothing was undone"), std::string::npos) << message;
  EXPECT_EQ(ana_->journal(-1).size(), journal_rows);
  EXPECT_DOUBLE_EQ(ana_->get(id_)->t0, 12.0);
  // The undo stack stays consistent: bob undoes his, then ana's undo goes through.
  ASSERT_TRUE(bob_->undo("bob"));
  ASSERT_TRUE(ana_->undo("ana"));
  EXPECT_EQ(ana_->get(id_)->class_name, "pat");
  ASSERT_TRUE(ana_->redo("ana"));
  EXPECT_EQ(bob_->get(id_)->class_name, "tap");
  expect_sound();
}

TEST_F(TwoWriters, AnEditBasedOnARevisionBeforeAnUndoIsRefused) {
  const Label ana_saw = *ana_->get(id_);
  bob_->apply(class_edit(*bob_->get(id_), "tap"), "bob");
  ASSERT_TRUE(bob_->undo("bob"));  // the values of ana_saw are back, the revision is not
  EXPECT_EQ(ana_->get(id_)->class_name, ana_saw.class_name);
  refusal([&] { ana_->apply(class_edit(ana_saw, "stroke"), "ana"); }, id_, "bob");
}

TEST_F(TwoWriters, ARedoNeverOverwritesTheOthersLaterEdit) {
  // Any new edit ends the redo chain, the other writer's too: ana's redo has nothing to put
  // back over bob's change.
  ana_->apply(class_edit(*ana_->get(id_), "tap"), "ana");
  ASSERT_TRUE(ana_->undo("ana"));
  bob_->apply(class_edit(*bob_->get(id_), "stroke"), "bob");
  EXPECT_FALSE(ana_->redo("ana"));
  EXPECT_EQ(ana_->get(id_)->class_name, "stroke");
  expect_sound();
}

//---- Schema 3 to 4

class LabelStoreSchema3 : public LabelStoreTest {
 protected:
  void SetUp() override {
    LabelStoreTest::SetUp();
    std::filesystem::copy_file(tactile::test::test_data_dir() + "/format_v3/labels.db", path_);
  }
};

TEST_F(LabelStoreSchema3, AStoreOfSchema3OpensUpgradedToRevisionsWithItsHistory) {
  const std::vector<FileProblem> before = verify_label_store(path_);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_NE(before[0].message.find("schema version 3 is older"), std::string::npos)
      << before[0].message;
  std::vector<Label> labels;
  {
    LabelStore store(path_, LabelStore::OpenMode::kExisting);
    EXPECT_EQ(store.opened_version(), 3);
    labels = store.list();
    ASSERT_EQ(labels.size(), 4u);
    for (const Label& label : labels) EXPECT_EQ(label.revision, 1) << label.id;
    EXPECT_TRUE(store.check().empty());
    EXPECT_EQ(store.rejections("fur-s01-t01").size(), 1u);
  }
  EXPECT_TRUE(verify_label_store(path_).empty());
  // The history from before the upgrade still undoes, and edits state revisions from now on.
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.opened_version(), 4);
  LabelStore other(path_, LabelStore::OpenMode::kExisting);
  other.apply(class_edit(labels[0], "tap"), "bob");
  EXPECT_THROW(store.apply(class_edit(labels[0], "pat"), "ana"), EditConflict);
  ASSERT_TRUE(store.undo("ana"));  // ana's rejection (schema 3) comes undone
  EXPECT_EQ(store.count(), 5);
  EXPECT_TRUE(store.check().empty());
  EXPECT_TRUE(verify_label_store(path_).empty());
}

TEST_F(LabelStoreSchema3, AValueDamagedBeforeTheUpgradeIsStillNamed) {
  sqlite3* database = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &database), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(database, "UPDATE labels SET note = 'tampered' WHERE id = 1", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(database);
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  const std::vector<StoreProblem> problems = store.check();
  ASSERT_FALSE(problems.empty());
  EXPECT_EQ(problems[0].table, "labels");
  EXPECT_EQ(problems[0].row, 1);
}

}  // namespace
}  // namespace tactile

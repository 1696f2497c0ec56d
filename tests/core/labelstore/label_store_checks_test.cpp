// Damaged label stores: every row carries a checksum of its fields, values are
// validated on read, digests notice rows lost on disk; a damaged row is named
// (store, row, field), left out of reads and never overwritten, and the rest of
// the store stays usable. Stores of schema 1 open and are upgraded.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "label_store_fixture.h"
#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/verify/verify.h"
#include "test_paths.h"

namespace tactile {
namespace {

LabelFilter of(const std::string& recording) {
  LabelFilter filter;
  filter.recording = recording;
  return filter;
}

class LabelStoreChecks : public LabelStoreTest {
 protected:
  void SetUp() override {
    LabelStoreTest::SetUp();
    LabelStore store(path_);
    store.add(make_label("rec", 1.0, 2.0, "pat"));
    store.add(make_label("rec", 3.0, 4.0, "slap"));
    store.add(make_label("other", 0.5, 1.5, "pat"));
  }
  // Changes the file behind the store's back, as a bad sector would.
  void tamper(const std::string& sql) const {
    sqlite3* database = nullptr;
    ASSERT_EQ(sqlite3_open(path_.c_str(), &database), SQLITE_OK);
    char* message = nullptr;
    ASSERT_EQ(sqlite3_exec(database, sql.c_str(), nullptr, nullptr, &message), SQLITE_OK)
        << (message != nullptr ? message : "");
    sqlite3_close(database);
  }
  static bool names(const StoreProblem& problem, const std::string& table, int64_t row,
                    const std::string& field) {
    return problem.table == table && problem.row == row && problem.field == field;
  }
};

TEST_F(LabelStoreChecks, AnIntactStoreHasNoProblems) {
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.list().size(), 3u);
  EXPECT_TRUE(store.check().empty());
}

TEST_F(LabelStoreChecks, AChangedValueIsNamedLeftOutAndNeverOverwritten) {
  tamper("UPDATE labels SET region = 'mildle' WHERE id = 1");
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  const std::vector<Label> labels = store.list(of("rec"));
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0].id, 2);
  ASSERT_FALSE(store.problems().empty());
  EXPECT_TRUE(names(store.problems()[0], "labels", 1, "region")) << store.problems()[0].what;
  EXPECT_EQ(store.problems()[0].where(path_), path_ + ": labels row 1 field region");
  try {
    store.get(1);
    FAIL() << "read a damaged row";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("labels row 1 field region"), std::string::npos)
        << error.what();
  }
  Label edit = make_label("rec", 1.0, 2.5, "pat");
  edit.id = 1;
  EXPECT_THROW(store.update(edit), Error);
  EXPECT_THROW(store.remove({1, 1}), Error);
  EXPECT_THROW(store.remove_where(of("rec")), Error);
  // The rest stays usable.
  const int64_t added = store.add(make_label("rec", 5.0, 6.0, "pat"));
  EXPECT_EQ(store.get(added)->t1, 6.0);
  store.remove({2, 1});
  EXPECT_EQ(store.list(of("other")).size(), 1u);
}

TEST_F(LabelStoreChecks, AnEndTimeMovedInItsNinthDigitIsCaught) {
  tamper("UPDATE labels SET t1 = 4.000000001 WHERE id = 2");
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.list().size(), 2u);
  const auto problems = store.check();
  ASSERT_FALSE(problems.empty());
  EXPECT_TRUE(names(problems[0], "labels", 2, "t1")) << problems[0].what;
}

TEST_F(LabelStoreChecks, ARowLostOnDiskIsNoticedByItsRecordingsDigest) {
  tamper("DELETE FROM labels WHERE id = 2");
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.list(of("other")).size(), 1u);
  EXPECT_TRUE(store.problems().empty());  // that recording is whole
  EXPECT_EQ(store.list(of("rec")).size(), 1u);
  ASSERT_EQ(store.problems().size(), 1u);
  EXPECT_TRUE(names(store.problems()[0], "digests", 0, "labels:rec"));
  EXPECT_NE(store.problems()[0].what.find("1 rows read, 2 written"), std::string::npos)
      << store.problems()[0].what;
}

TEST_F(LabelStoreChecks, ADamagedJournalRowStopsUndoAndIsNamed) {
  tamper("UPDATE journal SET after_json = replace(after_json, 'slap', 'slip') WHERE sequence = 2");
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.journal().size(), 2u);
  ASSERT_FALSE(store.problems().empty());
  EXPECT_TRUE(names(store.problems()[0], "journal", 2, "after_json")) << store.problems()[0].what;
  // Undo walks back the newest batch (label 3, intact), then meets the damaged row.
  EXPECT_TRUE(store.undo());
  EXPECT_THROW(store.undo(), Error);
  EXPECT_EQ(store.count(), 2);
}

TEST_F(LabelStoreChecks, UndoAndRedoKeepEveryChecksum) {
  {
    LabelStore store(path_, LabelStore::OpenMode::kExisting);
    Label edit = *store.get(1);
    edit.class_name = "slap";
    store.update(edit);
    store.remove({3, 1});
    ASSERT_TRUE(store.undo());
    ASSERT_TRUE(store.undo());
    ASSERT_TRUE(store.redo());
    store.add(make_label("rec", 7.0, 8.0, "pat"));  // clears the redo chain
  }
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_TRUE(store.check().empty()) << store.check()[0].what;
}

TEST_F(LabelStoreChecks, ReadOnlyOpeningChangesNothingBesideTheFile) {
  tamper("UPDATE labels SET class = 'pet' WHERE id = 3");
  const std::string before = read_text(path_);
  {
    LabelStore store(path_, LabelStore::OpenMode::kReadOnly);
    EXPECT_EQ(store.check().size(), 1u);
    EXPECT_THROW(store.add(make_label("rec", 9.0, 9.5, "pat")), Error);
  }
  EXPECT_EQ(read_text(path_), before);
  EXPECT_FALSE(std::filesystem::exists(path_ + "-wal"));
  EXPECT_FALSE(std::filesystem::exists(path_ + "-shm"));
}

TEST_F(LabelStoreChecks, ADamagedSchemaIsNamedEvenWhereOnlyWritesWouldMeetIt) {
  // A CHECK constraint naming a column that does not exist: reads work, writes fail.
  tamper(
      "PRAGMA writable_schema = ON; UPDATE sqlite_master SET sql = replace(sql, "
      "'confidence BETWEEN', 'confidenbe BETWEEN') WHERE name = 'labels'");
  const auto problems = verify_label_store(path_);
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(problems[0].message.find(path_ + ": schema, table labels: missing or damaged"),
            std::string::npos)
      << problems[0].message;
}

TEST_F(LabelStoreChecks, VerifyNamesLabelsOutsideTheirRecordingsSpan) {
  const auto problems = verify_label_store(path_, {{"rec", {0.0, 3.5}}});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(
      problems[0].message.find("labels row 2: [3, 4] s lies outside recording rec [0, 3.5] s"),
      std::string::npos)
      << problems[0].message;
}

//---- Schema 1

class LabelStoreSchema1 : public LabelStoreTest {
 protected:
  void SetUp() override {
    LabelStoreTest::SetUp();
    std::filesystem::copy_file(tactile::test::test_data_dir() + "/format_v1/labels.db", path_);
  }
};

TEST_F(LabelStoreSchema1, AStoreOfAnEarlierVersionOpensUpgradedWithItsHistory) {
  const std::vector<FileProblem> before = verify_label_store(path_);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_NE(before[0].message.find("schema version 1 carries no checksums"), std::string::npos);
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.opened_version(), 1);
  const std::vector<Label> labels = store.list();
  ASSERT_EQ(labels.size(), 6u);
  EXPECT_EQ(labels[0].class_name, "stroke");
  EXPECT_EQ(labels[0].region, "middle");
  EXPECT_TRUE(store.check().empty());
  EXPECT_TRUE(store.undo());  // the simulator's batch
  EXPECT_EQ(store.count(), 0);
  EXPECT_TRUE(store.redo());
  EXPECT_EQ(store.count(), 6);
  EXPECT_TRUE(verify_label_store(path_).empty());
}

TEST_F(LabelStoreSchema1, AValueBrokenBeforeTheUpgradeIsStillRefusedByValidation) {
  // A damaged date sealed by the upgrade's checksum still does not pass as a date.
  sqlite3* database = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &database), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(database,
                         "UPDATE labels SET created = '1970-13-01T00:00:00.000Z' "
                         "WHERE id = 4",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(database);
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  EXPECT_EQ(store.list().size(), 5u);
  ASSERT_EQ(store.problems().size(), 1u);
  EXPECT_TRUE(store.problems()[0].table == "labels" && store.problems()[0].row == 4 &&
              store.problems()[0].field == "created")
      << store.problems()[0].what;
}

}  // namespace
}  // namespace tactile

#include "tactile/labels/suggestions.h"

namespace tactile {
namespace {

TEST_F(LabelStoreChecks, ARejectedSuggestionIsRemovedRememberedAndLeftOutOfARerun) {
  LabelStore store(path_, LabelStore::OpenMode::kExisting);
  Label suggestion = make_label("rec", 6.0, 7.0, std::string(kUnknownClass));
  suggestion.source = LabelSource::kSegmenter;
  suggestion.annotator = "segmenter:threshold";
  const int64_t id = store.add(suggestion);
  EXPECT_THROW(store.reject({1, 1}, "ana"), Error);  // a manual label is not a suggestion
  store.reject({id, 1}, "ana");
  EXPECT_FALSE(store.get(id).has_value());
  const std::vector<Rejection> rejections = store.rejections("rec");
  ASSERT_EQ(rejections.size(), 1u);
  EXPECT_EQ(rejections[0].method, "segmenter:threshold");
  EXPECT_EQ(rejections[0].annotator, "ana");
  // A rerun finds it again (slightly moved) and another one: only the other stays.
  std::vector<Label> rerun = {suggestion, suggestion};
  rerun[0].t0 = 6.05;
  rerun[1].t0 = 9.0;
  rerun[1].t1 = 9.5;
  EXPECT_EQ(drop_rejected(rerun, rejections), 1u);
  ASSERT_EQ(rerun.size(), 1u);
  EXPECT_EQ(rerun[0].t0, 9.0);
  // Undo brings the suggestion back; the store stays sound.
  EXPECT_TRUE(store.undo("ana"));
  EXPECT_TRUE(store.get(id).has_value());
  EXPECT_TRUE(store.check().empty());
}

}  // namespace
}  // namespace tactile

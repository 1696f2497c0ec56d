// LabelStore: adding, changing, removing and querying labels, class vocabulary.
#include "tactile/labelstore/label_store.h"

#include <gtest/gtest.h>

#include <limits>

#include "label_store_fixture.h"
#include "tactile/error.h"

namespace tactile {
namespace {

//---- CRUD

TEST_F(LabelStoreTest, AddedLabelReadsBackWithItsFieldsAndStoreTimes) {
  LabelStore store(path_);
  Label label = make_label("nao/s01/r03", 1.25, 2.5, "stroke");
  label.region = "front";
  label.source = LabelSource::kSegmenter;
  label.confidence = 0.75;
  label.note = "second half is noisy";
  label.created = "ignored";
  const int64_t id = store.add(label);
  EXPECT_GT(id, 0);

  const std::optional<Label> stored = store.get(id);
  ASSERT_TRUE(stored);
  EXPECT_EQ(stored->id, id);
  EXPECT_EQ(stored->recording, "nao/s01/r03");
  EXPECT_DOUBLE_EQ(stored->t0, 1.25);
  EXPECT_DOUBLE_EQ(stored->t1, 2.5);
  EXPECT_EQ(stored->region, "front");
  EXPECT_EQ(stored->class_name, "stroke");
  EXPECT_EQ(stored->annotator, "ana");
  EXPECT_EQ(stored->source, LabelSource::kSegmenter);
  EXPECT_DOUBLE_EQ(stored->confidence, 0.75);
  EXPECT_EQ(stored->note, "second half is noisy");
  // ISO 8601 UTC with milliseconds: 2024-05-01T12:00:00.250Z
  ASSERT_EQ(stored->created.size(), 24u);
  EXPECT_EQ(stored->created[10], 'T');
  EXPECT_EQ(stored->created.back(), 'Z');
  EXPECT_EQ(stored->modified, stored->created);
  EXPECT_FALSE(store.get(id + 1));
}

TEST_F(LabelStoreTest, UpdateChangesFieldsAndKeepsCreatedTime) {
  LabelStore store(path_);
  const int64_t id = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const Label original = *store.get(id);
  Label changed = original;
  changed.class_name = "slap";
  changed.t1 = 0.5;
  changed.created = "1999-01-01T00:00:00.000Z";
  store.update(changed);
  const Label stored = *store.get(id);
  EXPECT_EQ(stored.class_name, "slap");
  EXPECT_DOUBLE_EQ(stored.t1, 0.5);
  EXPECT_EQ(stored.created, original.created);
  EXPECT_GE(stored.modified, original.modified);
  EXPECT_EQ(store.count(), 1);
}

TEST_F(LabelStoreTest, UpdateOrRemoveOfMissingIdNamesTheLabel) {
  LabelStore store(path_);
  Label ghost = make_label("r1", 0.0, 1.0, "pat");
  ghost.id = 17;
  try {
    store.update(ghost);
    FAIL() << "update of a missing label must throw";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_ + " label 17");
  }
  try {
    store.remove({17, 1});
    FAIL() << "remove of a missing label must throw";
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_ + " label 17");
  }
  EXPECT_TRUE(store.journal().empty());
}

TEST_F(LabelStoreTest, RemoveDeletesOnlyThatLabel) {
  LabelStore store(path_);
  const int64_t first = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const int64_t second = store.add(make_label("r1", 1.0, 2.0, "poke"));
  store.remove({first, 1});
  EXPECT_FALSE(store.get(first));
  EXPECT_TRUE(store.get(second));
  EXPECT_EQ(store.count(), 1);
}

TEST_F(LabelStoreTest, InvalidLabelsAreRejectedAndNothingIsStored) {
  LabelStore store(path_);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Label> bad;
  bad.push_back(make_label("r1", 2.0, 1.0, "pat"));  // t0 after t1
  bad.push_back(make_label("r1", 1.0, 1.0, "pat"));  // empty interval
  bad.push_back(make_label("r1", nan, 1.0, "pat"));
  bad.push_back(make_label("r1", 0.0, std::numeric_limits<double>::infinity(), "pat"));
  bad.push_back(make_label("r1", 0.0, 1.0, ""));
  bad.push_back(make_label("", 0.0, 1.0, "pat"));
  Label confident = make_label("r1", 0.0, 1.0, "pat");
  confident.confidence = 1.5;
  bad.push_back(confident);
  confident.confidence = nan;
  bad.push_back(confident);
  for (const Label& label : bad) {
    try {
      store.add(label);
      ADD_FAILURE() << "accepted t0=" << label.t0 << " t1=" << label.t1 << " class='"
                    << label.class_name << "' confidence=" << label.confidence;
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), path_ + " new label");
    }
  }
  EXPECT_EQ(store.count(), 0);
  EXPECT_TRUE(store.journal().empty());
}

TEST_F(LabelStoreTest, ErrorMessageSaysWhichBoundIsWrong) {
  LabelStore store(path_);
  try {
    store.add(make_label("r1", 2.0, 1.5, "pat"));
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.message(), "t0 (2 s) must be before t1 (1.5 s)");
  }
}

TEST_F(LabelStoreTest, AddManyIsAllOrNothing) {
  LabelStore store(path_);
  std::vector<Label> labels = {make_label("r1", 0.0, 1.0, "pat"), make_label("r1", 1.0, 2.0, "")};
  try {
    store.add_many(labels);
    FAIL();
  } catch (const Error& error) {
    EXPECT_EQ(error.where(), path_ + " new label 2 of 2");
  }
  EXPECT_EQ(store.count(), 0);
  labels[1].class_name = "poke";
  const std::vector<int64_t> ids = store.add_many(labels);
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_EQ(store.get(ids[1])->class_name, "poke");
  // One call, one journal batch.
  const std::vector<JournalEntry> journal = store.journal();
  ASSERT_EQ(journal.size(), 2u);
  EXPECT_EQ(journal[0].batch, journal[1].batch);
}

//---- Queries

TEST_F(LabelStoreTest, ListIsOrderedByRecordingThenTimeThenId) {
  LabelStore store(path_);
  const int64_t late_b = store.add(make_label("b", 5.0, 6.0, "pat"));
  const int64_t early_a = store.add(make_label("a", 1.0, 2.0, "pat"));
  const int64_t late_a = store.add(make_label("a", 3.0, 4.0, "pat"));
  const int64_t early_a_again = store.add(make_label("a", 1.0, 1.5, "poke"));
  std::vector<int64_t> order;
  for (const Label& label : store.list()) order.push_back(label.id);
  EXPECT_EQ(order, (std::vector<int64_t>{early_a, early_a_again, late_a, late_b}));
}

TEST_F(LabelStoreTest, FiltersSelectByRecordingRegionClassAndSource) {
  LabelStore store(path_);
  Label front = make_label("r1", 0.0, 1.0, "pat");
  front.region = "front";
  Label back = make_label("r1", 0.0, 1.0, "stroke");  // multi-touch: same time, other region
  back.region = "back";
  back.source = LabelSource::kModel;
  const int64_t front_id = store.add(front);
  const int64_t back_id = store.add(back);
  const int64_t other_id = store.add(make_label("r2", 0.0, 1.0, "pat"));

  auto ids = [&](const LabelFilter& filter) {
    std::vector<int64_t> found;
    for (const Label& label : store.list(filter)) found.push_back(label.id);
    return found;
  };
  LabelFilter filter;
  filter.recording = "r1";
  EXPECT_EQ(ids(filter), (std::vector<int64_t>{front_id, back_id}));
  filter.region = "back";
  EXPECT_EQ(ids(filter), (std::vector<int64_t>{back_id}));
  LabelFilter by_class;
  by_class.class_name = "pat";
  EXPECT_EQ(ids(by_class), (std::vector<int64_t>{front_id, other_id}));
  LabelFilter by_source;
  by_source.source = LabelSource::kModel;
  EXPECT_EQ(ids(by_source), (std::vector<int64_t>{back_id}));
  by_source.source = LabelSource::kGroundTruth;
  EXPECT_TRUE(ids(by_source).empty());
}

TEST_F(LabelStoreTest, OverlapQueryTreatsIntervalsAsHalfOpen) {
  LabelStore store(path_);
  const int64_t first = store.add(make_label("r1", 0.0, 1.0, "pat"));
  const int64_t second = store.add(make_label("r1", 1.0, 2.0, "pat"));
  const int64_t third = store.add(make_label("r1", 2.5, 4.0, "pat"));
  auto ids = [&](std::optional<double> from, std::optional<double> to) {
    LabelFilter filter;
    filter.overlapping_t0 = from;
    filter.overlapping_t1 = to;
    std::vector<int64_t> found;
    for (const Label& label : store.list(filter)) found.push_back(label.id);
    return found;
  };
  // [1, 2) touches [0, 1) only at its excluded end.
  EXPECT_EQ(ids(1.0, 2.0), (std::vector<int64_t>{second}));
  EXPECT_EQ(ids(0.5, 3.0), (std::vector<int64_t>{first, second, third}));
  EXPECT_TRUE(ids(2.0, 2.5).empty());
  EXPECT_EQ(ids(3.9, std::nullopt), (std::vector<int64_t>{third}));
  EXPECT_EQ(ids(std::nullopt, 0.1), (std::vector<int64_t>{first}));
}

TEST_F(LabelStoreTest, CountIsPerRecordingOrOverall) {
  LabelStore store(path_);
  store.add(make_label("r1", 0.0, 1.0, "pat"));
  store.add(make_label("r1", 1.0, 2.0, "pat"));
  store.add(make_label("r2", 0.0, 1.0, "pat"));
  EXPECT_EQ(store.count("r1"), 2);
  EXPECT_EQ(store.count("r2"), 1);
  EXPECT_EQ(store.count("r3"), 0);
  EXPECT_EQ(store.count(), 3);
}

TEST_F(LabelStoreTest, RemoveWhereRemovesOnlyMatchesInOneUndoableBatch) {
  LabelStore store(path_);
  Label segment = make_label("r1", 0.0, 1.0, "pat", "segmenter");
  segment.source = LabelSource::kSegmenter;
  store.add_many({segment, segment, segment});
  const int64_t manual = store.add(make_label("r1", 0.0, 1.0, "pat"));
  LabelFilter filter;
  filter.source = LabelSource::kSegmenter;
  EXPECT_EQ(store.remove_where(filter, "rerun"), 3);
  EXPECT_EQ(store.count(), 1);
  EXPECT_TRUE(store.get(manual));
  EXPECT_EQ(store.journal(1)[0].annotator, "rerun");
  EXPECT_EQ(store.remove_where(filter), 0);
  ASSERT_TRUE(store.undo());
  EXPECT_EQ(store.count(), 4);
}

//---- Class vocabulary

TEST_F(LabelStoreTest, ClassVocabularyRoundTripsPerSkinInOrder) {
  const std::vector<std::string> nao = {"pat",     "poke", "punch",  "push",  "rub",
                                        "scratch", "slap", "stroke", "tickle"};
  {
    LabelStore store(path_);
    store.set_classes("nao", nao);
    store.set_classes("flux", {"zone 1", "zone 2"});
    store.set_classes("flux", {"caress 4->1", "zone 3"});  // replaces
  }
  LabelStore reopened(path_);
  EXPECT_EQ(reopened.classes("nao"), nao);
  EXPECT_EQ(reopened.classes("flux"), (std::vector<std::string>{"caress 4->1", "zone 3"}));
  EXPECT_TRUE(reopened.classes("fur").empty());
}

TEST_F(LabelStoreTest, ClassVocabularyRejectsDuplicatesAndEmptyNames) {
  LabelStore store(path_);
  store.set_classes("fur", {"slap", "pat"});
  EXPECT_THROW(store.set_classes("fur", {"slap", "slap"}), Error);
  EXPECT_THROW(store.set_classes("fur", {"slap", ""}), Error);
  EXPECT_THROW(store.set_classes("", {"slap"}), Error);
  EXPECT_EQ(store.classes("fur"), (std::vector<std::string>{"slap", "pat"}));
}

}  // namespace
}  // namespace tactile

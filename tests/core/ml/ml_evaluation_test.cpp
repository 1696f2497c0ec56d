// Evaluation protocols (spec §6.6), confusion figures (§6.7, TV K8) and evaluate() end to
// end with k-NN: folds, stratification, reproducibility, threads, cancel, grid search.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <random>
#include <set>

#include "ml_test_data.h"
#include "tactile/error.h"
#include "tactile/ml/evaluation.h"

namespace tactile::ml {
namespace {

std::vector<int64_t> sorted_union(const std::vector<int64_t>& a, const std::vector<int64_t>& b) {
  std::vector<int64_t> all = a;
  all.insert(all.end(), b.begin(), b.end());
  std::sort(all.begin(), all.end());
  return all;
}

//---- Protocol::parse

TEST(Protocol, ParsesEveryForm) {
  const Protocol kfold = Protocol::parse("kfold:5x10");
  EXPECT_EQ(kfold.kind, Protocol::Kind::kKFold);
  EXPECT_EQ(kfold.folds, 5);
  EXPECT_EQ(kfold.repetitions, 10);
  EXPECT_EQ(Protocol::parse("kfold:7").repetitions, 1);
  EXPECT_EQ(Protocol::parse("loo").kind, Protocol::Kind::kLeaveOneOut);
  EXPECT_EQ(Protocol::parse("loso").kind, Protocol::Kind::kLeaveOneSubjectOut);
  const Protocol holdout = Protocol::parse("holdout:0.15x10");
  EXPECT_EQ(holdout.kind, Protocol::Kind::kHoldout);
  EXPECT_DOUBLE_EQ(holdout.test_fraction, 0.15);
  EXPECT_EQ(holdout.repetitions, 10);
  const Protocol split = Protocol::parse("split:side=back,condition=stationary/side=front");
  EXPECT_EQ(split.kind, Protocol::Kind::kSplit);
  EXPECT_EQ(split.train_query, "side=back,condition=stationary");
  EXPECT_EQ(split.test_query, "side=front");
}

TEST(Protocol, PrintsWhatItParses) {
  for (const char* text : {"kfold:5x10", "kfold:7", "loo", "loso", "group:session",
                           "holdout:0.15x10", "split:side=back/side=front"})
    EXPECT_EQ(Protocol::parse(text).to_string(), text);
}

TEST(Protocol, BadSpecificationsNameTheProtocolOption) {
  for (const char* text : {"kfold", "kfold:1", "kfold:x3", "kfold:5x0", "kfold:5xa", "kfold:2.5",
                           "loo:3", "holdout:1.5x2", "holdout:0x2", "holdout:0.2x", "kfold:5x",
                           "split:a=b", "split:a=b/", "split:a=b/c=d/e=f", "bootstrap:10", ""}) {
    try {
      Protocol::parse(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const Error& error) {
      EXPECT_EQ(error.where(), "--protocol") << text;
    }
  }
}

TEST(Protocol, MissingFoldCountSaysWhatFormIsExpected) {
  try {
    Protocol::parse("kfold:x");
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("expected kfold:K or kfold:KxR"), std::string::npos)
        << error.what();
  }
}

//---- Folds

TEST(Folds, StratifiedKFoldCoversEveryRowOncePerRepetitionWithBalancedClasses) {
  const Dataset dataset = blob_dataset({23, 17, 9}, 2, 1);
  const auto folds = make_folds(dataset, Protocol::parse("kfold:5x3"), 42);
  ASSERT_EQ(folds.size(), 15u);
  for (int repetition = 0; repetition < 3; ++repetition) {
    std::vector<int> tested(static_cast<size_t>(dataset.rows()), 0);
    std::map<std::string, std::vector<int>> per_class_sizes;
    for (int fold = 0; fold < 5; ++fold) {
      const Fold& split = folds[static_cast<size_t>(repetition * 5 + fold)];
      EXPECT_EQ(sorted_union(split.train, split.test).size(), static_cast<size_t>(dataset.rows()));
      std::vector<int64_t> all = sorted_union(split.train, split.test);
      EXPECT_TRUE(std::adjacent_find(all.begin(), all.end()) == all.end())
          << "train and test overlap";
      std::map<std::string, int> sizes;
      for (int64_t row : split.test) {
        ++tested[static_cast<size_t>(row)];
        ++sizes[dataset.classes[static_cast<size_t>(row)]];
      }
      for (const char* name : {"c0", "c1", "c2"}) per_class_sizes[name].push_back(sizes[name]);
    }
    for (int count : tested) EXPECT_EQ(count, 1);
    for (const auto& [name, sizes] : per_class_sizes) {
      const auto [low, high] = std::minmax_element(sizes.begin(), sizes.end());
      EXPECT_LE(*high - *low, 1) << name;
    }
  }
  // Fold 0 gets ceil(n_c / 5) of each class: 5 + 4 + 2.
  EXPECT_EQ(folds[0].test.size(), 11u);
  // Repetitions reshuffle.
  EXPECT_NE(folds[0].test, folds[5].test);
}

TEST(Folds, SameSeedSameFoldsOtherSeedOtherFolds) {
  const Dataset dataset = blob_dataset({20, 20}, 2, 1);
  const auto first = make_folds(dataset, Protocol::parse("kfold:4x2"), 7);
  const auto second = make_folds(dataset, Protocol::parse("kfold:4x2"), 7);
  const auto other = make_folds(dataset, Protocol::parse("kfold:4x2"), 8);
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i].test, second[i].test);
  bool differs = false;
  for (size_t i = 0; i < first.size(); ++i) differs |= first[i].test != other[i].test;
  EXPECT_TRUE(differs);
}

TEST(Folds, LeaveOneOutTestsEachRowAlone) {
  const Dataset dataset = blob_dataset({3, 3}, 1, 1);
  const auto folds = make_folds(dataset, Protocol::parse("loo"), 1);
  ASSERT_EQ(folds.size(), 6u);
  for (int64_t row = 0; row < 6; ++row) {
    EXPECT_EQ(folds[static_cast<size_t>(row)].test, std::vector<int64_t>{row});
    EXPECT_EQ(folds[static_cast<size_t>(row)].train.size(), 5u);
  }
}

TEST(Folds, LeaveOneSubjectOutKeepsSubjectsTogether) {
  const Dataset dataset = blob_dataset({10, 10}, 1, 1);
  const auto folds = make_folds(dataset, Protocol::parse("loso"), 1);
  ASSERT_EQ(folds.size(), 4u);
  for (size_t fold = 0; fold < folds.size(); ++fold) {
    std::set<std::string> test_subjects;
    for (int64_t row : folds[fold].test)
      test_subjects.insert(dataset.subjects[static_cast<size_t>(row)]);
    EXPECT_EQ(test_subjects, std::set<std::string>{"s" + std::to_string(fold)});
    for (int64_t row : folds[fold].train)
      EXPECT_EQ(test_subjects.count(dataset.subjects[static_cast<size_t>(row)]), 0u);
  }
}

TEST(Folds, LeaveOneGroupOutSplitsByAnyColumn) {
  Dataset dataset = blob_dataset({6, 6}, 1, 1);
  // A session per row, three sessions, in the metadata only.
  dataset.metadata.resize(static_cast<size_t>(dataset.rows()));
  for (size_t row = 0; row < dataset.metadata.size(); ++row)
    dataset.metadata[row]["session"] = "day" + std::to_string(row % 3);
  const Protocol protocol = Protocol::parse("group:session");
  EXPECT_EQ(protocol.to_string(), "group:session");
  const auto folds = make_folds(dataset, protocol, 1);
  ASSERT_EQ(folds.size(), 3u);
  for (size_t fold = 0; fold < folds.size(); ++fold) {
    EXPECT_EQ(folds[fold].test.size(), 4u);
    for (int64_t row : folds[fold].test)
      EXPECT_EQ(dataset.metadata[static_cast<size_t>(row)]["session"],
                "day" + std::to_string(fold));
    for (int64_t row : folds[fold].train)
      EXPECT_NE(dataset.metadata[static_cast<size_t>(row)]["session"],
                "day" + std::to_string(fold));
  }
  // The table's own columns: subject gives loso's folds.
  EXPECT_EQ(make_folds(dataset, Protocol::parse("group:subject"), 1).size(),
            make_folds(dataset, Protocol::parse("loso"), 1).size());
  // A row without the column, a column with one value, no column: refused with the reason.
  dataset.metadata[4].erase("session");
  EXPECT_THROW(make_folds(dataset, protocol, 1), Error);
  EXPECT_THROW(Protocol::parse("group:"), Error);
  for (auto& metadata : dataset.metadata) metadata["site"] = "lab";
  EXPECT_THROW(make_folds(dataset, Protocol::parse("group:site"), 1), Error);
}

TEST(Folds, LeaveOneSubjectOutNeedsSubjects) {
  Dataset dataset = blob_dataset({4, 4}, 1, 1);
  dataset.subjects[5] = "";
  EXPECT_THROW(make_folds(dataset, Protocol::parse("loso"), 1), Error);
  std::fill(dataset.subjects.begin(), dataset.subjects.end(), "only");
  EXPECT_THROW(make_folds(dataset, Protocol::parse("loso"), 1), Error);
}

TEST(Folds, HoldoutTestsTheFractionOfEachClass) {
  const Dataset dataset = blob_dataset({40, 20, 1}, 1, 1);
  const auto folds = make_folds(dataset, Protocol::parse("holdout:0.15x10"), 3);
  ASSERT_EQ(folds.size(), 10u);
  for (const Fold& fold : folds) {
    std::map<std::string, int> sizes;
    for (int64_t row : fold.test) ++sizes[dataset.classes[static_cast<size_t>(row)]];
    EXPECT_EQ(sizes["c0"], 6);  // round(0.15 * 40)
    EXPECT_EQ(sizes["c1"], 3);  // round(0.15 * 20)
    EXPECT_EQ(sizes["c2"], 0);  // a class of one sample is only trained on
    EXPECT_EQ(fold.train.size() + fold.test.size(), 61u);
  }
  EXPECT_NE(folds[0].test, folds[1].test);
}

TEST(Folds, SplitFollowsTheQueries) {
  const Dataset dataset = blob_dataset({12, 12}, 1, 1);
  const auto folds =
      make_folds(dataset, Protocol::parse("split:side=back,condition=stationary/side=front"), 1);
  ASSERT_EQ(folds.size(), 1u);
  for (int64_t row : folds[0].train) {
    EXPECT_EQ(dataset.metadata[static_cast<size_t>(row)].at("side"), "back");
    EXPECT_EQ(dataset.metadata[static_cast<size_t>(row)].at("condition"), "stationary");
  }
  for (int64_t row : folds[0].test)
    EXPECT_EQ(dataset.metadata[static_cast<size_t>(row)].at("side"), "front");
  EXPECT_EQ(folds[0].test.size(), 12u);
  EXPECT_EQ(folds[0].train.size(), 8u);  // odd rows not divisible by 3
  const auto by_subject =
      make_folds(dataset, Protocol::parse("split:subject=s0/subject=s2,class=c0"), 1);
  EXPECT_EQ(by_subject[0].train.size(), 6u);
  for (int64_t row : by_subject[0].test) EXPECT_EQ(dataset.classes[static_cast<size_t>(row)], "c0");
}

TEST(Folds, SplitQueryMatchingNothingIsNamed) {
  const Dataset dataset = blob_dataset({6, 6}, 1, 1);
  try {
    make_folds(dataset, Protocol::parse("split:side=back/side=top"), 1);
    FAIL() << "an empty test query was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("side=top"), std::string::npos) << error.what();
  }
  EXPECT_THROW(make_folds(dataset, Protocol::parse("split:colour=red/side=front"), 1), Error);
  EXPECT_THROW(make_folds(dataset, Protocol::parse("split:side=back/class=c1"), 1),
               Error);  // overlap
}

TEST(Folds, MoreFoldsThanRowsIsAnError) {
  const Dataset dataset = blob_dataset({2, 2}, 1, 1);
  EXPECT_THROW(make_folds(dataset, Protocol::parse("kfold:5"), 1), Error);
  EXPECT_THROW(make_folds(Dataset{}, Protocol::parse("loo"), 1), Error);
}

//---- Confusion figures (TV K8)

TEST(ConfusionFigures, Table5AccuracyIsTraceOverTotal) {
  Eigen::MatrixXi table(9, 9);
  table << 24, 0, 0, 0, 0, 0, 0, 0, 0,  //
      0, 23, 0, 1, 0, 0, 0, 0, 0,       //
      0, 0, 24, 0, 0, 0, 0, 0, 0,       //
      0, 0, 0, 24, 0, 0, 0, 0, 0,       //
      0, 0, 0, 0, 22, 0, 0, 2, 0,       //
      0, 0, 0, 0, 0, 23, 0, 0, 1,       //
      1, 0, 1, 0, 0, 0, 22, 0, 0,       //
      0, 0, 0, 0, 0, 0, 0, 24, 0,       //
      0, 0, 0, 0, 0, 1, 0, 0, 23;
  EXPECT_NEAR(accuracy_of(table), 0.967593, 5e-7);
  const auto figures = class_figures(table);
  for (const ClassFigures& figure : figures) EXPECT_EQ(figure.support, 24);
  EXPECT_NEAR(figures[4].recall, 22.0 / 24.0, 1e-12);     // Rub
  EXPECT_NEAR(figures[7].precision, 24.0 / 26.0, 1e-12);  // Stroke: Rub 2 predicted as Stroke
  EXPECT_NEAR(figures[7].false_alarm, 2.0 / 24.0, 1e-12);
}

TEST(ConfusionFigures, Table8AccuracyIsTraceOverTotal) {
  Eigen::MatrixXi table(9, 9);
  table << 48, 0, 0, 0, 0, 0, 0, 0, 0,  //
      0, 44, 0, 4, 0, 0, 0, 0, 0,       //
      0, 0, 46, 0, 0, 0, 2, 0, 0,       //
      0, 2, 0, 44, 0, 0, 0, 2, 0,       //
      0, 0, 0, 2, 44, 0, 0, 2, 0,       //
      0, 0, 0, 0, 0, 46, 0, 0, 2,       //
      2, 0, 2, 0, 0, 0, 44, 0, 0,       //
      0, 0, 0, 4, 0, 0, 0, 44, 0,       //
      0, 0, 0, 0, 0, 2, 0, 0, 46;
  EXPECT_NEAR(accuracy_of(table), 0.939815, 5e-7);
}

TEST(ConfusionFigures, UnknownAnswersAreNotCorrectAndNoFalseAlarm) {
  Eigen::MatrixXi confusion(2, 3);  // last column: unknown
  confusion << 3, 1, 2,             //
      0, 4, 0;
  EXPECT_DOUBLE_EQ(accuracy_of(confusion), 0.7);
  const auto figures = class_figures(confusion);
  EXPECT_EQ(figures[0].support, 6);
  EXPECT_DOUBLE_EQ(figures[0].recall, 0.5);
  EXPECT_DOUBLE_EQ(figures[0].false_alarm, 0.0);
  EXPECT_DOUBLE_EQ(figures[1].false_alarm, 0.25);
  EXPECT_DOUBLE_EQ(figures[1].precision, 0.8);
}

}  // namespace
}  // namespace tactile::ml

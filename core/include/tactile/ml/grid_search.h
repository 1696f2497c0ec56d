#pragma once
// Hyper-parameter grid search inside the training fold only (issue 5): the meta-classifier
// `grid-search` (alias `grid`), e.g.
//   grid:base=knn,k=1|3|5,metric=euclidean|cosine,inner=kfold:3
// Parameters:
//   base   the classifier whose parameters are searched (required; not grid-search itself)
//   inner  the protocol of the inner cross-validation on the training rows (default
//          kfold:5; kfold, loo or holdout: loso and split need metadata the inner rows lack)
//   any other key is a parameter of `base`; `a|b|c` lists the values to try.
// fit() scores every combination (keys in alphabetical order, values in the given order) by
// the accuracy of the inner cross-validation, with folds drawn from the fit seed, keeps the
// first best and refits it on all training rows. Test rows are never seen by the search.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/ml/classifier.h"
#include "tactile/ml/evaluation.h"

namespace tactile::ml {

// A block of a stacked table's columns (features/stack.h): its pipeline and its columns,
// 0-based, inclusive.
struct AutoBlock {
  std::string name;
  int first = -1, last = -1;
};
// "generic:0-41|raw:42-297" -> the blocks; throws tactile::Error naming blocks= on an item
// that is not NAME:A-B with A <= B.
std::vector<AutoBlock> parse_auto_blocks(const std::string& text);

struct GridCandidate {
  std::string specification;    // "knn:k=3,metric=cosine"
  double inner_accuracy = 0.0;  // on `rows` rows; -1 when it could not learn from them
  int64_t rows = 0;             // training rows of the last inner cross-validation it ran
};

class GridSearchClassifier : public Classifier {
 public:
  GridSearchClassifier(std::string base, std::vector<std::pair<std::string, std::string>> axes,
                       Protocol inner);
  // `auto`: the candidates are whole specifications (different classifiers), not one base's
  // grid; `listed` is what the user gave ("" = the default list); `blocks` as
  // parse_auto_blocks reads it ("" = every column for every candidate).
  GridSearchClassifier(std::vector<std::string> specifications, Protocol inner, std::string listed,
                       std::string blocks = {});
  std::string name() const override { return auto_ ? "auto" : "grid-search"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // Every combination in search order, each with "base:key=value,..." for make_classifier;
  // for auto after a fit, also the column-selecting variants it added.
  const std::vector<GridCandidate>& candidates() const { return candidates_; }
  // The specification chosen by the last fit (its base's effective parameters); with
  // blocks, prefixed by the chosen block's pipeline ("rocket/select:...").
  std::string chosen_specification() const;

 private:
  const Classifier& chosen() const;
  double inner_accuracy(const Dataset& inner, const std::string& specification,
                        uint64_t inner_seed) const;
  // auto's successive halving; the index of the winner.
  size_t halve_candidates(const Matrix& x, const std::vector<int>& y, int class_count,
                          uint64_t seed);

  bool auto_ = false;
  size_t listed_count_ = 0;  // candidates from the parameters (auto may add more at fit time)
  std::string blocks_;       // auto: as given
  std::vector<AutoBlock> candidate_blocks_;  // auto: per listed candidate (first < 0: every column)
  std::string listed_;                       // auto: the candidates as given
  std::string base_;
  std::vector<std::pair<std::string, std::string>> axes_;  // key -> "v1|v2|..."
  Protocol inner_;
  std::vector<GridCandidate> candidates_;
  std::unique_ptr<Classifier> chosen_;
};

std::unique_ptr<Classifier> make_grid_search_classifier(const Parameters& parameters);

// `auto`: inside each training fold only, an inner cross-validation (inner=, default
// kfold:5) picks among the presets and a standard k-NN grid (or candidates=a|b|c, whole
// specifications with ';' between a classifier's parameters) and refits the best on the fold.
// On a stacked table (features/stack.h), blocks=NAME:A-B|... makes it search pipelines too:
// every candidate once per block, on that block's columns (select:columns=A-B).
// The outer evaluation never lets the search see its test rows. It searches by successive
// halving: every candidate is first tried on one stratified hold-out split (70/30) of a
// stratified third (or ninth, ...) of the training rows, the best third go on to three times
// as many rows, and so on; the last few are compared by the inner protocol on all rows
// (rung_sizes). When the columns outnumber the rows, each candidate also runs behind
// `select:k=K` (K = rows / 4, at least 10): the K columns of largest ANOVA F on each inner
// training fold.
inline constexpr size_t kHalvingFactor = 3;
inline constexpr int64_t kSmallestRung = 30;
// The rows of each rung, the last all `rows`: one rung per halving until at most
// kHalvingFactor candidates are left, each earlier one a third of the next but at least
// kSmallestRung rows and 5 a class (so a small table repeats its size).
std::vector<int64_t> rung_sizes(int64_t rows, int class_count, size_t candidates);
std::vector<std::string> auto_candidates();
// `auto` given without blocks on a stacked table: the same with blocks=, so that it searches
// the table's pipelines; any other specification as it is.
std::string searched_specification(const std::string& specification,
                                   const std::vector<FeatureColumn>& columns);
std::unique_ptr<Classifier> make_auto_classifier(const Parameters& parameters);

}  // namespace tactile::ml

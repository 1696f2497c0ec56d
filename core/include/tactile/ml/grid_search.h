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

#include "tactile/ml/classifier.h"
#include "tactile/ml/evaluation.h"

namespace tactile::ml {

struct GridCandidate {
  std::string specification;  // "knn:k=3,metric=cosine"
  double inner_accuracy = 0.0;
};

class GridSearchClassifier : public Classifier {
 public:
  GridSearchClassifier(std::string base, std::vector<std::pair<std::string, std::string>> axes,
                       Protocol inner);
  // `auto`: the candidates are whole specifications (different classifiers), not one base's
  // grid; `listed` is what the user gave ("" = the default list).
  GridSearchClassifier(std::vector<std::string> specifications, Protocol inner, std::string listed);
  std::string name() const override { return auto_ ? "auto" : "grid-search"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // Every combination in search order, each with "base:key=value,..." for make_classifier.
  const std::vector<GridCandidate>& candidates() const { return candidates_; }
  // The specification chosen by the last fit (its base's effective parameters).
  std::string chosen_specification() const;

 private:
  const Classifier& chosen() const;

  bool auto_ = false;
  std::string listed_;  // auto: the candidates as given
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
// The outer evaluation never lets the search see its test rows.
std::vector<std::string> auto_candidates();
std::unique_ptr<Classifier> make_auto_classifier(const Parameters& parameters);

}  // namespace tactile::ml

#pragma once
// Gradient boosted trees: XGBoost (Debian's libxgboost-dev) through its C API.
//
// Preset `boosted-trees`, XGBoost's defaults (XGBClassifier: n_estimators 100, max_depth 6,
// learning_rate 0.3), objective multi:softprob, tree_method hist:
//   rounds = 100      boosting rounds (one tree per class per round)
//   depth = 6         max_depth
//   eta = 0.3         learning rate
//   subsample = 1     fraction of the rows each round draws
//   colsample = 1     fraction of the columns each tree draws (colsample_bytree)
// XGBoost's own seed is derived from the fit's seed; nthread is every core (set_threads).
// Its log never reaches the terminal (verbosity 0). Scores are the softprob class
// probabilities (rows sum to 1); feature importances are XGBoost's "gain" (mean gain of the
// splits on a feature), normalised to sum 1. The fitted model is saved as XGBoost's own JSON
// model, embedded as a string in our model JSON.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

class BoostedTrees : public Classifier {
 public:
  // `preset` is "boosted-trees"; throws tactile::Error naming the bad parameter.
  BoostedTrees(const std::string& preset, const Parameters& parameters);
  ~BoostedTrees() override;
  BoostedTrees(const BoostedTrees&) = delete;
  BoostedTrees& operator=(const BoostedTrees&) = delete;

  std::string name() const override { return "boosted-trees"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;
  std::vector<double> feature_importances() const override { return importances_; }

  // XGBoost's nthread (0: hardware concurrency).
  void set_threads(int threads) { threads_ = threads; }

 private:
  void free_booster();
  // Sets XGBoost's parameters on booster_ and runs the rounds on `train` (a DMatrixHandle).
  void train_booster(void* train, int class_count, uint64_t seed);

  int64_t rounds_ = 100;
  int64_t depth_ = 6;
  double eta_ = 0.3;
  double subsample_ = 1.0;
  double colsample_ = 1.0;
  int threads_ = 0;

  int class_count_ = 0;
  Eigen::Index feature_count_ = 0;
  void* booster_ = nullptr;  // XGBoost's BoosterHandle
  std::vector<double> importances_;
};

// Registry factory for `boosted-trees`.
std::unique_ptr<Classifier> make_boosted_trees_classifier(const Parameters& parameters);

}  // namespace tactile::ml

#pragma once
// Tree ensembles by bagging: every tree a CART tree (tree.h's growth, Gini) grown on a
// bootstrap sample of the rows (n draws with replacement; a row drawn k times weighs k).
//
// Presets:
//   bagged-trees   MATLAB Classification Learner "Bagged Trees" (fitcensemble Method 'Bag'):
//                  trees = 30, predictors = all, max_splits = n-1, min_leaf = 1
//   random-forest  scikit-learn RandomForestClassifier defaults: trees = 100,
//                  predictors = sqrt (floor(sqrt(P)) drawn at each split), grown until pure
//                  (max_splits = n-1, min_leaf = 1, a node of 2 or more samples may split)
// Parameters: `trees`, `predictors` (sqrt | all | a count), `max_splits` (n-1 | a count per
// tree), `min_leaf`.
//
// Tree t draws its bootstrap and its predictors from derive_seed(seed, t), and trees are fit
// on worker threads (set_threads; every core by default): the model is the same for any
// thread count. Scores are class probabilities: the mean over the trees of the class
// fractions in the leaf a row lands in. Feature importances: mean decrease in impurity (per
// tree normalised to sum 1, averaged over the trees, as scikit-learn's).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"
#include "tactile/ml/tree.h"

namespace tactile::ml {

class TreeEnsemble : public Classifier {
 public:
  // `preset` is "bagged-trees" or "random-forest"; throws tactile::Error naming the bad key.
  TreeEnsemble(const std::string& preset, const Parameters& parameters);

  std::string name() const override { return preset_; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  // Mean of the trees' leaf class fractions (rows sum to 1).
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;
  std::vector<double> feature_importances() const override { return importances_; }

  // Threads that fit trees (0: hardware concurrency). Never changes the model.
  void set_threads(int threads) { threads_ = threads; }
  const std::vector<std::vector<TreeNode>>& trees() const { return trees_; }

 private:
  std::string preset_;
  int64_t tree_count_ = 100;
  std::string predictors_ = "sqrt";  // "sqrt", "all" or a count
  int64_t max_splits_ = -1;          // -1: n-1
  int64_t min_leaf_ = 1;
  int threads_ = 0;

  int class_count_ = 0;
  Eigen::Index feature_count_ = 0;
  std::vector<std::vector<TreeNode>> trees_;
  std::vector<double> importances_;
};

// Registry factories for `bagged-trees` and `random-forest`.
std::unique_ptr<Classifier> make_bagged_trees_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_random_forest_classifier(const Parameters& parameters);

}  // namespace tactile::ml

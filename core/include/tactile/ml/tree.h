#pragma once
// Classification tree (CART): binary splits `x_f < t` chosen by the largest decrease of the
// Gini index, no surrogate splits, leaves scored by their training class fractions.
//
// Presets (MATLAB Classification Learner, fitctree defaults otherwise):
//   tree         max_splits = 100 (MATLAB "Fine Tree")
//   medium-tree  max_splits = 20  (MATLAB "Medium Tree"; TSA paper Table 4, spec §2.13)
// Parameters: `max_splits` (branch nodes at most), `min_parent` (a node needs at least this
// many samples to be split, fitctree's MinParentSize 10) and `min_leaf` (each child keeps at
// least this many, fitctree's MinLeafSize 1).
//
// Growth follows fitctree's depth control: the tree grows layer by layer; when a layer has
// more splittable nodes than splits left, the nodes with the largest impurity gain
// (node fraction x Gini decrease) are split first (ties: left to right). A node is split only
// if its Gini index decreases. Within a node the best split is searched over every feature
// and every midpoint between consecutive distinct values; ties go to the lower feature, then
// the lower threshold. Features are used as given: splits do not depend on scaling.
//
// The growth itself (grow_tree) is shared with the tree ensembles (forest.h): it takes
// per-row integer weights (a bootstrap's draw counts; 0 = not drawn) and may draw a random
// subset of the predictors at each split.

#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <random>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct TreeNode {
  int feature = -1;        // -1 for a leaf
  double threshold = 0.0;  // x[feature] < threshold goes left
  int left = -1;
  int right = -1;
  int64_t samples = 0;
  std::vector<double> class_fractions;  // of the training samples that reached the node
};

// Each column's rows in ascending value order (equal values by row), computed once per fit
// and shared by every tree grown on the same x: a large node sweeps a column in this order
// instead of sorting its rows again.
struct SortedColumns {
  std::vector<std::vector<int32_t>> order;  // order[feature][rank] = row
};
// `threads` sort columns in parallel (0 = hardware concurrency); the result does not depend
// on it.
SortedColumns sort_columns(const Matrix& x, int threads = 1);

struct TreeGrowth {
  int64_t max_splits = 100;  // branch nodes at most
  int64_t min_parent = 10;   // weighted samples a node needs to be split
  int64_t min_leaf = 1;      // weighted samples each child keeps at least
  // Predictors drawn at each split (0 = all, in column order). Drawn without replacement
  // from the tree's engine; when none of them gives a split that lowers the Gini index,
  // more are drawn until one does or all were tried (scikit-learn's rule).
  int64_t predictors = 0;
};

struct GrownTree {
  std::vector<TreeNode> nodes;  // node 0 is the root
  // Per feature: Σ over the splits on it of (node weight / root weight) x Gini decrease
  // (mean decrease in impurity, not normalised).
  Vector importances;
};

// CART growth as described above on the rows with weight > 0; `weights` has one entry per row
// of x. TreeNode::samples and class_fractions count weighted samples. `engine` is drawn from
// only when growth.predictors > 0.
GrownTree grow_tree(const Matrix& x, const std::vector<int>& y, int class_count,
                    const std::vector<int32_t>& weights, const SortedColumns& sorted,
                    const TreeGrowth& growth, std::mt19937_64& engine);

// The nodes of a tree as JSON and back; nodes_from_json checks every node (class fractions,
// feature index, children after their parent) and throws tactile::Error naming `where`.
nlohmann::json nodes_to_json(const std::vector<TreeNode>& nodes);
std::vector<TreeNode> nodes_from_json(const nlohmann::json& saved, int class_count,
                                      Eigen::Index feature_count, const std::string& where);
// The class fractions of the leaf that row `row` of x lands in.
const std::vector<double>& leaf_fractions(const std::vector<TreeNode>& nodes, const Matrix& x,
                                          Eigen::Index row);

class DecisionTree : public Classifier {
 public:
  // `preset` is "tree" or "medium-tree"; throws tactile::Error on an unknown key or a bad value.
  DecisionTree(const std::string& preset, const Parameters& parameters);

  std::string name() const override { return preset_; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  // Class fractions of the leaf each row lands in (rows sum to 1).
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;
  // Mean decrease in impurity per feature, normalised to sum 1 (all 0 without a split).
  std::vector<double> feature_importances() const override { return importances_; }

  // Node 0 is the root.
  const std::vector<TreeNode>& nodes() const { return nodes_; }
  int split_count() const;

 private:
  std::string preset_;
  int64_t max_splits_ = 100;
  int64_t min_parent_ = 10;
  int64_t min_leaf_ = 1;

  int class_count_ = 0;
  Eigen::Index feature_count_ = 0;
  std::vector<TreeNode> nodes_;
  std::vector<double> importances_;
};

std::vector<std::string> tree_preset_names();

// Registry factories for `tree` and `medium-tree`.
std::unique_ptr<Classifier> make_tree_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_medium_tree_classifier(const Parameters& parameters);

}  // namespace tactile::ml

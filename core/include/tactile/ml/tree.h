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

#include <cstdint>
#include <memory>
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
};

std::vector<std::string> tree_preset_names();

// Registry factories for `tree` and `medium-tree`.
std::unique_ptr<Classifier> make_tree_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_medium_tree_classifier(const Parameters& parameters);

}  // namespace tactile::ml

#include "tactile/ml/tree.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>

#include "tactile/error.h"
#include "tactile/ml/checks.h"
#include "thresholds.h"

namespace tactile::ml {

namespace {

struct Split {
  bool found = false;
  int feature = -1;
  double threshold = 0.0;
  double gini_decrease = 0.0;  // parent Gini minus the size-weighted Gini of the children
};

// Σ_k count_k² / n: the Gini index is 1 - this / n, so maximising the children's sum of it
// minimises their size-weighted Gini.
double purity(double sum_of_squares, int64_t samples) {
  return samples > 0 ? sum_of_squares / static_cast<double>(samples) : 0.0;
}

// CART's search: every feature, every cut between distinct sorted values, children no
// smaller than `min_leaf`; the largest Gini decrease, ties to the lower feature, then cut.
Split best_split(const Matrix& x, const std::vector<int>& y, const std::vector<int64_t>& rows,
                 int class_count, int64_t min_leaf) {
  const auto samples = static_cast<int64_t>(rows.size());
  std::vector<double> parent_counts(static_cast<size_t>(class_count), 0.0);
  for (const int64_t row : rows)
    parent_counts[static_cast<size_t>(y[static_cast<size_t>(row)])] += 1.0;
  double parent_squares = 0.0;
  for (const double count : parent_counts) parent_squares += count * count;
  const double parent_purity = purity(parent_squares, samples);

  Split best;
  double best_purity = parent_purity;
  const double tolerance = 1e-12 * static_cast<double>(samples);
  std::vector<std::pair<double, int>> sorted(rows.size());
  std::vector<double> left_counts(static_cast<size_t>(class_count));
  for (Eigen::Index feature = 0; feature < x.cols(); ++feature) {
    for (size_t index = 0; index < rows.size(); ++index)
      sorted[index] = {x(rows[index], feature), y[static_cast<size_t>(rows[index])]};
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::fill(left_counts.begin(), left_counts.end(), 0.0);
    double left_squares = 0.0;
    double right_squares = parent_squares;
    for (int64_t left = 1; left < samples; ++left) {
      const auto label = static_cast<size_t>(sorted[static_cast<size_t>(left - 1)].second);
      const double right_count = parent_counts[label] - left_counts[label];
      left_squares += 2.0 * left_counts[label] + 1.0;
      right_squares -= 2.0 * right_count - 1.0;
      left_counts[label] += 1.0;
      const double lower = sorted[static_cast<size_t>(left - 1)].first;
      const double upper = sorted[static_cast<size_t>(left)].first;
      if (!(lower < upper) || left < min_leaf || samples - left < min_leaf) continue;
      const double children_purity =
          purity(left_squares, left) + purity(right_squares, samples - left);
      if (children_purity > best_purity + tolerance) {
        best_purity = children_purity;
        best.found = true;
        best.feature = static_cast<int>(feature);
        best.threshold = midpoint(lower, upper);
      }
    }
  }
  best.gini_decrease = (best_purity - parent_purity) / static_cast<double>(samples);
  return best;
}

TreeNode make_node(const std::vector<int>& y, const std::vector<int64_t>& rows, int class_count) {
  TreeNode node;
  node.samples = static_cast<int64_t>(rows.size());
  node.class_fractions.assign(static_cast<size_t>(class_count), 0.0);
  for (const int64_t row : rows)
    node.class_fractions[static_cast<size_t>(y[static_cast<size_t>(row)])] += 1.0;
  for (double& fraction : node.class_fractions) fraction /= static_cast<double>(node.samples);
  return node;
}

bool is_pure(const TreeNode& node) {
  return std::any_of(node.class_fractions.begin(), node.class_fractions.end(),
                     [](double fraction) { return fraction == 1.0; });
}

}  // namespace

std::vector<std::string> tree_preset_names() { return {"tree", "medium-tree"}; }

DecisionTree::DecisionTree(const std::string& preset, const Parameters& parameters)
    : preset_(preset) {
  if (preset == "tree")
    max_splits_ = 100;
  else if (preset == "medium-tree")
    max_splits_ = 20;
  else
    throw Error(parameters.where(), "no tree preset named '" + preset + "'");
  parameters.expect_only({"max_splits", "min_parent", "min_leaf"});
  max_splits_ = parameters.integer("max_splits", max_splits_);
  min_parent_ = parameters.integer("min_parent", min_parent_);
  min_leaf_ = parameters.integer("min_leaf", min_leaf_);
  if (max_splits_ < 0) throw Error(parameters.where(), "max_splits must be 0 or more");
  if (min_parent_ < 2) throw Error(parameters.where(), "min_parent must be 2 or more");
  if (min_leaf_ < 1) throw Error(parameters.where(), "min_leaf must be 1 or more");
}

Parameters DecisionTree::parameters() const {
  Parameters parameters;
  parameters.set("max_splits", std::to_string(max_splits_));
  parameters.set("min_parent", std::to_string(min_parent_));
  parameters.set("min_leaf", std::to_string(min_leaf_));
  return parameters;
}

int DecisionTree::split_count() const {
  return static_cast<int>(std::count_if(nodes_.begin(), nodes_.end(),
                                        [](const TreeNode& node) { return node.feature >= 0; }));
}

void DecisionTree::fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t) {
  check_training_set(x, y, class_count, preset_);
  class_count_ = class_count;
  feature_count_ = x.cols();
  nodes_.clear();

  std::vector<std::vector<int64_t>> node_rows(1);
  node_rows[0].resize(static_cast<size_t>(x.rows()));
  std::iota(node_rows[0].begin(), node_rows[0].end(), int64_t{0});
  nodes_.push_back(make_node(y, node_rows[0], class_count));

  const double total = static_cast<double>(x.rows());
  std::vector<int> layer = {0};
  int64_t splits_left = max_splits_;
  while (!layer.empty() && splits_left > 0) {
    struct Candidate {
      size_t position;  // left-to-right place in the layer
      Split split;
      double gain;
    };
    std::vector<Candidate> candidates;
    for (size_t position = 0; position < layer.size(); ++position) {
      const int id = layer[position];
      const TreeNode& node = nodes_[static_cast<size_t>(id)];
      if (node.samples < min_parent_ || is_pure(node)) continue;
      const Split split =
          best_split(x, y, node_rows[static_cast<size_t>(id)], class_count, min_leaf_);
      if (!split.found) continue;
      candidates.push_back(
          {position, split, static_cast<double>(node.samples) / total * split.gini_decrease});
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.gain > b.gain; });
    if (static_cast<int64_t>(candidates.size()) > splits_left)
      candidates.resize(static_cast<size_t>(splits_left));
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.position < b.position; });
    splits_left -= static_cast<int64_t>(candidates.size());

    std::vector<int> next_layer;
    for (const Candidate& candidate : candidates) {
      const int id = layer[candidate.position];
      std::vector<int64_t> left_rows;
      std::vector<int64_t> right_rows;
      for (const int64_t row : node_rows[static_cast<size_t>(id)])
        (x(row, candidate.split.feature) < candidate.split.threshold ? left_rows : right_rows)
            .push_back(row);
      const int left = static_cast<int>(nodes_.size());
      nodes_.push_back(make_node(y, left_rows, class_count));
      nodes_.push_back(make_node(y, right_rows, class_count));
      node_rows.push_back(std::move(left_rows));
      node_rows.push_back(std::move(right_rows));
      node_rows[static_cast<size_t>(id)].clear();
      TreeNode& parent = nodes_[static_cast<size_t>(id)];
      parent.feature = candidate.split.feature;
      parent.threshold = candidate.split.threshold;
      parent.left = left;
      parent.right = left + 1;
      next_layer.push_back(left);
      next_layer.push_back(left + 1);
    }
    layer = std::move(next_layer);
  }
}

Matrix DecisionTree::scores(const Matrix& x) const {
  check_fitted(!nodes_.empty(), preset_);
  check_query(x, feature_count_, preset_);
  Matrix scores(x.rows(), class_count_);
  for (Eigen::Index row = 0; row < x.rows(); ++row) {
    const TreeNode* node = &nodes_[0];
    while (node->feature >= 0)
      node = &nodes_[static_cast<size_t>(x(row, node->feature) < node->threshold ? node->left
                                                                                 : node->right)];
    scores.row(row) =
        Eigen::Map<const Vector>(node->class_fractions.data(), class_count_).transpose();
  }
  return scores;
}

nlohmann::json DecisionTree::save() const {
  if (nodes_.empty()) throw Error(preset_, "save() before fit()");
  nlohmann::json nodes = nlohmann::json::array();
  for (const TreeNode& node : nodes_)
    nodes.push_back({{"feature", node.feature},
                     {"threshold", node.threshold},
                     {"left", node.left},
                     {"right", node.right},
                     {"samples", node.samples},
                     {"class_fractions", node.class_fractions}});
  return {{"class_count", class_count_},
          {"feature_count", feature_count_},
          {"nodes", std::move(nodes)}};
}

void DecisionTree::load(const nlohmann::json& model) {
  const std::string where = preset_ + " model";
  try {
    const int class_count = model.at("class_count").get<int>();
    const auto feature_count = model.at("feature_count").get<Eigen::Index>();
    if (class_count < 1 || feature_count < 1)
      throw Error(where, "bad class_count or feature_count");
    std::vector<TreeNode> nodes;
    for (const auto& saved : model.at("nodes")) {
      TreeNode node;
      node.feature = saved.at("feature").get<int>();
      node.threshold = saved.at("threshold").get<double>();
      node.left = saved.at("left").get<int>();
      node.right = saved.at("right").get<int>();
      node.samples = saved.at("samples").get<int64_t>();
      node.class_fractions = saved.at("class_fractions").get<std::vector<double>>();
      nodes.push_back(std::move(node));
    }
    if (nodes.empty()) throw Error(where, "no nodes");
    for (size_t id = 0; id < nodes.size(); ++id) {
      const TreeNode& node = nodes[id];
      const std::string name = "node " + std::to_string(id);
      if (static_cast<int>(node.class_fractions.size()) != class_count)
        throw Error(where, name + " has " + std::to_string(node.class_fractions.size()) +
                               " class fractions");
      if (node.feature < 0) continue;
      // Children come after their parent, so a saved tree cannot loop.
      const auto count = static_cast<int>(nodes.size());
      if (node.feature >= feature_count || node.left <= static_cast<int>(id) ||
          node.left >= count || node.right <= static_cast<int>(id) || node.right >= count ||
          !std::isfinite(node.threshold))
        throw Error(where, name + " has a bad feature, threshold or child");
    }
    class_count_ = class_count;
    feature_count_ = feature_count;
    nodes_ = std::move(nodes);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

std::unique_ptr<Classifier> make_tree_classifier(const Parameters& parameters) {
  return std::make_unique<DecisionTree>("tree", parameters);
}

std::unique_ptr<Classifier> make_medium_tree_classifier(const Parameters& parameters) {
  return std::make_unique<DecisionTree>("medium-tree", parameters);
}

}  // namespace tactile::ml

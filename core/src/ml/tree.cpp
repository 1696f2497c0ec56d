#include "tactile/ml/tree.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"
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
double purity(double sum_of_squares, double samples) {
  return samples > 0.0 ? sum_of_squares / samples : 0.0;
}

// What one tree's growth shares between its nodes: the data, each row's node, and scratch
// space reused by every split search.
struct TreeGrower {
  const Matrix& x;
  const std::vector<int>& y;
  const std::vector<int32_t>& weights;
  const SortedColumns& sorted;
  int class_count;
  int64_t min_leaf;
  std::vector<int32_t> row_node;                    // -1: not drawn, or in a node not split
  std::vector<std::pair<double, int32_t>> ordered;  // one node's (value, row), ascending
  std::vector<double> left_counts;
  std::vector<int32_t> feature_pool;  // a permutation of the columns, drawn from in place
};

// The node's rows in ascending order of one feature (equal values by row): a large node
// filters the column's presorted order, a small one sorts its own rows.
void order_node_rows(TreeGrower& grower, Eigen::Index feature, int node,
                     const std::vector<int32_t>& rows) {
  grower.ordered.clear();
  const auto all = static_cast<double>(grower.x.rows());
  const auto count = static_cast<double>(rows.size());
  if (2.0 * count * std::log2(count + 1.0) > all) {
    for (const int32_t row : grower.sorted.order[static_cast<size_t>(feature)])
      if (grower.row_node[static_cast<size_t>(row)] == node)
        grower.ordered.emplace_back(grower.x(row, feature), row);
    return;
  }
  for (const int32_t row : rows) grower.ordered.emplace_back(grower.x(row, feature), row);
  std::sort(grower.ordered.begin(), grower.ordered.end());
}

struct NodeTotals {
  std::vector<double> counts;  // weighted, per class
  double samples = 0.0;
  double squares = 0.0;  // Σ counts²
};

// Every cut of one feature between distinct values, children no lighter than `min_leaf`;
// keeps the cut in `best` when it raises the children's purity above `best_purity`.
void sweep_feature(TreeGrower& grower, Eigen::Index feature, int node,
                   const std::vector<int32_t>& rows, const NodeTotals& totals, Split& best,
                   double& best_purity) {
  order_node_rows(grower, feature, node, rows);
  std::fill(grower.left_counts.begin(), grower.left_counts.end(), 0.0);
  const double tolerance = 1e-12 * totals.samples;
  const auto min_leaf = static_cast<double>(grower.min_leaf);
  double left_samples = 0.0;
  double left_squares = 0.0;
  double right_squares = totals.squares;
  for (size_t index = 0; index + 1 < grower.ordered.size(); ++index) {
    const int32_t row = grower.ordered[index].second;
    const auto label = static_cast<size_t>(grower.y[static_cast<size_t>(row)]);
    const auto weight = static_cast<double>(grower.weights[static_cast<size_t>(row)]);
    // (c + w)² = c² + 2cw + w² on the left, (c - w)² = c² - 2cw + w² on the right: exact in
    // doubles, as the counts are whole numbers.
    const double right_count = totals.counts[label] - grower.left_counts[label];
    left_squares += 2.0 * grower.left_counts[label] * weight + weight * weight;
    right_squares -= 2.0 * right_count * weight - weight * weight;
    grower.left_counts[label] += weight;
    left_samples += weight;
    const double lower = grower.ordered[index].first;
    const double upper = grower.ordered[index + 1].first;
    if (!(lower < upper) || left_samples < min_leaf || totals.samples - left_samples < min_leaf)
      continue;
    const double children_purity =
        purity(left_squares, left_samples) + purity(right_squares, totals.samples - left_samples);
    if (children_purity > best_purity + tolerance) {
      best_purity = children_purity;
      best.found = true;
      best.feature = static_cast<int>(feature);
      best.threshold = midpoint(lower, upper);
    }
  }
}

// CART's search: every feature (or `predictors` drawn ones, more while none lowers the
// Gini index), every cut between distinct sorted values; the largest Gini decrease, ties to
// the feature searched first (the lower one when all are searched), then the lower cut.
Split best_split(TreeGrower& grower, int node, const std::vector<int32_t>& rows, int64_t predictors,
                 std::mt19937_64& engine) {
  NodeTotals totals;
  totals.counts.assign(static_cast<size_t>(grower.class_count), 0.0);
  for (const int32_t row : rows) {
    const auto weight = static_cast<double>(grower.weights[static_cast<size_t>(row)]);
    totals.counts[static_cast<size_t>(grower.y[static_cast<size_t>(row)])] += weight;
    totals.samples += weight;
  }
  for (const double count : totals.counts) totals.squares += count * count;
  const double parent_purity = purity(totals.squares, totals.samples);

  Split best;
  double best_purity = parent_purity;
  const Eigen::Index features = grower.x.cols();
  if (predictors <= 0 || predictors >= features) {
    for (Eigen::Index feature = 0; feature < features; ++feature)
      sweep_feature(grower, feature, node, rows, totals, best, best_purity);
  } else {
    // Fisher-Yates from the front, one draw per feature searched.
    auto& pool = grower.feature_pool;
    for (size_t drawn = 0; drawn < pool.size(); ++drawn) {
      if (static_cast<int64_t>(drawn) >= predictors && best.found) break;
      const size_t pick = drawn + uniform_index(engine, pool.size() - drawn);
      std::swap(pool[drawn], pool[pick]);
      sweep_feature(grower, pool[drawn], node, rows, totals, best, best_purity);
    }
  }
  best.gini_decrease = (best_purity - parent_purity) / totals.samples;
  return best;
}

TreeNode make_node(const std::vector<int>& y, const std::vector<int32_t>& weights,
                   const std::vector<int32_t>& rows, int class_count) {
  TreeNode node;
  node.class_fractions.assign(static_cast<size_t>(class_count), 0.0);
  for (const int32_t row : rows) {
    const int32_t weight = weights[static_cast<size_t>(row)];
    node.class_fractions[static_cast<size_t>(y[static_cast<size_t>(row)])] += weight;
    node.samples += weight;
  }
  for (double& fraction : node.class_fractions) fraction /= static_cast<double>(node.samples);
  return node;
}

bool is_pure(const TreeNode& node) {
  return std::any_of(node.class_fractions.begin(), node.class_fractions.end(),
                     [](double fraction) { return fraction == 1.0; });
}

}  // namespace

SortedColumns sort_columns(const Matrix& x, int threads) {
  if (x.rows() > std::numeric_limits<int32_t>::max())
    throw Error("tree", "more rows than a tree can index");
  SortedColumns sorted;
  sorted.order.resize(static_cast<size_t>(x.cols()));
  std::atomic<Eigen::Index> next{0};
  const auto work = [&] {
    for (Eigen::Index feature = next++; feature < x.cols(); feature = next++) {
      auto& order = sorted.order[static_cast<size_t>(feature)];
      order.resize(static_cast<size_t>(x.rows()));
      std::iota(order.begin(), order.end(), int32_t{0});
      std::stable_sort(order.begin(), order.end(),
                       [&](int32_t a, int32_t b) { return x(a, feature) < x(b, feature); });
    }
  };
  const int workers = threads > 0 ? threads : thread_budget();
  std::vector<std::thread> pool;
  for (int worker = 1; worker < workers && worker < x.cols(); ++worker) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  return sorted;
}

GrownTree grow_tree(const Matrix& x, const std::vector<int>& y, int class_count,
                    const std::vector<int32_t>& weights, const SortedColumns& sorted,
                    const TreeGrowth& growth, std::mt19937_64& engine) {
  TreeGrower grower{x, y, weights, sorted, class_count, growth.min_leaf, {}, {}, {}, {}};
  grower.row_node.assign(static_cast<size_t>(x.rows()), -1);
  grower.left_counts.resize(static_cast<size_t>(class_count));
  grower.feature_pool.resize(static_cast<size_t>(x.cols()));
  std::iota(grower.feature_pool.begin(), grower.feature_pool.end(), int32_t{0});

  GrownTree tree;
  tree.importances = Vector::Zero(x.cols());
  std::vector<std::vector<int32_t>> node_rows(1);
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    if (weights[static_cast<size_t>(row)] > 0) {
      node_rows[0].push_back(static_cast<int32_t>(row));
      grower.row_node[static_cast<size_t>(row)] = 0;
    }
  if (node_rows[0].empty()) throw Error("tree", "no rows to grow a tree on");
  tree.nodes.push_back(make_node(y, weights, node_rows[0], class_count));
  auto& nodes = tree.nodes;

  const auto total = static_cast<double>(nodes[0].samples);
  std::vector<int> layer = {0};
  int64_t splits_left = growth.max_splits;
  while (!layer.empty() && splits_left > 0) {
    struct Candidate {
      size_t position;  // left-to-right place in the layer
      Split split;
      double gain;
    };
    std::vector<Candidate> candidates;
    for (size_t position = 0; position < layer.size(); ++position) {
      const int id = layer[position];
      const TreeNode& node = nodes[static_cast<size_t>(id)];
      if (node.samples < growth.min_parent || is_pure(node)) continue;
      const Split split =
          best_split(grower, id, node_rows[static_cast<size_t>(id)], growth.predictors, engine);
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

    // Rows of the nodes left unsplit leave the search.
    std::vector<bool> splitting(layer.size(), false);
    for (const Candidate& candidate : candidates) splitting[candidate.position] = true;
    for (size_t position = 0; position < layer.size(); ++position)
      if (!splitting[position]) {
        auto& rows = node_rows[static_cast<size_t>(layer[position])];
        for (const int32_t row : rows) grower.row_node[static_cast<size_t>(row)] = -1;
        rows = {};
      }

    std::vector<int> next_layer;
    for (const Candidate& candidate : candidates) {
      const int id = layer[candidate.position];
      const int left = static_cast<int>(nodes.size());
      std::vector<int32_t> left_rows;
      std::vector<int32_t> right_rows;
      for (const int32_t row : node_rows[static_cast<size_t>(id)]) {
        const bool goes_left = x(row, candidate.split.feature) < candidate.split.threshold;
        (goes_left ? left_rows : right_rows).push_back(row);
        grower.row_node[static_cast<size_t>(row)] = goes_left ? left : left + 1;
      }
      nodes.push_back(make_node(y, weights, left_rows, class_count));
      nodes.push_back(make_node(y, weights, right_rows, class_count));
      node_rows.push_back(std::move(left_rows));
      node_rows.push_back(std::move(right_rows));
      node_rows[static_cast<size_t>(id)] = {};
      TreeNode& parent = nodes[static_cast<size_t>(id)];
      parent.feature = candidate.split.feature;
      parent.threshold = candidate.split.threshold;
      parent.left = left;
      parent.right = left + 1;
      tree.importances(candidate.split.feature) += candidate.gain;
      next_layer.push_back(left);
      next_layer.push_back(left + 1);
    }
    layer = std::move(next_layer);
  }
  return tree;
}

nlohmann::json nodes_to_json(const std::vector<TreeNode>& nodes) {
  nlohmann::json saved = nlohmann::json::array();
  for (const TreeNode& node : nodes)
    saved.push_back({{"feature", node.feature},
                     {"threshold", node.threshold},
                     {"left", node.left},
                     {"right", node.right},
                     {"samples", node.samples},
                     {"class_fractions", node.class_fractions}});
  return saved;
}

std::vector<TreeNode> nodes_from_json(const nlohmann::json& saved, int class_count,
                                      Eigen::Index feature_count, const std::string& where) {
  std::vector<TreeNode> nodes;
  for (const auto& entry : saved) {
    TreeNode node;
    node.feature = entry.at("feature").get<int>();
    node.threshold = entry.at("threshold").get<double>();
    node.left = entry.at("left").get<int>();
    node.right = entry.at("right").get<int>();
    node.samples = entry.at("samples").get<int64_t>();
    node.class_fractions = entry.at("class_fractions").get<std::vector<double>>();
    nodes.push_back(std::move(node));
  }
  if (nodes.empty()) throw Error(where, "no nodes");
  for (size_t id = 0; id < nodes.size(); ++id) {
    const TreeNode& node = nodes[id];
    const std::string name = "node " + std::to_string(id);
    if (static_cast<int>(node.class_fractions.size()) != class_count)
      throw Error(
          where, name + " has " + std::to_string(node.class_fractions.size()) + " class fractions");
    if (node.feature < 0) continue;
    // Children come after their parent, so a saved tree cannot loop.
    const auto count = static_cast<int>(nodes.size());
    if (node.feature >= feature_count || node.left <= static_cast<int>(id) || node.left >= count ||
        node.right <= static_cast<int>(id) || node.right >= count || !std::isfinite(node.threshold))
      throw Error(where, name + " has a bad feature, threshold or child");
  }
  return nodes;
}

const std::vector<double>& leaf_fractions(const std::vector<TreeNode>& nodes, const Matrix& x,
                                          Eigen::Index row) {
  const TreeNode* node = &nodes[0];
  while (node->feature >= 0)
    node = &nodes[static_cast<size_t>(x(row, node->feature) < node->threshold ? node->left
                                                                              : node->right)];
  return node->class_fractions;
}

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
  importances_.clear();
  TreeGrowth growth;
  growth.max_splits = max_splits_;
  growth.min_parent = min_parent_;
  growth.min_leaf = min_leaf_;
  const std::vector<int32_t> weights(static_cast<size_t>(x.rows()), 1);
  std::mt19937_64 unused;  // every predictor is searched: nothing is drawn
  GrownTree tree = grow_tree(x, y, class_count, weights, sort_columns(x), growth, unused);
  nodes_ = std::move(tree.nodes);
  const double sum = tree.importances.sum();
  if (sum > 0.0) tree.importances /= sum;
  importances_.assign(tree.importances.data(), tree.importances.data() + tree.importances.size());
}

Matrix DecisionTree::scores(const Matrix& x) const {
  check_fitted(!nodes_.empty(), preset_);
  check_query(x, feature_count_, preset_);
  Matrix scores(x.rows(), class_count_);
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    scores.row(row) =
        Eigen::Map<const Vector>(leaf_fractions(nodes_, x, row).data(), class_count_).transpose();
  return scores;
}

nlohmann::json DecisionTree::save() const {
  if (nodes_.empty()) throw Error(preset_, "save() before fit()");
  return {{"class_count", class_count_},
          {"feature_count", feature_count_},
          {"importances", importances_},
          {"nodes", nodes_to_json(nodes_)}};
}

void DecisionTree::load(const nlohmann::json& model) {
  const std::string where = preset_ + " model";
  try {
    const int class_count = model.at("class_count").get<int>();
    const auto feature_count = model.at("feature_count").get<Eigen::Index>();
    if (class_count < 1 || feature_count < 1)
      throw Error(where, "bad class_count or feature_count");
    std::vector<TreeNode> nodes =
        nodes_from_json(model.at("nodes"), class_count, feature_count, where);
    // Models saved before importances were kept have none.
    std::vector<double> importances;
    if (model.contains("importances"))
      importances = model.at("importances").get<std::vector<double>>();
    if (!importances.empty() && static_cast<Eigen::Index>(importances.size()) != feature_count)
      throw Error(where, "importances do not match feature_count");
    class_count_ = class_count;
    feature_count_ = feature_count;
    nodes_ = std::move(nodes);
    importances_ = std::move(importances);
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

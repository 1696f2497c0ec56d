#include "tactile/ml/forest.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

// Predictors drawn per split for P columns: 0 means all of them.
int64_t ensemble_predictors(const std::string& predictors, Eigen::Index columns) {
  if (predictors == "all") return 0;
  if (predictors == "sqrt")
    return std::max<int64_t>(1, static_cast<int64_t>(std::sqrt(static_cast<double>(columns))));
  return std::min<int64_t>(std::stoll(predictors), columns);
}

}  // namespace

TreeEnsemble::TreeEnsemble(const std::string& preset, const Parameters& parameters)
    : preset_(preset) {
  if (preset == "bagged-trees") {
    tree_count_ = 30;
    predictors_ = "all";
  } else if (preset == "random-forest") {
    tree_count_ = 100;
    predictors_ = "sqrt";
  } else {
    throw Error(parameters.where(), "no tree ensemble preset named '" + preset + "'");
  }
  parameters.expect_only({"trees", "predictors", "max_splits", "min_leaf"});
  tree_count_ = parameters.integer("trees", tree_count_);
  predictors_ = parameters.text("predictors", predictors_);
  if (parameters.text("max_splits", "n-1") != "n-1") {
    max_splits_ = parameters.integer("max_splits", max_splits_);
    if (max_splits_ < 0)
      throw Error(parameters.where(), "max_splits must be n-1 or a count of 0 or more");
  }
  min_leaf_ = parameters.integer("min_leaf", min_leaf_);
  if (tree_count_ < 1) throw Error(parameters.where(), "trees must be 1 or more");
  if (predictors_ != "sqrt" && predictors_ != "all") {
    const int64_t count = parameters.integer("predictors", 0);
    if (count < 1)
      throw Error(parameters.where(), "predictors must be sqrt, all or a count of 1 or more");
    predictors_ = std::to_string(count);
  }
  if (min_leaf_ < 1) throw Error(parameters.where(), "min_leaf must be 1 or more");
}

Parameters TreeEnsemble::parameters() const {
  Parameters parameters;
  parameters.set("trees", std::to_string(tree_count_));
  parameters.set("predictors", predictors_);
  parameters.set("max_splits", max_splits_ < 0 ? "n-1" : std::to_string(max_splits_));
  parameters.set("min_leaf", std::to_string(min_leaf_));
  return parameters;
}

void TreeEnsemble::fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) {
  check_training_set(x, y, class_count, preset_);
  class_count_ = class_count;
  feature_count_ = x.cols();
  trees_.clear();
  importances_.clear();

  const int threads = std::clamp<int>(threads_ > 0 ? threads_ : thread_budget(), 1,
                                      static_cast<int>(std::min<int64_t>(tree_count_, 64)));
  const SortedColumns sorted = sort_columns(x, threads);
  TreeGrowth growth;
  growth.max_splits = max_splits_ < 0 ? std::numeric_limits<int64_t>::max() : max_splits_;
  growth.min_parent = 2;
  growth.min_leaf = min_leaf_;
  growth.predictors = ensemble_predictors(predictors_, x.cols());

  const auto rows = static_cast<uint64_t>(x.rows());
  std::vector<GrownTree> grown(static_cast<size_t>(tree_count_));
  std::vector<std::exception_ptr> failures(static_cast<size_t>(threads));
  std::atomic<int64_t> next{0};
  std::atomic<bool> stop{false};
  const std::atomic<bool>* cancel = current_cancel_flag();
  const auto work = [&](int worker) {
    const CancelScope scope(cancel);
    try {
      for (int64_t tree = next++; tree < tree_count_ && !stop.load(); tree = next++) {
        if (cancel_requested()) throw Error(preset_, "cancelled");
        std::mt19937_64 engine(derive_seed(seed, static_cast<uint64_t>(tree)));
        std::vector<int32_t> weights(static_cast<size_t>(rows), 0);
        for (uint64_t draw = 0; draw < rows; ++draw) ++weights[uniform_index(engine, rows)];
        grown[static_cast<size_t>(tree)] =
            grow_tree(x, y, class_count, weights, sorted, growth, engine);
      }
    } catch (...) {
      failures[static_cast<size_t>(worker)] = std::current_exception();
      stop.store(true);
    }
  };
  std::vector<std::thread> pool;
  for (int worker = 1; worker < threads; ++worker) pool.emplace_back(work, worker);
  work(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);

  // scikit-learn's feature_importances_: each tree's normalised, then their mean, normalised.
  Vector importances = Vector::Zero(x.cols());
  for (GrownTree& tree : grown) {
    const double sum = tree.importances.sum();
    if (sum > 0.0) importances += tree.importances / sum;
    trees_.push_back(std::move(tree.nodes));
  }
  const double sum = importances.sum();
  if (sum > 0.0) importances /= sum;
  importances_.assign(importances.data(), importances.data() + importances.size());
}

Matrix TreeEnsemble::scores(const Matrix& x) const {
  check_fitted(!trees_.empty(), preset_);
  check_query(x, feature_count_, preset_);
  Matrix scores = Matrix::Zero(x.rows(), class_count_);
  for (const auto& tree : trees_)
    for (Eigen::Index row = 0; row < x.rows(); ++row)
      scores.row(row) +=
          Eigen::Map<const Vector>(leaf_fractions(tree, x, row).data(), class_count_).transpose();
  return scores / static_cast<double>(trees_.size());
}

nlohmann::json TreeEnsemble::save() const {
  if (trees_.empty()) throw Error(preset_, "save() before fit()");
  nlohmann::json trees = nlohmann::json::array();
  for (const auto& tree : trees_) trees.push_back(nodes_to_json(tree));
  return {{"class_count", class_count_},
          {"feature_count", feature_count_},
          {"importances", importances_},
          {"trees", std::move(trees)}};
}

void TreeEnsemble::load(const nlohmann::json& model) {
  const std::string where = preset_ + " model";
  try {
    const int class_count = model.at("class_count").get<int>();
    const auto feature_count = model.at("feature_count").get<Eigen::Index>();
    if (class_count < 1 || feature_count < 1)
      throw Error(where, "bad class_count or feature_count");
    std::vector<std::vector<TreeNode>> trees;
    for (const auto& saved : model.at("trees"))
      trees.push_back(nodes_from_json(saved, class_count, feature_count,
                                      where + ", tree " + std::to_string(trees.size())));
    if (trees.empty()) throw Error(where, "no trees");
    auto importances = model.at("importances").get<std::vector<double>>();
    if (static_cast<Eigen::Index>(importances.size()) != feature_count)
      throw Error(where, "importances do not match feature_count");
    class_count_ = class_count;
    feature_count_ = feature_count;
    trees_ = std::move(trees);
    importances_ = std::move(importances);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

std::unique_ptr<Classifier> make_bagged_trees_classifier(const Parameters& parameters) {
  return std::make_unique<TreeEnsemble>("bagged-trees", parameters);
}

std::unique_ptr<Classifier> make_random_forest_classifier(const Parameters& parameters) {
  return std::make_unique<TreeEnsemble>("random-forest", parameters);
}

}  // namespace tactile::ml

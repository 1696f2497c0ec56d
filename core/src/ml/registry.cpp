// The table of classifiers: one line per name, name -> factory. Adding a classifier is one
// #include and one line in classifier_table(); evaluation, the command line and the
// workbench pick it up from here.
#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/ml/boosted_trees.h"
#include "tactile/ml/clafic.h"
#include "tactile/ml/classifier.h"
#include "tactile/ml/column_selection.h"
#include "tactile/ml/em.h"
#include "tactile/ml/forest.h"
#include "tactile/ml/gaussian.h"
#include "tactile/ml/grid_search.h"
#include "tactile/ml/knn.h"
#include "tactile/ml/logitboost.h"
#include "tactile/ml/naive_bayes.h"
#include "tactile/ml/ridge.h"
#include "tactile/ml/som.h"
#include "tactile/ml/svm.h"
#include "tactile/ml/tree.h"

namespace tactile::ml {

namespace {

// A factory reads its parameters (rejecting unknown keys with expect_only) and returns an
// unfitted classifier.
using ClassifierFactory = std::unique_ptr<Classifier> (*)(const Parameters&);

struct ClassifierRow {
  const char* name;
  const char* description;
  ClassifierFactory make;
  bool preset = true;  // false: a search or wrapper of other classifiers
  int64_t widest = 0;  // ClassifierEntry::widest
};

// ClassifierEntry::widest of the covariance models (EM's ten restarts of a mixture too), and
// of those that go over every column many times (every node of every boosted or bagged tree).
// The SOM is not one: it trains a wide table in the span of its rows (som.h).
constexpr int64_t kWidestCovariance = 500;
constexpr int64_t kWidestScanned = 2000;
// Boosting weighs every column's histogram in every node of 100 trees per class.
constexpr int64_t kWidestBoosted = 500;

// Listed order is the order `tactile evaluate --list` prints.
const std::vector<ClassifierRow>& classifier_table() {
  static const std::vector<ClassifierRow> table = {
      // {"name", "one-line description", make_name_classifier},  (include "tactile/ml/family.h")
      {"linear-svm",
       "C-SVC, linear kernel, standardised, one-vs-one (c, scale, probability, weights=balanced)",
       make_linear_svm_classifier},
      {"quadratic-svm",
       "MATLAB Quadratic SVM: (1+x'z/s^2)^2, scale auto per pair; weights=balanced for rare "
       "classes",
       make_quadratic_svm_classifier},
      {"cubic-svm",
       "MATLAB Cubic SVM: (1+x'z/s^2)^3, scale auto per pair; weights=balanced for rare classes",
       make_cubic_svm_classifier},
      {"fine-gaussian-svm",
       "MATLAB Fine Gaussian SVM: s = sqrt(P)/4; weights=balanced for rare classes",
       make_fine_gaussian_svm_classifier},
      {"medium-gaussian-svm",
       "MATLAB Medium Gaussian SVM: s = sqrt(P); weights=balanced for rare classes",
       make_medium_gaussian_svm_classifier},
      {"coarse-gaussian-svm",
       "MATLAB Coarse Gaussian SVM: s = 4 sqrt(P); weights=balanced for rare classes",
       make_coarse_gaussian_svm_classifier},
      {"knn",
       "k nearest neighbours (k, metric=euclidean|cosine, weights, "
       "standardize=false|true|range)",
       make_knn_classifier},
      {"cosine-knn", "MATLAB Cosine KNN: cosine distance, k=10, equal weights, standardised",
       make_cosine_knn_classifier},
      {"weighted-knn", "MATLAB Weighted KNN: Euclidean, k=10, weights 1/d^2, standardised",
       make_weighted_knn_classifier},
      {"subspace-knn", "MATLAB Subspace KNN: 30 1-NN learners on random halves of the predictors",
       make_subspace_knn_classifier},
      {"grid-search",
       "hyper-parameter grid by inner CV on the training fold: base=knn,k=1|3|5,inner=kfold:3",
       make_grid_search_classifier, false},
      {"grid", "short name of grid-search", make_grid_search_classifier, false},
      {"auto",
       "picks among the presets and a k-NN grid by inner CV on the training fold, refits the best "
       "(inner, candidates=a|b)",
       make_auto_classifier, false},
      {"select",
       "a base classifier on some columns: a block (columns=A-B) and/or the k with the largest "
       "ANOVA F on the training fold (k, base)",
       make_select_classifier, false},
      {"tree", "CART, Gini, max_splits=100 (MATLAB Fine Tree)", make_tree_classifier},
      {"medium-tree", "CART, Gini, max_splits=20 (MATLAB Medium Tree)",
       make_medium_tree_classifier},
      {"bagged-trees",
       "MATLAB Bagged Trees: 30 deep CART trees on bootstrap samples, all predictors (trees, "
       "predictors, max_splits, min_leaf)",
       make_bagged_trees_classifier, true, kWidestScanned},
      {"random-forest",
       "random forest, scikit-learn defaults: 100 trees, sqrt(P) predictors per split, grown "
       "until pure (trees, predictors=sqrt|all|N, max_splits, min_leaf)",
       make_random_forest_classifier},
      {"boosted-trees",
       "XGBoost gradient boosted trees, softprob (rounds=100, depth=6, eta=0.3, subsample, "
       "colsample)",
       make_boosted_trees_classifier, true, kWidestBoosted},
      {"logitboost", "LogitBoost with stumps (learners=10, learning_rate=1; Weka defaults)",
       make_logitboost_classifier},
      {"gaussian-ml",
       "Gaussian maximum likelihood, full covariance per class, equal priors (smart fur)",
       make_gaussian_ml_classifier, true, kWidestCovariance},
      {"gaussian-nb", "MATLAB Gaussian Naive Bayes (var_smoothing, priors)",
       make_gaussian_nb_classifier},
      {"kernel-nb", "MATLAB Kernel Naive Bayes: normal kernel, unbounded support, Silverman width",
       make_kernel_nb_classifier},
      {"qda", "MATLAB Quadratic Discriminant, regularised when singular (ridge, priors)",
       make_qda_classifier, true, kWidestCovariance},
      {"clafic",
       "CLAFIC subspace method: c1 subspace size, c2 sensor banks, tau fidelity -> unknown",
       make_clafic_classifier},
      {"som", "Kohonen SOM (7x7) with neuron-to-class regions; rows, columns, epochs, schedules",
       make_som_classifier},
      {"ridge",
       "one-vs-rest ridge on z-scores, alpha by exact leave-one-out over 10^-3..10^3 (as "
       "scikit-learn's RidgeClassifierCV; alpha_min, alpha_max, alphas)",
       make_ridge_classifier},
      {"em", "EM Gaussian mixture, clusters mapped to classes (Kaboli Fig. 4)", make_em_classifier,
       true, kWidestCovariance},
  };
  return table;
}

std::string known_names() {
  std::string known;
  for (const ClassifierRow& row : classifier_table())
    known += (known.empty() ? "" : ", ") + std::string(row.name);
  return known.empty() ? "none" : known;
}

}  // namespace

std::unique_ptr<Classifier> make_classifier(const std::string& specification) {
  const size_t colon = specification.find(':');
  const std::string name = specification.substr(0, colon);
  const std::string where = name.empty() ? std::string("classifier") : "classifier " + name;
  const auto& table = classifier_table();
  const auto found = std::find_if(table.begin(), table.end(),
                                  [&](const ClassifierRow& row) { return name == row.name; });
  if (found == table.end())
    throw Error(where, "unknown classifier '" + name + "' (known: " + known_names() + ")");
  Parameters parameters;
  if (colon != std::string::npos)
    parameters = Parameters::parse(specification.substr(colon + 1), where);
  parameters.set_where(where);
  return found->make(parameters);
}

std::vector<std::string> classifier_names() {
  std::vector<std::string> names;
  for (const ClassifierRow& row : classifier_table()) names.emplace_back(row.name);
  return names;
}

std::vector<ClassifierEntry> classifier_catalog() {
  std::vector<ClassifierEntry> entries;
  for (const ClassifierRow& row : classifier_table())
    entries.push_back({row.name, row.description, row.preset, row.widest});
  return entries;
}

int64_t widest_columns(const std::string& specification) {
  const std::string name = specification.substr(0, specification.find(':'));
  for (const ClassifierRow& row : classifier_table())
    if (name == row.name) return row.widest;
  return 0;
}

// The document holds what make_classifier needs to rebuild the same classifier (name and
// effective parameters) and what load() needs to restore its fitted state.
nlohmann::json save_classifier(const Classifier& classifier) {
  nlohmann::json parameters = nlohmann::json::object();
  const Parameters effective = classifier.parameters();
  for (const auto& [key, value] : effective.values()) parameters[key] = value;
  return {{"name", classifier.name()}, {"parameters", parameters}, {"model", classifier.save()}};
}

std::string specification_of(const Classifier& classifier) {
  std::string specification = classifier.name();
  const Parameters parameters = classifier.parameters();
  char separator = ':';
  for (const auto& [key, value] : parameters.values()) {
    specification.append(1, separator).append(key).append("=").append(value);
    separator = ',';
  }
  return specification;
}

std::unique_ptr<Classifier> load_classifier(const nlohmann::json& document) {
  if (!document.is_object() || !document.contains("name") || !document["name"].is_string() ||
      !document.contains("model"))
    throw Error("model", "not a saved classifier (expected an object with 'name' and 'model')");
  std::string specification = document["name"].get<std::string>();
  if (document.contains("parameters")) {
    const nlohmann::json& parameters = document["parameters"];
    if (!parameters.is_object()) throw Error("model", "'parameters' is not an object");
    std::string list;
    for (const auto& [key, value] : parameters.items()) {
      if (!value.is_string()) throw Error("model", "parameter '" + key + "' is not a string");
      list += (list.empty() ? "" : ",") + key + "=" + value.get<std::string>();
    }
    if (!list.empty()) specification += ":" + list;
  }
  std::unique_ptr<Classifier> classifier = make_classifier(specification);
  try {
    classifier->load(document["model"]);
  } catch (const nlohmann::json::exception& error) {
    throw Error("model " + classifier->name(), std::string("malformed model: ") + error.what());
  }
  return classifier;
}

}  // namespace tactile::ml

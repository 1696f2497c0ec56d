#pragma once
// One interface for every classifier (spec §6.10): fit, predict, per-class scores,
// save/load as JSON, name and parameters, so evaluation code is shared.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "tactile/parameters.h"

namespace tactile::ml {

using Matrix = Eigen::MatrixXd;  // rows = samples, columns = features
using Vector = Eigen::VectorXd;

// Class index returned by predict() when a classifier answers "unknown" (CLAFIC's
// fidelity test, an unlabelled SOM neuron).
constexpr int kUnknownClass = -1;

class Classifier {
 public:
  virtual ~Classifier() = default;
  // The command-line name, e.g. "linear-svm", "knn".
  virtual std::string name() const = 0;
  // The effective parameters, defaults included, as `key=value` pairs.
  virtual Parameters parameters() const = 0;
  // y holds class indices 0..class_count-1. Every random step draws from `seed`.
  // Throws tactile::Error on input it cannot learn from (e.g. no samples).
  virtual void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) = 0;
  // Per-class scores, rows = samples, columns = classes; larger = more likely. What each
  // classifier's are (probabilities, posteriors, weighted votes, ...): docs/CLASSIFIERS.md,
  // "Scores".
  virtual Matrix scores(const Matrix& x) const = 0;
  // Class per row: argmax of scores (first on ties), unless the method has its own rule (the
  // SVM's vote, k-NN's majority with the nearest neighbour breaking ties) or can answer
  // unknown.
  virtual std::vector<int> predict(const Matrix& x) const;
  // Both at once: the classes predict() gives and the scores() matrix. The default calls
  // both; a classifier whose two share their costly step (k-NN's neighbour search)
  // overrides it to do that step once.
  struct Decisions {
    std::vector<int> classes;
    Matrix scores;
  };
  virtual Decisions decide(const Matrix& x) const;
  // Said before fit() by a caller that will ask this fit for predict() only (an evaluation
  // that reports no scores): a classifier whose scores cost extra work at fit time may leave
  // that work out (the SVM's Platt sigmoids: five more trainings per pair). predict() gives the
  // same classes either way; scores() remain defined, possibly cruder (the SVM's vote shares).
  virtual void skip_scores() {}
  virtual nlohmann::json save() const = 0;
  virtual void load(const nlohmann::json& model) = 0;
  // How much each feature column served the fitted model (the tree ensembles' mean decrease
  // in impurity, XGBoost's gain), one entry per column, normalised to sum 1; empty (the
  // default) for a classifier that has no such figure. The evaluation averages them over
  // folds.
  virtual std::vector<double> feature_importances() const { return {}; }
};

// How sure one decision is, from its row of scores, comparable between classifiers: the
// scores turned into shares that sum to 1 (kept as they are when they already lie in [0, 1]
// and sum to 1, as votes and probabilities do; otherwise a softmax), `score` the predicted
// class's share and `margin` its lead over the best other class (0: a tie, the least sure).
// A kUnknownClass answer scores 0 with margin 0.
struct Confidence {
  double score = 0.0;
  double margin = 0.0;
};
Confidence confidence_of(const Eigen::Ref<const Vector>& scores, int predicted);

// "name[:key=value,...]", e.g. "knn:k=3,metric=cosine". Throws tactile::Error naming the
// unknown name or the bad parameter.
std::unique_ptr<Classifier> make_classifier(const std::string& specification);
// Every name make_classifier accepts.
std::vector<std::string> classifier_names();
// Every name with a one-line description (what it is, which preset or paper it reproduces),
// in the order `tactile evaluate --list` prints them.
struct ClassifierEntry {
  std::string name;
  std::string description;
  // A classifier of its own with working defaults (Train all runs it, auto may pick it); false
  // for the searches and wrappers that need another classifier (grid-search, auto, select).
  bool preset = true;
  // The most columns auto tries it on whole (0: no limit): past them its training grows out
  // of proportion (a full covariance is P x P and its inverse P^3; boosting scans every column
  // in every node of hundreds of trees), so auto gives it wider blocks only through select.
  int64_t widest = 0;
};
std::vector<ClassifierEntry> classifier_catalog();
// The catalog's widest of the classifier a specification names ("qda:ridge=1" -> qda's); 0
// for an unknown name.
int64_t widest_columns(const std::string& specification);
// A model saved with save(), with its name and parameters, restored.
std::unique_ptr<Classifier> load_classifier(const nlohmann::json& document);
nlohmann::json save_classifier(const Classifier& classifier);
// "name:key=value,..." from name() and parameters(): make_classifier of it gives the same
// classifier.
std::string specification_of(const Classifier& classifier);

// z-score fitted on training data (spec §6.4): μ = mean, s = sample std; s = 0 -> z = x - μ.
struct Standardizer {
  Vector mean;
  Vector scale;  // 1 where the training std was 0
  void fit(const Matrix& x);
  // mean = each column's minimum, scale = its range (1 where the column is constant): the
  // training rows map onto [0, 1].
  void fit_range(const Matrix& x);
  Matrix transform(const Matrix& x) const;
  nlohmann::json save() const;
  void load(const nlohmann::json& model);
};

}  // namespace tactile::ml

#pragma once
// CLAFIC subspace method with sensor banks and the fidelity test that answers "unknown"
// (Robovie-IIF paper, spec §4.4-4.7, test vector R3).
//
// Command-line name `clafic`, parameters (defaults in brackets):
//   c1=0.15      cumulative contribution threshold: m_k = smallest m with r_k(m) >= c1
//                (c1 = 1 keeps the whole numerical rank). The paper's conditions are
//                c1 in {1, 0.15}.
//   c2=0         sensor-bank threshold as a multiple of the typical element magnitude
//                (spec §4.7: |u[p]| >= c2 * rho, rho = 1/sqrt(D)); 0 keeps every element.
//                The paper's conditions are c2 in {0, 1, 2}.
//   tau=0.95     fidelity: accept the best class l only if DF_l / DF_second > 1/tau.
//   c1_mode=energy    r(m) = sum d_j^2 / sum d^2 (spec default); `singular` uses sum d_j / sum d.
//   c2_scale=rms      rho = 1/sqrt(D); `std` uses the population std of the entries of u_kj.
//   dimensions=       overrides m: one whole number for every class, or one per class joined
//                     by '|' (e.g. the paper's Table I: 4|4|5|5|5|5|4|3|6|5|7|3|4|7|4);
//                     clamped to each class's numerical rank.
// Presets reproduced: `clafic` is the paper's (C1, C2) = (0.15, 0), tau = 0.95;
// `clafic:c1=1,c2=2` etc. give the other five conditions of Figs 9-10.
//
// Scores are the discrimination functions DF_k(x) (or DF*_k(x) when c2 > 0): squared lengths
// of the projections of x on each class subspace, not probabilities. predict() returns
// kUnknownClass when the fidelity test fails. A class absent from the training data has an
// empty subspace (DF = 0) and is never predicted.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct ClaficOptions {
  enum class Contribution { kEnergy, kSingular };
  enum class ElementScale { kRms, kStd };
  double c1 = 0.15;
  double c2 = 0.0;
  Contribution contribution = Contribution::kEnergy;
  ElementScale element_scale = ElementScale::kRms;
  int dimension_override = 0;  // > 0: use this m (clamped to the rank) instead of c1
};

// One class's subspace (spec §4.4 and §4.7).
struct ClaficSubspace {
  Vector singular_values;   // d_1 >= ... >= d_r of X_k, r = numerical rank
  Vector cumulative_ratio;  // r_k(m) for m = 1..r
  int dimension = 0;        // m_k
  Matrix basis;             // D x m_k orthonormal u_k1..u_km, largest-|.| entry positive
  Matrix bank_basis;  // D x m*: u*_kj after the c2 threshold, renormalised, empty ones dropped
  std::vector<int64_t> needed_features;  // Q_k (eq 10), ascending
};

// Fits one class subspace from its training vectors (rows of `samples`, no centring: CLAFIC
// uses the autocorrelation subspace). Zero rows give an empty subspace.
ClaficSubspace fit_clafic_subspace(const Matrix& samples, const ClaficOptions& options);

// DF(x) = sum_j (x^T b_j)^2 for every row of x (spec eq 6), on the columns b_j of `basis`.
Vector clafic_discrimination(const Matrix& x, const Matrix& basis);

// Decision and fidelity (spec §4.5-4.6) on one row of discrimination values: the first
// argmax l, accepted iff DF_l / DF_second > 1/tau (DF_second = 0: iff DF_l > 0), else
// kUnknownClass.
int clafic_decide(const Vector& discrimination, double tau);

class ClaficClassifier : public Classifier {
 public:
  explicit ClaficClassifier(const Parameters& parameters = {});

  std::string name() const override { return "clafic"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // Leave-one-out over the rows of (x, y) (spec §4.10): the answer for each row from a model
  // fitted on every other row, exactly as refitting per fold would give, but a held-out row
  // changes only its own class's subspace, so every other class is fitted once (the Robovie
  // experiment's 240 folds of 37401 features). Leaves this classifier fitted on all rows.
  std::vector<int> leave_one_out(const Matrix& x, const std::vector<int>& y, int class_count);

  const ClaficSubspace& subspace(int class_index) const;
  // m_k per class (Table I).
  std::vector<int> subspace_dimensions() const;
  // |Q_k| per class: the number of features (for Robovie, sensor pairs) the class's sensor
  // bank needs (eq 10).
  std::vector<int64_t> sensor_bank_sizes() const;
  // |Q_k| / D per class: the fraction of the feature space used (the paper's 15 % and 5 %).
  std::vector<double> feature_fractions() const;
  int64_t feature_count() const { return feature_count_; }

 private:
  Matrix discrimination(const Matrix& x) const;
  ClaficOptions class_options(size_t class_index) const;  // the dimension override applied

  ClaficOptions options_;
  double tau_ = 0.95;
  std::vector<int> dimension_overrides_;  // per class, or one value for all, or empty
  int64_t feature_count_ = 0;
  std::vector<ClaficSubspace> subspaces_;
};

// The registry's factory for `clafic`.
std::unique_ptr<Classifier> make_clafic_classifier(const Parameters& parameters);

// The sensors (0-based) of the Robovie pair features `features` (spec §4.3: row-major upper
// triangle of an N x N correlation matrix, D = N(N-1)/2), ascending and unique: the sensor
// bank of a class given its needed features. Throws tactile::Error for an index >= D.
std::vector<int> pair_sensors(const std::vector<int64_t>& features, int sensor_count);

// Robovie recognition and false-alarm rates (spec §4.10) from a confusion matrix
// (rows true, columns predicted) whose last column counts "unknown" answers, as
// EvaluationResult::confusion holds it: recognition_k = M[k][k] / n_k, false alarm_k =
// (column_k - M[k][k]) / n_k, n_k = row sum including unknown. An unknown answer counts
// as not correct and as no false alarm. Rates of a class with n_k = 0 are 0.
struct RecognitionRates {
  std::vector<double> recognition;
  std::vector<double> false_alarm;
};
RecognitionRates recognition_rates(const Eigen::MatrixXi& confusion_with_unknown);

}  // namespace tactile::ml

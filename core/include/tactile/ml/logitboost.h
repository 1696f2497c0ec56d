#pragma once
// LogitBoost with regression stumps, multi-class as in Friedman, Hastie & Tibshirani (2000),
// "Additive logistic regression", Algorithm 6 (J classes), as Weka's LogitBoost runs it.
//
// Preset `logitboost` (Kaboli Table 9, spec §1.15: Weka defaults, decision stumps):
//   learners = 10       boosting iterations M
//   learning_rate = 1   shrinkage ν applied to every stump
// (MATLAB's Classification Learner ensembles use 30 learners and rate 0.1: pass
// `logitboost:learners=30,learning_rate=0.1`.)
//
// Iteration m, for every class j (p_j = current class probability, y*_j = 1 for class j):
//   working response z = (y* - p) / (p (1 - p)), i.e. 1/p or -1/(1-p), clipped to ±3 (Weka's
//   Z_MAX, keeps a confident sample from dominating), weight w = p (1 - p);
//   f_mj = weighted least-squares stump fit of z (one feature, one cut, two constants).
// Then f_mj <- ν (J-1)/J (f_mj - (1/J) Σ_k f_mk), F_j += f_mj, p = softmax(F) (Alg. 6, 2(b)).
// Scores are p (rows sum to 1). Classes absent from the training set get small
// probabilities, never NaN. Stump search: every feature and every midpoint between
// consecutive distinct values, ties to the lower feature, then the lower cut; no split that
// reduces the weighted squared error -> a constant stump. The fit is deterministic (the seed
// is not used).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct RegressionStump {
  int feature = -1;  // -1: constant, `below` everywhere
  double threshold = 0.0;
  double below = 0.0;  // value where x[feature] < threshold
  double above = 0.0;
  // The stump's value for row `row` of x.
  double operator()(const Matrix& x, Eigen::Index row) const {
    return feature < 0 || x(row, feature) < threshold ? below : above;
  }
};

class LogitBoost : public Classifier {
 public:
  LogitBoost(const std::string& preset, const Parameters& parameters);

  std::string name() const override { return "logitboost"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  // Class probabilities softmax(F) (rows sum to 1).
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // stumps()[m][j]: the stump fitted at iteration m for class j, before centring and
  // shrinkage (the centring mixes the J stumps, so it is applied when scoring).
  const std::vector<std::vector<RegressionStump>>& stumps() const { return stumps_; }

 private:
  int64_t learners_ = 10;
  double learning_rate_ = 1.0;

  int class_count_ = 0;
  Eigen::Index feature_count_ = 0;
  std::vector<std::vector<RegressionStump>> stumps_;
  bool fitted_ = false;
};

// Registry factory for `logitboost`.
std::unique_ptr<Classifier> make_logitboost_classifier(const Parameters& parameters);

}  // namespace tactile::ml

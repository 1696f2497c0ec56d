#pragma once
// Ridge classifier with internal leave-one-out choice of the penalty, as scikit-learn's
// RidgeClassifierCV (the classifier for rocket features, issue 26).
//
// `ridge`: columns z-scored on the training fold (Standardizer); one-vs-rest targets +1 for
// the class and -1 for the others; per class a ridge regression with an unpenalised intercept,
// w = (Z'Z + alpha I)^-1 Z'(y - mean y), all classes sharing one alpha. alpha is chosen among
// `alphas` values spaced evenly in log between alpha_min and alpha_max (default 10^-3..10^3,
// 10 values, RidgeClassifierCV(alphas=np.logspace(-3, 3, 10))) by the mean squared
// leave-one-out error over every row and class, computed exactly without refitting from one
// eigendecomposition (of Z'Z when columns <= rows, else of the rows' Gram matrix ZZ'):
//   H = U diag(s^2 / (s^2 + alpha)) U' + 11'/n,  e_i = (y_i - yhat_i) / (1 - H_ii),
// the first alpha of least error winning a tie. Deterministic (no random step).
// scores() = decision values z'w_k + b_k; predict() = the largest (first on ties).
// Parameters: alpha_min, alpha_max, alphas (count; 1 = alpha_min alone).

#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

class RidgeClassifier : public Classifier {
 public:
  explicit RidgeClassifier(const Parameters& parameters = {});
  std::string name() const override { return "ridge"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // The grid, ascending; after fit(), the chosen alpha and each grid value's LOO error.
  std::vector<double> alpha_grid() const;
  double alpha() const { return alpha_; }
  const std::vector<double>& loo_errors() const { return loo_errors_; }

 private:
  double alpha_min_ = 1e-3;
  double alpha_max_ = 1e3;
  int alpha_count_ = 10;
  double alpha_ = 0.0;
  std::vector<double> loo_errors_;
  Standardizer standardizer_;
  Matrix weights_;  // columns x classes
  Vector intercept_;
  bool fitted_ = false;
};

std::unique_ptr<Classifier> make_ridge_classifier(const Parameters& parameters);

}  // namespace tactile::ml

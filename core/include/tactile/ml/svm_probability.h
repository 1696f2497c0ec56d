#pragma once
// Probabilities from SVM decision values, computed as libsvm computes them for a C-SVC
// trained with `probability = 1` (libsvm 3.24 exports none of these steps):
//   - one Platt sigmoid per binary learner, P(positive | f) = 1 / (1 + exp(A f + B)), fitted
//     to decision values of held-out rows (libsvm's 5-fold cross-validation, run by
//     cross_validated_sigmoid in core/src/ml/libsvm_support.h);
//   - the pairwise probabilities of the one-vs-one learners coupled into class probabilities.

#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// P(positive | f) = 1 / (1 + exp(A f + B)); A < 0 when a larger f means the positive class.
struct PlattSigmoid {
  double a = 0.0;
  double b = 0.0;
  // Written so that neither exp() overflows nor 1 - p loses digits (libsvm's sigmoid_predict).
  double probability(double decision) const;
};

// Lin, Lin & Weng (2007), "A note on Platt's probabilistic outputs for support vector
// machines", Algorithm 1 (libsvm's sigmoid_train): Newton's method with backtracking on the
// cross-entropy against Platt's regularised targets t+ = (N+ + 1)/(N+ + 2), t- = 1/(N- + 2),
// from A = 0, B = log((N- + 1)/(N+ + 1)); stops when both gradient entries are below 1e-5,
// after 100 iterations, or when the line search's step falls below 1e-10.
// `positive[i]` tells whether row i belongs to the positive class.
PlattSigmoid fit_platt_sigmoid(const std::vector<double>& decisions,
                               const std::vector<bool>& positive);

// Wu, Lin & Weng (2004), "Probability estimates for multi-class classification by pairwise
// coupling", method 2 (libsvm's multiclass_probability): p minimising
// Σ_i Σ_{j≠i} (r_ji p_i - r_ij p_j)² subject to Σ p = 1, by the fixed-point iteration
// p_t <- p_t + (p'Qp - (Qp)_t) / Q_tt, renormalised, until max_t |(Qp)_t - p'Qp| < 0.005/k
// or max(100, k) sweeps. `pairwise(i, j)` = r_ij = P(class i | class i or j) for i ≠ j (the
// diagonal is not read); each r_ij is clamped to [1e-7, 1 - 1e-7] and r_ji taken as 1 - r_ij
// for i < j, as libsvm's svm_predict_probability does. k = 2 gives (r_01, r_10) directly.
Vector couple_pairwise(const Matrix& pairwise);

}  // namespace tactile::ml

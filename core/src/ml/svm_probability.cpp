#include "tactile/ml/svm_probability.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "libsvm_support.h"
#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

// log(1 + exp(-|x|)) plus the linear part, the cross-entropy of one row without overflow.
double sigmoid_loss(double target, double value) {
  return value >= 0.0 ? target * value + std::log1p(std::exp(-value))
                      : (target - 1.0) * value + std::log1p(std::exp(value));
}

}  // namespace

double PlattSigmoid::probability(double decision) const {
  const double value = a * decision + b;
  return value >= 0.0 ? std::exp(-value) / (1.0 + std::exp(-value)) : 1.0 / (1.0 + std::exp(value));
}

PlattSigmoid fit_platt_sigmoid(const std::vector<double>& decisions,
                               const std::vector<bool>& positive) {
  if (decisions.size() != positive.size())
    throw Error("Platt sigmoid", "decision values and classes differ in count");
  constexpr int kIterations = 100;
  constexpr double kSmallestStep = 1e-10;
  constexpr double kHessianRidge = 1e-12;  // keeps the Hessian strictly positive definite
  constexpr double kGradientTolerance = 1e-5;
  const auto count = static_cast<Eigen::Index>(decisions.size());
  const Eigen::Map<const Vector> f(decisions.data(), count);
  const double positives = static_cast<double>(std::count(positive.begin(), positive.end(), true));
  const double negatives = static_cast<double>(count) - positives;
  Vector targets(count);
  for (Eigen::Index row = 0; row < count; ++row)
    targets(row) = positive[static_cast<size_t>(row)] ? (positives + 1.0) / (positives + 2.0)
                                                      : 1.0 / (negatives + 2.0);
  const auto loss = [&](double a, double b) {
    double sum = 0.0;
    for (Eigen::Index row = 0; row < count; ++row)
      sum += sigmoid_loss(targets(row), f(row) * a + b);
    return sum;
  };

  PlattSigmoid sigmoid{0.0, std::log((negatives + 1.0) / (positives + 1.0))};
  double value = loss(sigmoid.a, sigmoid.b);
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    // Gradient and Hessian of the loss in (A, B); p = P(positive), q = 1 - p.
    double h11 = kHessianRidge, h22 = kHessianRidge, h21 = 0.0, g1 = 0.0, g2 = 0.0;
    for (Eigen::Index row = 0; row < count; ++row) {
      // p and q = 1 - p each from the exponential of a non-positive number.
      const double decision = f(row) * sigmoid.a + sigmoid.b;
      const double shrink = std::exp(-std::abs(decision));
      const double p = (decision >= 0.0 ? shrink : 1.0) / (1.0 + shrink);
      const double q = (decision >= 0.0 ? 1.0 : shrink) / (1.0 + shrink);
      const double curvature = p * q;
      h11 += f(row) * f(row) * curvature;
      h22 += curvature;
      h21 += f(row) * curvature;
      const double residual = targets(row) - p;
      g1 += f(row) * residual;
      g2 += residual;
    }
    if (std::abs(g1) < kGradientTolerance && std::abs(g2) < kGradientTolerance) break;
    const double determinant = h11 * h22 - h21 * h21;
    const double step_a = -(h22 * g1 - h21 * g2) / determinant;
    const double step_b = -(-h21 * g1 + h11 * g2) / determinant;
    const double slope = g1 * step_a + g2 * step_b;
    double step = 1.0;
    while (step >= kSmallestStep) {
      const double next_a = sigmoid.a + step * step_a;
      const double next_b = sigmoid.b + step * step_b;
      const double next_value = loss(next_a, next_b);
      if (next_value < value + 1e-4 * step * slope) {  // sufficient decrease (Armijo)
        sigmoid = {next_a, next_b};
        value = next_value;
        break;
      }
      step /= 2.0;
    }
    if (step < kSmallestStep) break;  // the line search failed: keep the last point
  }
  return sigmoid;
}

Vector couple_pairwise(const Matrix& pairwise) {
  constexpr double kSmallest = 1e-7;
  const Eigen::Index k = pairwise.rows();
  if (pairwise.cols() != k) throw Error("pairwise coupling", "needs a square matrix");
  if (k == 0) return Vector();
  if (k == 1) return Vector::Ones(1);
  Matrix r(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    r(i, i) = 0.0;
    for (Eigen::Index j = i + 1; j < k; ++j) {
      r(i, j) = std::clamp(pairwise(i, j), kSmallest, 1.0 - kSmallest);
      r(j, i) = 1.0 - r(i, j);
    }
  }
  if (k == 2) return Vector{{r(0, 1), r(1, 0)}};

  // Q_tt = Σ_{j≠t} r_jt², Q_tj = -r_jt r_tj.
  Matrix q = -(r.transpose().array() * r.array()).matrix();
  q.diagonal() = r.array().square().colwise().sum().transpose();
  Vector p = Vector::Constant(k, 1.0 / static_cast<double>(k));
  const double tolerance = 0.005 / static_cast<double>(k);
  const Eigen::Index sweeps = std::max<Eigen::Index>(100, k);
  for (Eigen::Index sweep = 0; sweep < sweeps; ++sweep) {
    // Qp and p'Qp recomputed once a sweep for accuracy, then updated in place.
    Vector qp = q * p;
    double pqp = p.dot(qp);
    if ((qp.array() - pqp).abs().maxCoeff() < tolerance) break;
    for (Eigen::Index t = 0; t < k; ++t) {
      const double change = (pqp - qp(t)) / q(t, t);
      p(t) += change;
      pqp = (pqp + change * (change * q(t, t) + 2.0 * qp(t))) / (1.0 + change) / (1.0 + change);
      qp = (qp + change * q.col(t)) / (1.0 + change);
      p /= 1.0 + change;
    }
  }
  return p;
}

//---- Platt's sigmoid of one libsvm learner --------------------------------------------------

PlattSigmoid cross_validated_sigmoid(const svm_problem& problem, const svm_parameter& parameter,
                                     std::mt19937_64 engine, const std::string& where) {
  constexpr int kFolds = 5;
  const auto rows = static_cast<size_t>(problem.l);
  std::vector<size_t> order(rows);
  std::iota(order.begin(), order.end(), size_t{0});
  shuffle(order, engine);
  std::vector<double> decisions(rows, 0.0);
  std::vector<bool> positive(rows);
  for (size_t row = 0; row < rows; ++row) positive[row] = problem.y[row] > 0.0;
  svm_parameter fold_parameter = parameter;
  fold_parameter.probability = 0;
  std::vector<svm_node*> nodes;
  std::vector<double> targets;
  for (size_t fold = 0; fold < kFolds; ++fold) {
    if (cancel_requested()) throw Error(where, "cancelled");
    const size_t begin = fold * rows / kFolds, end = (fold + 1) * rows / kFolds;
    nodes.clear();
    targets.clear();
    for (size_t slot = 0; slot < rows; ++slot) {
      if (slot >= begin && slot < end) continue;
      nodes.push_back(problem.x[order[slot]]);
      targets.push_back(problem.y[order[slot]]);
    }
    const auto positives =
        std::count_if(targets.begin(), targets.end(), [](double y) { return y > 0; });
    const bool one_class =
        positives == 0 || positives == static_cast<std::ptrdiff_t>(targets.size());
    if (targets.empty() || one_class) {
      const double value = targets.empty() ? 0.0 : positives > 0 ? 1.0 : -1.0;
      for (size_t slot = begin; slot < end; ++slot) decisions[order[slot]] = value;
      continue;
    }
    svm_problem fold_problem{static_cast<int>(targets.size()), targets.data(), nodes.data()};
    const LibsvmModel model(svm_train(&fold_problem, &fold_parameter));
    if (!model) throw Error(where, "libsvm returned no model");
    for (size_t slot = begin; slot < end; ++slot) {
      double value = 0.0;
      svm_predict_values(model.get(), problem.x[order[slot]], &value);
      decisions[order[slot]] = value * model->label[0];
    }
  }
  return fit_platt_sigmoid(decisions, positive);
}

}  // namespace tactile::ml

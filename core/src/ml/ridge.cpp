// Ridge classifier with exact leave-one-out choice of alpha (ridge.h; RidgeClassifierCV).
#include "tactile/ml/ridge.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "model_json.h"
#include "tactile/error.h"
#include "tactile/ml/checks.h"

namespace tactile::ml {

namespace {

// Eigenvalues below this share of the largest are the null space (rounding, not signal).
constexpr double kRidgeNullShare = 1e-12;

double ridge_parameter(const Parameters& parameters, const std::string& key, double fallback) {
  const double value = parameters.number(key, fallback);
  if (!(value > 0.0))
    throw Error(parameters.where(), key + "=" + model_json::format_number(value) + ": must be > 0");
  return value;
}

}  // namespace

RidgeClassifier::RidgeClassifier(const Parameters& parameters) {
  parameters.expect_only({"alpha_min", "alpha_max", "alphas"});
  alpha_min_ = ridge_parameter(parameters, "alpha_min", 1e-3);
  alpha_max_ = ridge_parameter(parameters, "alpha_max", 1e3);
  const int64_t count = parameters.integer("alphas", 10);
  if (count < 1 || count > 1000)
    throw Error(parameters.where(), "alphas=" + std::to_string(count) + ": must be in [1, 1000]");
  if (alpha_max_ < alpha_min_)
    throw Error(parameters.where(),
                "alpha_max=" + model_json::format_number(alpha_max_) + ": must be >= alpha_min");
  alpha_count_ = static_cast<int>(count);
}

Parameters RidgeClassifier::parameters() const {
  Parameters parameters;
  parameters.set("alpha_min", model_json::format_number(alpha_min_));
  parameters.set("alpha_max", model_json::format_number(alpha_max_));
  parameters.set("alphas", std::to_string(alpha_count_));
  return parameters;
}

std::vector<double> RidgeClassifier::alpha_grid() const {
  std::vector<double> grid;
  const double low = std::log10(alpha_min_), high = std::log10(alpha_max_);
  for (int index = 0; index < alpha_count_; ++index)
    grid.push_back(alpha_count_ == 1
                       ? alpha_min_
                       : std::pow(10.0, low + (high - low) * index / (alpha_count_ - 1)));
  return grid;
}

void RidgeClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                          uint64_t /*seed: the fit is deterministic*/) {
  check_training_set(x, y, class_count, name());
  standardizer_.fit(x);
  const Matrix z = standardizer_.transform(x);
  const Eigen::Index n = z.rows();
  Matrix targets = Matrix::Constant(n, class_count, -1.0);
  for (Eigen::Index row = 0; row < n; ++row) targets(row, y[static_cast<size_t>(row)]) = 1.0;
  intercept_ = targets.colwise().mean().transpose();
  const Matrix centred = targets.rowwise() - intercept_.transpose();

  // U (n x r, orthonormal) and s^2 of the thin SVD Z = U S V', from the smaller of the two
  // symmetric products: the hat matrix and the weights need nothing else.
  Matrix basis;
  Vector squares;
  if (z.cols() <= n) {
    const Eigen::SelfAdjointEigenSolver<Matrix> solver(z.transpose() * z);
    const double largest = std::max(solver.eigenvalues().maxCoeff(), 0.0);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index k = 0; k < solver.eigenvalues().size(); ++k)
      if (solver.eigenvalues()(k) > kRidgeNullShare * largest) kept.push_back(k);
    basis.resize(n, static_cast<Eigen::Index>(kept.size()));
    squares.resize(basis.cols());
    for (size_t k = 0; k < kept.size(); ++k) {
      const double value = solver.eigenvalues()(kept[k]);
      squares(static_cast<Eigen::Index>(k)) = value;
      basis.col(static_cast<Eigen::Index>(k)) =
          z * solver.eigenvectors().col(kept[k]) / std::sqrt(value);
    }
  } else {
    const Eigen::SelfAdjointEigenSolver<Matrix> solver(z * z.transpose());
    const double largest = std::max(solver.eigenvalues().maxCoeff(), 0.0);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index k = 0; k < solver.eigenvalues().size(); ++k)
      if (solver.eigenvalues()(k) > kRidgeNullShare * largest) kept.push_back(k);
    basis.resize(n, static_cast<Eigen::Index>(kept.size()));
    squares.resize(basis.cols());
    for (size_t k = 0; k < kept.size(); ++k) {
      squares(static_cast<Eigen::Index>(k)) = solver.eigenvalues()(kept[k]);
      basis.col(static_cast<Eigen::Index>(k)) = solver.eigenvectors().col(kept[k]);
    }
  }
  const Matrix projected = basis.transpose() * centred;           // U'(Y - mean)
  const Matrix leverage_parts = basis.array().square().matrix();  // U_ij^2

  // Exact LOO residuals for every alpha (the intercept's leverage 1/n included).
  const std::vector<double> grid = alpha_grid();
  loo_errors_.assign(grid.size(), 0.0);
  size_t best = 0;
  for (size_t index = 0; index < grid.size(); ++index) {
    const Vector shrink = squares.array() / (squares.array() + grid[index]);
    const Matrix fitted = basis * (shrink.asDiagonal() * projected);
    const Vector leverage = (leverage_parts * shrink).array() + 1.0 / static_cast<double>(n);
    const Vector remaining = (1.0 - leverage.array()).max(1e-12);
    const Matrix residuals = (centred - fitted).array().colwise() / remaining.array();
    loo_errors_[index] = residuals.array().square().mean();
    if (loo_errors_[index] < loo_errors_[best]) best = index;
  }
  alpha_ = grid[best];
  // w = Z'U diag(1 / (s^2 + alpha)) U'(Y - mean): the primal ridge solution.
  const Vector inverse = (squares.array() + alpha_).inverse();
  weights_ = z.transpose() * (basis * (inverse.asDiagonal() * projected));
  fitted_ = true;
}

Matrix RidgeClassifier::scores(const Matrix& x) const {
  check_fitted(fitted_, name());
  check_query(x, weights_.rows(), name());
  return (standardizer_.transform(x) * weights_).rowwise() + intercept_.transpose();
}

nlohmann::json RidgeClassifier::save() const {
  check_fitted(fitted_, name());
  return {{"standardizer", standardizer_.save()},
          {"weights", model_json::from_matrix(weights_)},
          {"intercept", model_json::from_vector(intercept_)},
          {"alpha", alpha_},
          {"loo_errors", loo_errors_}};
}

void RidgeClassifier::load(const nlohmann::json& model) {
  const std::string where = name() + " model";
  standardizer_.load(model.at("standardizer"));
  weights_ = model_json::to_matrix(model.at("weights"), where);
  intercept_ = model_json::to_vector(model.at("intercept"));
  alpha_ = model.at("alpha").get<double>();
  loo_errors_ = model.at("loo_errors").get<std::vector<double>>();
  if (weights_.rows() != standardizer_.mean.size() || weights_.cols() != intercept_.size())
    throw Error(where, "weights of " + std::to_string(weights_.rows()) + " x " +
                           std::to_string(weights_.cols()) + " do not match " +
                           std::to_string(standardizer_.mean.size()) + " features and " +
                           std::to_string(intercept_.size()) + " classes");
  fitted_ = true;
}

std::unique_ptr<Classifier> make_ridge_classifier(const Parameters& parameters) {
  return std::make_unique<RidgeClassifier>(parameters);
}

}  // namespace tactile::ml

#include "tactile/ml/classifier.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tactile/error.h"

namespace tactile::ml {

std::vector<int> Classifier::predict(const Matrix& x) const {
  const Matrix score = scores(x);
  std::vector<int> classes(static_cast<size_t>(score.rows()), kUnknownClass);
  for (Eigen::Index row = 0; row < score.rows(); ++row) {
    if (score.cols() == 0) continue;
    Eigen::Index best = 0;
    score.row(row).maxCoeff(&best);  // Eigen returns the first maximum
    classes[static_cast<size_t>(row)] = static_cast<int>(best);
  }
  return classes;
}

Classifier::Decisions Classifier::decide(const Matrix& x) const {
  Decisions decisions;
  decisions.scores = scores(x);
  decisions.classes = predict(x);
  return decisions;
}

Confidence confidence_of(const Eigen::Ref<const Vector>& scores, int predicted) {
  Confidence confidence;
  if (predicted < 0 || predicted >= scores.size() || !scores.allFinite()) return confidence;
  Vector shares = scores;
  const double sum = scores.sum();
  const bool already_shares =
      scores.minCoeff() >= 0.0 && scores.maxCoeff() <= 1.0 && std::abs(sum - 1.0) < 1e-9;
  if (!already_shares) {
    // Subtracting the largest keeps exp() from overflowing; lowest() scores become 0.
    shares = (scores.array() - scores.maxCoeff()).exp();
    shares /= shares.sum();
  }
  confidence.score = shares(predicted);
  double other = 0.0;
  for (Eigen::Index k = 0; k < shares.size(); ++k)
    if (k != predicted) other = std::max(other, shares(k));
  confidence.margin = std::max(0.0, confidence.score - other);
  return confidence;
}

void Standardizer::fit(const Matrix& x) {
  const Eigen::Index n = x.rows();
  mean = n > 0 ? Vector(x.colwise().mean().transpose()) : Vector::Zero(x.cols());
  scale = Vector::Ones(x.cols());
  if (n < 2) return;
  for (Eigen::Index column = 0; column < x.cols(); ++column) {
    const double variance =
        (x.col(column).array() - mean(column)).square().sum() / static_cast<double>(n - 1);
    const double deviation = std::sqrt(variance);
    if (deviation > 1e-12 * std::max(1.0, std::abs(mean(column)))) scale(column) = deviation;
  }
}

void Standardizer::fit_range(const Matrix& x) {
  if (x.rows() < 1) throw Error("standardizer", "needs at least one row");
  mean = x.colwise().minCoeff().transpose();
  const Vector high = x.colwise().maxCoeff().transpose();
  scale = Vector::Ones(x.cols());
  for (Eigen::Index column = 0; column < x.cols(); ++column) {
    const double range = high(column) - mean(column);
    if (range > 1e-12 * std::max(1.0, std::abs(mean(column)))) scale(column) = range;
  }
}

Matrix Standardizer::transform(const Matrix& x) const {
  if (x.cols() != mean.size())
    throw Error("standardizer", "expected " + std::to_string(mean.size()) + " features, got " +
                                    std::to_string(x.cols()));
  return (x.rowwise() - mean.transpose()).array().rowwise() / scale.transpose().array();
}

nlohmann::json Standardizer::save() const {
  return {{"mean", std::vector<double>(mean.data(), mean.data() + mean.size())},
          {"scale", std::vector<double>(scale.data(), scale.data() + scale.size())}};
}

void Standardizer::load(const nlohmann::json& model) {
  const auto means = model.at("mean").get<std::vector<double>>();
  const auto scales = model.at("scale").get<std::vector<double>>();
  if (means.size() != scales.size()) throw Error("standardizer", "mean and scale differ in length");
  mean = Eigen::Map<const Vector>(means.data(), static_cast<Eigen::Index>(means.size()));
  scale = Eigen::Map<const Vector>(scales.data(), static_cast<Eigen::Index>(scales.size()));
}

}  // namespace tactile::ml

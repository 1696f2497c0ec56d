#include "tactile/ml/classifier.h"

#include <cmath>

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

#include "probabilistic_support.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "tactile/error.h"

namespace tactile::ml::support {

std::vector<std::vector<Eigen::Index>> rows_by_class(const std::vector<int>& y, int class_count) {
  std::vector<std::vector<Eigen::Index>> members(static_cast<size_t>(class_count));
  for (size_t row = 0; row < y.size(); ++row)
    members[static_cast<size_t>(y[row])].push_back(static_cast<Eigen::Index>(row));
  return members;
}

Matrix select_rows(const Matrix& x, const std::vector<Eigen::Index>& indices) {
  Matrix selected(static_cast<Eigen::Index>(indices.size()), x.cols());
  for (size_t row = 0; row < indices.size(); ++row)
    selected.row(static_cast<Eigen::Index>(row)) = x.row(indices[row]);
  return selected;
}

Vector log_sum_exp_rows(const Matrix& log_values) {
  constexpr double kNegativeInfinity = -std::numeric_limits<double>::infinity();
  Vector result(log_values.rows());
  for (Eigen::Index row = 0; row < log_values.rows(); ++row) {
    const double largest = log_values.row(row).maxCoeff();
    // Subtracting -inf from -inf would give NaN: a row with no finite entry stays -inf.
    if (largest == kNegativeInfinity) {
      result(row) = kNegativeInfinity;
      continue;
    }
    result(row) = largest + std::log((log_values.row(row).array() - largest).exp().sum());
  }
  return result;
}

Matrix normalise_log_rows(const Matrix& log_values) {
  const Vector normaliser = log_sum_exp_rows(log_values);
  Matrix probabilities(log_values.rows(), log_values.cols());
  for (Eigen::Index row = 0; row < log_values.rows(); ++row) {
    if (!std::isfinite(normaliser(row))) {
      // No class has any support: spread evenly rather than emit NaN.
      probabilities.row(row).setConstant(1.0 / static_cast<double>(log_values.cols()));
      continue;
    }
    probabilities.row(row) = (log_values.row(row).array() - normaliser(row)).exp();
  }
  return probabilities;
}

Vector class_priors(const std::vector<std::vector<Eigen::Index>>& members, const std::string& mode,
                    const std::string& where) {
  Vector priors = Vector::Zero(static_cast<Eigen::Index>(members.size()));
  double total = 0.0;
  for (size_t k = 0; k < members.size(); ++k) {
    if (members[k].empty()) continue;
    if (mode == "empirical")
      priors(static_cast<Eigen::Index>(k)) = static_cast<double>(members[k].size());
    else if (mode == "uniform")
      priors(static_cast<Eigen::Index>(k)) = 1.0;
    else
      throw Error(where, "priors=" + mode + ": expected empirical or uniform");
    total += priors(static_cast<Eigen::Index>(k));
  }
  return priors / total;
}

std::string format_number(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

double positive_number(const Parameters& parameters, const std::string& key, double fallback,
                       bool allow_zero) {
  const double value = parameters.number(key, fallback);
  if (value < 0.0 || (!allow_zero && value == 0.0))
    throw Error(parameters.where(), key + "=" + format_number(value) + ": must be " +
                                        (allow_zero ? "zero or more" : "greater than zero"));
  return value;
}

nlohmann::json vector_to_json(const Vector& vector) {
  return std::vector<double>(vector.data(), vector.data() + vector.size());
}

nlohmann::json matrix_to_json(const Matrix& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index row = 0; row < matrix.rows(); ++row)
    rows.push_back(vector_to_json(matrix.row(row)));
  return rows;
}

Vector vector_from_json(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array()) throw Error(where, "expected an array of numbers");
  Vector vector(static_cast<Eigen::Index>(value.size()));
  for (size_t index = 0; index < value.size(); ++index) {
    if (!value[index].is_number())
      throw Error(where, "entry " + std::to_string(index) + " is not a number");
    vector(static_cast<Eigen::Index>(index)) = value[index].get<double>();
  }
  return vector;
}

Matrix matrix_from_json(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array()) throw Error(where, "expected an array of rows");
  if (value.empty()) return Matrix();
  const Eigen::Index columns = static_cast<Eigen::Index>(value[0].size());
  Matrix matrix(static_cast<Eigen::Index>(value.size()), columns);
  for (size_t row = 0; row < value.size(); ++row) {
    const Vector entries = vector_from_json(value[row], where + " row " + std::to_string(row));
    if (entries.size() != columns) throw Error(where, "rows differ in length");
    matrix.row(static_cast<Eigen::Index>(row)) = entries.transpose();
  }
  return matrix;
}

}  // namespace tactile::ml::support

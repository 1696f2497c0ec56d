#pragma once
// Helpers shared by the probabilistic classifiers (Gaussian ML, QDA, naive Bayes, EM):
// input checks that name the bad row and column, log-domain normalisation that never
// yields NaN, and JSON for Eigen vectors and matrices. Private to core/src/ml.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "tactile/ml/checks.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml {

inline constexpr double kNegativeInfinity = -std::numeric_limits<double>::infinity();

}  // namespace tactile::ml

namespace tactile::ml::support {

// Row indices of each class, in row order.
std::vector<std::vector<Eigen::Index>> rows_by_class(const std::vector<int>& y, int class_count);
// The rows `indices` of x, in that order.
Matrix select_rows(const Matrix& x, const std::vector<Eigen::Index>& indices);

// log Σ exp(values) of each row, exact for rows holding -infinity entries; a row of only
// -infinity gives -infinity.
Vector log_sum_exp_rows(const Matrix& log_values);
// exp(log_values - row log-sum-exp): each row becomes probabilities that sum to 1, with
// -infinity entries mapping to 0.
Matrix normalise_log_rows(const Matrix& log_values);

// Class priors: "empirical" (N_k / N) or "uniform" over the classes present in training.
Vector class_priors(const std::vector<std::vector<Eigen::Index>>& members, const std::string& mode,
                    const std::string& where);

// Shortest text that reads back as the same double (for parameters()).
std::string format_number(double value);
// A parameter that must be > 0 (or >= 0 when `allow_zero`); Error naming the key otherwise.
double positive_number(const Parameters& parameters, const std::string& key, double fallback,
                       bool allow_zero = false);

nlohmann::json vector_to_json(const Vector& vector);
nlohmann::json matrix_to_json(const Matrix& matrix);  // array of rows
Vector vector_from_json(const nlohmann::json& value, const std::string& where);
Matrix matrix_from_json(const nlohmann::json& value, const std::string& where);

}  // namespace tactile::ml::support

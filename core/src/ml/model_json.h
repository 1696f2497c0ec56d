#pragma once
// Matrices, vectors and parameters in saved models: plain JSON that restores the exact
// doubles (nlohmann writes the shortest text that reads back to the same double).

#include <charconv>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/ml/classifier.h"

namespace tactile::ml::model_json {

inline nlohmann::json from_matrix(const Matrix& matrix) {
  return {{"rows", matrix.rows()},
          {"columns", matrix.cols()},
          {"values", std::vector<double>(matrix.data(), matrix.data() + matrix.size())}};
}

inline Matrix to_matrix(const nlohmann::json& node, const std::string& where) {
  const auto rows = node.at("rows").get<Eigen::Index>();
  const auto columns = node.at("columns").get<Eigen::Index>();
  const auto values = node.at("values").get<std::vector<double>>();
  if (rows < 0 || columns < 0 || static_cast<size_t>(rows * columns) != values.size())
    throw Error(where, "matrix of " + std::to_string(rows) + " x " + std::to_string(columns) +
                           " holds " + std::to_string(values.size()) + " values");
  return Eigen::Map<const Matrix>(values.data(), rows, columns);
}

inline nlohmann::json from_vector(const Vector& vector) {
  return std::vector<double>(vector.data(), vector.data() + vector.size());
}

inline Vector to_vector(const nlohmann::json& node) {
  const auto values = node.get<std::vector<double>>();
  return Eigen::Map<const Vector>(values.data(), static_cast<Eigen::Index>(values.size()));
}

// Shortest text that reads back to the same double ("0.15", not "0.150000").
inline std::string format_number(double value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, result.ptr);
}

inline nlohmann::json from_parameters(const Parameters& parameters) {
  nlohmann::json node = nlohmann::json::object();
  for (const auto& [key, value] : parameters.values()) node[key] = value;
  return node;
}

inline Parameters to_parameters(const nlohmann::json& node, const std::string& where) {
  Parameters parameters;
  parameters.set_where(where);
  for (const auto& [key, value] : node.items()) parameters.set(key, value.get<std::string>());
  return parameters;
}

}  // namespace tactile::ml::model_json

#include "tactile/ml/logitboost.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>

#include "tactile/error.h"
#include "tactile/ml/checks.h"
#include "thresholds.h"

namespace tactile::ml {

namespace {

// Weka's Z_MAX: the working response of a confidently right sample is at most 3 in size.
constexpr double kResponseLimit = 3.0;

// Row-wise softmax, shifted by the row maximum so exp never overflows.
Matrix softmax(const Matrix& f) {
  Matrix p = (f.colwise() - f.rowwise().maxCoeff()).array().exp().matrix();
  return p.array().colwise() / p.rowwise().sum().array();
}

// Each feature's row order by value (stable), computed once: every stump sweeps all rows.
struct SortedFeatures {
  std::vector<std::vector<int64_t>> order;  // order[feature][rank] = row
};

SortedFeatures sort_features(const Matrix& x) {
  SortedFeatures sorted;
  sorted.order.resize(static_cast<size_t>(x.cols()));
  for (Eigen::Index feature = 0; feature < x.cols(); ++feature) {
    auto& order = sorted.order[static_cast<size_t>(feature)];
    order.resize(static_cast<size_t>(x.rows()));
    std::iota(order.begin(), order.end(), int64_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](int64_t a, int64_t b) { return x(a, feature) < x(b, feature); });
  }
  return sorted;
}

// Weighted least-squares stump: minimising Σ w (z - f)² with f constant on each side of a
// cut is maximising S_L²/W_L + S_R²/W_R (S = Σ w z, W = Σ w on each side).
RegressionStump fit_stump(const Matrix& x, const SortedFeatures& sorted, const Vector& response,
                          const Vector& weight) {
  RegressionStump stump;
  const double total_weight = weight.sum();
  if (!(total_weight > 0.0)) return stump;  // every sample fitted already: add nothing
  const double total_sum = weight.dot(response);
  stump.below = total_sum / total_weight;
  const double minimum_side = 1e-12 * total_weight;
  double best = total_sum * total_sum / total_weight;
  const Eigen::Index rows = x.rows();
  for (Eigen::Index feature = 0; feature < x.cols(); ++feature) {
    const auto& order = sorted.order[static_cast<size_t>(feature)];
    double left_weight = 0.0;
    double left_sum = 0.0;
    for (Eigen::Index rank = 0; rank + 1 < rows; ++rank) {
      const int64_t row = order[static_cast<size_t>(rank)];
      left_weight += weight(row);
      left_sum += weight(row) * response(row);
      const double lower = x(row, feature);
      const double upper = x(order[static_cast<size_t>(rank + 1)], feature);
      const double right_weight = total_weight - left_weight;
      if (!(lower < upper) || left_weight <= minimum_side || right_weight <= minimum_side) continue;
      const double right_sum = total_sum - left_sum;
      const double fit = left_sum * left_sum / left_weight + right_sum * right_sum / right_weight;
      if (fit > best + 1e-12 * std::abs(best)) {
        best = fit;
        stump.feature = static_cast<int>(feature);
        stump.threshold = midpoint(lower, upper);
        stump.below = left_sum / left_weight;
        stump.above = right_sum / right_weight;
      }
    }
  }
  return stump;
}

// Friedman et al. Alg. 6 step 2(b) with shrinkage: F_j += ν (J-1)/J (f_j - (1/J) Σ_k f_k).
void add_centred(Matrix& f, const Matrix& stump_values, double learning_rate) {
  const double classes = static_cast<double>(stump_values.cols());
  const double factor = learning_rate * (classes - 1.0) / classes;
  f += factor * (stump_values.colwise() - stump_values.rowwise().mean());
}

}  // namespace

LogitBoost::LogitBoost(const std::string& preset, const Parameters& parameters) {
  if (preset != "logitboost")
    throw Error(parameters.where(), "no LogitBoost preset named '" + preset + "'");
  parameters.expect_only({"learners", "learning_rate"});
  learners_ = parameters.integer("learners", learners_);
  learning_rate_ = parameters.number("learning_rate", learning_rate_);
  if (learners_ < 1) throw Error(parameters.where(), "learners must be 1 or more");
  if (!(learning_rate_ > 0.0)) throw Error(parameters.where(), "learning_rate must be positive");
}

Parameters LogitBoost::parameters() const {
  Parameters parameters;
  parameters.set("learners", std::to_string(learners_));
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof(buffer), learning_rate_);
  parameters.set("learning_rate", std::string(buffer, written.ptr));
  return parameters;
}

void LogitBoost::fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t) {
  check_training_set(x, y, class_count, "logitboost");
  fitted_ = false;
  class_count_ = class_count;
  feature_count_ = x.cols();
  stumps_.clear();

  const SortedFeatures sorted = sort_features(x);
  const Eigen::Index rows = x.rows();
  Matrix f = Matrix::Zero(rows, class_count);
  Matrix probability = Matrix::Constant(rows, class_count, 1.0 / class_count);
  Matrix stump_values(rows, class_count);
  Vector response(rows);
  Vector weight(rows);
  for (int64_t iteration = 0; iteration < learners_; ++iteration) {
    std::vector<RegressionStump> stumps;
    for (int label = 0; label < class_count; ++label) {
      for (Eigen::Index row = 0; row < rows; ++row) {
        const double p = probability(row, label);
        // z = (y* - p) / (p (1 - p)) written per case so p = 0 or 1 gives ±inf, then clipped.
        response(row) = y[static_cast<size_t>(row)] == label
                            ? std::min(1.0 / p, kResponseLimit)
                            : std::max(-1.0 / (1.0 - p), -kResponseLimit);
        weight(row) = p * (1.0 - p);
      }
      const RegressionStump stump = fit_stump(x, sorted, response, weight);
      for (Eigen::Index row = 0; row < rows; ++row) stump_values(row, label) = stump(x, row);
      stumps.push_back(stump);
    }
    add_centred(f, stump_values, learning_rate_);
    probability = softmax(f);
    stumps_.push_back(std::move(stumps));
  }
  fitted_ = true;
}

Matrix LogitBoost::scores(const Matrix& x) const {
  check_fitted(fitted_, "logitboost");
  check_query(x, feature_count_, "logitboost");
  Matrix f = Matrix::Zero(x.rows(), class_count_);
  Matrix stump_values(x.rows(), class_count_);
  for (const auto& stumps : stumps_) {
    for (int label = 0; label < class_count_; ++label)
      for (Eigen::Index row = 0; row < x.rows(); ++row)
        stump_values(row, label) = stumps[static_cast<size_t>(label)](x, row);
    add_centred(f, stump_values, learning_rate_);
  }
  return softmax(f);
}

nlohmann::json LogitBoost::save() const {
  if (!fitted_) throw Error("logitboost", "save() before fit()");
  nlohmann::json iterations = nlohmann::json::array();
  for (const auto& stumps : stumps_) {
    nlohmann::json saved = nlohmann::json::array();
    for (const RegressionStump& stump : stumps)
      saved.push_back({{"feature", stump.feature},
                       {"threshold", stump.threshold},
                       {"below", stump.below},
                       {"above", stump.above}});
    iterations.push_back(std::move(saved));
  }
  return {{"class_count", class_count_},
          {"feature_count", feature_count_},
          {"learning_rate", learning_rate_},
          {"stumps", std::move(iterations)}};
}

void LogitBoost::load(const nlohmann::json& model) {
  const std::string where = "logitboost model";
  fitted_ = false;
  try {
    const int class_count = model.at("class_count").get<int>();
    const auto feature_count = model.at("feature_count").get<Eigen::Index>();
    const double learning_rate = model.at("learning_rate").get<double>();
    if (class_count < 1 || feature_count < 1 || !(learning_rate > 0.0) ||
        !std::isfinite(learning_rate))
      throw Error(where, "bad class_count, feature_count or learning_rate");
    std::vector<std::vector<RegressionStump>> iterations;
    for (const auto& saved_iteration : model.at("stumps")) {
      std::vector<RegressionStump> stumps;
      for (const auto& saved : saved_iteration) {
        RegressionStump stump;
        stump.feature = saved.at("feature").get<int>();
        stump.threshold = saved.at("threshold").get<double>();
        stump.below = saved.at("below").get<double>();
        stump.above = saved.at("above").get<double>();
        if (stump.feature >= feature_count || stump.feature < -1 ||
            !std::isfinite(stump.threshold) || !std::isfinite(stump.below) ||
            !std::isfinite(stump.above))
          throw Error(where, "stump " + std::to_string(iterations.size()) + "/" +
                                 std::to_string(stumps.size()) + " has a bad feature or value");
        stumps.push_back(stump);
      }
      if (static_cast<int>(stumps.size()) != class_count)
        throw Error(where, "iteration " + std::to_string(iterations.size()) + " has " +
                               std::to_string(stumps.size()) + " stumps, expected " +
                               std::to_string(class_count));
      iterations.push_back(std::move(stumps));
    }
    if (iterations.empty()) throw Error(where, "no stumps");
    class_count_ = class_count;
    feature_count_ = feature_count;
    learning_rate_ = learning_rate;
    learners_ = static_cast<int64_t>(iterations.size());
    stumps_ = std::move(iterations);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  fitted_ = true;
}

std::unique_ptr<Classifier> make_logitboost_classifier(const Parameters& parameters) {
  return std::make_unique<LogitBoost>("logitboost", parameters);
}

}  // namespace tactile::ml

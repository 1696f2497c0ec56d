#include "tactile/ml/knn.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>

#include "tactile/error.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

// A neighbour closer than this counts as "at distance 0" for the inverse weights.
constexpr double kZeroDistance = 1e-12;

std::string metric_text(KnnMetric metric) {
  return metric == KnnMetric::kCosine ? "cosine" : "euclidean";
}

KnnMetric parse_metric(const Parameters& parameters, KnnMetric fallback) {
  const std::string text = parameters.text("metric", metric_text(fallback));
  if (text == "euclidean") return KnnMetric::kEuclidean;
  if (text == "cosine") return KnnMetric::kCosine;
  throw Error(parameters.where(), "metric=" + text + ": expected euclidean or cosine");
}

std::string weights_text(KnnWeights weights) {
  switch (weights) {
    case KnnWeights::kInverse:
      return "inverse";
    case KnnWeights::kSquaredInverse:
      return "squared-inverse";
    case KnnWeights::kEqual:
      break;
  }
  return "equal";
}

int positive_count(const Parameters& parameters, const std::string& key, int fallback,
                   int minimum) {
  const int64_t value = parameters.integer(key, fallback);
  if (value < minimum || value > 1'000'000)
    throw Error(parameters.where(), key + "=" + std::to_string(value) + ": expected at least " +
                                        std::to_string(minimum));
  return static_cast<int>(value);
}

std::vector<int> read_labels(const nlohmann::json& model, int class_count, size_t count,
                             const std::string& where) {
  auto labels = model.at("labels").get<std::vector<int>>();
  if (labels.size() != count) throw Error(where, "model has a label count unlike its samples");
  for (int label : labels)
    if (label < 0 || label >= class_count) throw Error(where, "model has a label out of range");
  return labels;
}

nlohmann::json matrix_to_json(const Matrix& matrix) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index row = 0; row < matrix.rows(); ++row) {
    std::vector<double> values(static_cast<size_t>(matrix.cols()));
    for (Eigen::Index column = 0; column < matrix.cols(); ++column)
      values[static_cast<size_t>(column)] = matrix(row, column);
    rows.push_back(values);
  }
  return rows;
}

Matrix matrix_from_json(const nlohmann::json& rows, const std::string& where) {
  if (!rows.is_array() || rows.empty()) throw Error(where, "model has no samples");
  const size_t columns = rows[0].size();
  Matrix matrix(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(columns));
  for (size_t row = 0; row < rows.size(); ++row) {
    const auto values = rows[row].get<std::vector<double>>();
    if (values.size() != columns) throw Error(where, "model samples differ in length");
    for (size_t column = 0; column < columns; ++column)
      matrix(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column)) = values[column];
  }
  if (!matrix.allFinite()) throw Error(where, "model has a value that is not finite");
  return matrix;
}

}  // namespace

//---- KnnClassifier --------------------------------------------------------------------------

KnnClassifier::KnnClassifier(std::string name, KnnSettings settings)
    : name_(std::move(name)), settings_(settings) {
  if (settings_.k < 1) throw Error("classifier " + name_, "k must be at least 1");
}

Parameters KnnClassifier::parameters() const {
  Parameters parameters;
  parameters.set("k", std::to_string(settings_.k));
  parameters.set("metric", metric_text(settings_.metric));
  parameters.set("weights", weights_text(settings_.weights));
  parameters.set("standardize",
                 !settings_.standardize ? "false" : (settings_.range ? "range" : "true"));
  return parameters;
}

void KnnClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                        uint64_t /*seed: k-NN draws nothing*/) {
  check_training_set(x, y, class_count, "classifier " + name_);
  class_count_ = class_count;
  labels_ = y;
  if (settings_.standardize) {
    if (settings_.range)
      standardizer_.fit_range(x);
    else
      standardizer_.fit(x);
    samples_ = standardizer_.transform(x).transpose();
  } else {
    standardizer_ = Standardizer();
    samples_ = x.transpose();
  }
  prepare();
}

void KnnClassifier::prepare() {
  norms_ = samples_.colwise().norm().transpose();
  samples_float_ = samples_.transpose().cast<float>();
}

// Queries are searched in blocks: one matrix product gives every query's approximate
// distance to every sample (|q|² + |x|² - 2 q·x, or the cosine from q·x), a selection keeps
// the candidates within a rounding margin of the k-th, and only those are measured
// exactly as one query at a time would (so ties and exact matches decide as before).
std::vector<std::vector<Neighbour>> KnnClassifier::neighbours(const Matrix& x) const {
  const std::string where = "classifier " + name_;
  if (labels_.empty()) throw Error(where, "not fitted");
  check_query(x, samples_.rows(), where);
  const Matrix queries = settings_.standardize ? standardizer_.transform(x) : x;
  const auto count = static_cast<int64_t>(labels_.size());
  const int64_t k = std::min<int64_t>(settings_.k, count);
  std::vector<std::vector<Neighbour>> result(static_cast<size_t>(x.rows()));
  const bool euclidean = settings_.metric == KnnMetric::kEuclidean;
  const Vector squared_norms = norms_.array().square().matrix();
  const double largest_norm = count > 0 ? norms_.maxCoeff() : 0.0;
  // Exact distance of one query to one sample, as the one-at-a-time search measured it.
  const auto exact = [&](const Vector& point, double point_norm, int64_t row) {
    if (euclidean) return (samples_.col(row) - point).norm();
    // Cosine distance 1 - x.y / (|x| |y|) (spec §2.13); a zero vector is at distance 1.
    const double product = point_norm * norms_(row);
    return product > 0.0 ? std::max(0.0, 1.0 - samples_.col(row).dot(point) / product) : 1.0;
  };
  constexpr Eigen::Index kBlock = 256;
  const double margin = 4.0 * (static_cast<double>(samples_.rows()) + 2.0) * 6e-8 * 2.0;
  std::vector<double> smallest;  // the k smallest approximate values so far, ascending
  std::vector<Neighbour> candidates;
  for (Eigen::Index first = 0; first < queries.rows(); first += kBlock) {
    const Eigen::Index block = std::min(kBlock, queries.rows() - first);
    // count x block: each query's products with every sample, contiguous per query, in
    // single precision (only to choose candidates).
    const Eigen::MatrixXf block_queries =
        queries.middleRows(first, block).transpose().cast<float>();
    Matrix values = (samples_float_ * block_queries).cast<double>();
    Vector point_norms(block);
    for (Eigen::Index i = 0; i < block; ++i) point_norms(i) = queries.row(first + i).norm();
    if (euclidean) {
      // |x|² - 2 q·x ranks as |q - x|² does (|q|² is the same for every sample).
      values = (-2.0 * values).colwise() + squared_norms;
    } else {
      for (Eigen::Index i = 0; i < block; ++i) {
        const Eigen::ArrayXd product = norms_.array() * point_norms(i);
        values.col(i) = (product > 0.0).select(1.0 - values.col(i).array() / product, 1.0).matrix();
      }
    }
    for (Eigen::Index i = 0; i < block; ++i) {
      const Eigen::Index query = first + i;
      const Vector point = queries.row(query).transpose();
      const double point_norm = point_norms(i);
      const double* column = values.col(i).data();
      smallest.assign(static_cast<size_t>(k), std::numeric_limits<double>::infinity());
      for (int64_t row = 0; row < count; ++row) {
        const double value = column[row];
        if (!(value < smallest.back())) continue;
        size_t at = smallest.size() - 1;
        while (at > 0 && smallest[at - 1] > value) smallest[at] = smallest[at - 1], --at;
        smallest[at] = value;
      }
      // Rounding of the single-precision product: each of its `features` terms can be off
      // by an ulp of |q||x| (2^-24 relative), the float inputs by as much again; the margin
      // is four times the sum, so every sample that can be among the k nearest stays.
      const double scale =
          euclidean ? (point_norm + largest_norm) * (point_norm + largest_norm) : 1.0;
      const double bound = smallest.back() + margin * scale;
      candidates.clear();
      for (int64_t row = 0; row < count; ++row)
        if (column[row] <= bound) candidates.push_back({row, exact(point, point_norm, row)});
      std::sort(candidates.begin(), candidates.end(), [](const Neighbour& a, const Neighbour& b) {
        return a.distance < b.distance || (a.distance == b.distance && a.row < b.row);
      });
      candidates.resize(static_cast<size_t>(k));
      result[static_cast<size_t>(query)] = candidates;
    }
  }
  return result;
}

Vector KnnClassifier::vote(const std::vector<Neighbour>& nearest, KnnWeights weights) const {
  Vector votes = Vector::Zero(class_count_);
  // Inverse weights would be infinite at distance 0: such neighbours share the whole vote.
  const bool exact_match = weights != KnnWeights::kEqual && !nearest.empty() &&
                           nearest.front().distance <= kZeroDistance;
  for (const Neighbour& neighbour : nearest) {
    double weight = 1.0;
    if (exact_match)
      weight = neighbour.distance <= kZeroDistance ? 1.0 : 0.0;
    else if (weights == KnnWeights::kInverse)
      weight = 1.0 / neighbour.distance;
    else if (weights == KnnWeights::kSquaredInverse)
      weight = 1.0 / (neighbour.distance * neighbour.distance);
    votes(labels_[static_cast<size_t>(neighbour.row)]) += weight;
  }
  return votes / votes.sum();
}

KnnWeights KnnClassifier::score_weights() const {
  // Equal votes of k neighbours take few values (k = 10: multiples of 0.1); 1/d tells a
  // query between two close neighbours from one between two far ones.
  return settings_.weights == KnnWeights::kEqual ? KnnWeights::kInverse : settings_.weights;
}

Matrix KnnClassifier::scores(const Matrix& x) const {
  const auto nearest = neighbours(x);
  Matrix result(x.rows(), class_count_);
  for (Eigen::Index row = 0; row < x.rows(); ++row)
    result.row(row) = vote(nearest[static_cast<size_t>(row)], score_weights()).transpose();
  return result;
}

std::vector<int> KnnClassifier::predict(const Matrix& x) const { return decide(x).classes; }

Classifier::Decisions KnnClassifier::decide(const Matrix& x) const {
  const auto nearest = neighbours(x);
  Decisions decisions;
  decisions.classes.assign(static_cast<size_t>(x.rows()), kUnknownClass);
  decisions.scores.resize(x.rows(), class_count_);
  for (size_t row = 0; row < nearest.size(); ++row) {
    const Vector votes = vote(nearest[row], settings_.weights);
    decisions.scores.row(static_cast<Eigen::Index>(row)) =
        vote(nearest[row], score_weights()).transpose();
    const double best = votes.maxCoeff();
    // Spec §4.9: a tie between classes goes to the nearest neighbour among the tied classes.
    for (const Neighbour& neighbour : nearest[row]) {
      const int label = labels_[static_cast<size_t>(neighbour.row)];
      if (votes(label) == best) {
        decisions.classes[row] = label;
        break;
      }
    }
  }
  return decisions;
}

nlohmann::json KnnClassifier::save() const {
  nlohmann::json model = {{"class_count", class_count_},
                          {"labels", labels_},
                          {"samples", matrix_to_json(samples_.transpose())}};
  if (settings_.standardize) model["standardizer"] = standardizer_.save();
  return model;
}

void KnnClassifier::load(const nlohmann::json& model) {
  const std::string where = "model " + name_;
  const int class_count = model.at("class_count").get<int>();
  if (class_count < 1) throw Error(where, "model has no classes");
  Matrix samples = matrix_from_json(model.at("samples"), where);
  auto labels = read_labels(model, class_count, static_cast<size_t>(samples.rows()), where);
  Standardizer standardizer;
  if (settings_.standardize) {
    standardizer.load(model.at("standardizer"));
    if (standardizer.mean.size() != samples.cols())
      throw Error(where, "standardizer and samples differ in feature count");
  }
  class_count_ = class_count;
  labels_ = std::move(labels);
  samples_ = samples.transpose();
  standardizer_ = std::move(standardizer);
  prepare();
}

//---- SubspaceKnnClassifier -----------------------------------------------------------------

SubspaceKnnClassifier::SubspaceKnnClassifier(int learners, int dimensions, KnnMetric metric,
                                             bool standardize)
    : learners_(learners), dimensions_(dimensions), metric_(metric), standardize_(standardize) {}

Parameters SubspaceKnnClassifier::parameters() const {
  Parameters parameters;
  parameters.set("learners", std::to_string(learners_));
  parameters.set("dimensions", std::to_string(dimensions_));
  parameters.set("metric", metric_text(metric_));
  parameters.set("standardize", standardize_ ? "true" : "false");
  return parameters;
}

void SubspaceKnnClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                                uint64_t seed) {
  check_training_set(x, y, class_count, "classifier subspace-knn");
  const int64_t predictors = x.cols();
  // Spec §2.13: subspace dimension ceil(P/2) unless given; never more than P.
  const int64_t dimensions =
      dimensions_ > 0 ? std::min<int64_t>(dimensions_, predictors) : (predictors + 1) / 2;
  std::mt19937_64 random(seed);
  std::vector<std::vector<int64_t>> subspaces;
  for (int learner = 0; learner < learners_; ++learner) {
    // Partial Fisher-Yates: the first `dimensions` draws of a shuffle of 0..P-1.
    std::vector<int64_t> predictors_left(static_cast<size_t>(predictors));
    std::iota(predictors_left.begin(), predictors_left.end(), int64_t{0});
    for (int64_t i = 0; i < dimensions; ++i)
      std::swap(predictors_left[static_cast<size_t>(i)],
                predictors_left[static_cast<size_t>(i + uniform_index(random, predictors - i))]);
    predictors_left.resize(static_cast<size_t>(dimensions));
    std::sort(predictors_left.begin(), predictors_left.end());
    subspaces.push_back(std::move(predictors_left));
  }
  if (standardize_) {
    standardizer_.fit(x);
    samples_ = standardizer_.transform(x);
  } else {
    standardizer_ = Standardizer();
    samples_ = x;
  }
  class_count_ = class_count;
  labels_ = y;
  subspaces_ = std::move(subspaces);
}

Matrix SubspaceKnnClassifier::scores(const Matrix& x) const {
  const std::string where = "classifier subspace-knn";
  if (subspaces_.empty()) throw Error(where, "not fitted");
  check_query(x, samples_.cols(), where);
  const Matrix queries = standardize_ ? standardizer_.transform(x) : x;
  Matrix votes = Matrix::Zero(x.rows(), class_count_);
  // Each learner is made when it votes and dropped after: 30 learners each holding half of
  // Robovie's 37,401 columns were 0.9 GB, one at a time 30 MB.
  KnnSettings settings;
  settings.metric = metric_;
  for (const std::vector<int64_t>& subspace : subspaces_) {
    KnnClassifier member("subspace-knn learner", settings);
    member.fit(samples_(Eigen::all, subspace), labels_, class_count_, 0);
    const std::vector<int> answers = member.predict(queries(Eigen::all, subspace));
    for (size_t row = 0; row < answers.size(); ++row)
      votes(static_cast<Eigen::Index>(row), answers[row]) += 1.0;
  }
  return votes / static_cast<double>(subspaces_.size());
}

nlohmann::json SubspaceKnnClassifier::save() const {
  nlohmann::json model = {{"class_count", class_count_},
                          {"labels", labels_},
                          {"samples", matrix_to_json(samples_)},
                          {"subspaces", subspaces_}};
  if (standardize_) model["standardizer"] = standardizer_.save();
  return model;
}

void SubspaceKnnClassifier::load(const nlohmann::json& model) {
  const std::string where = "model subspace-knn";
  const int class_count = model.at("class_count").get<int>();
  if (class_count < 1) throw Error(where, "model has no classes");
  Matrix samples = matrix_from_json(model.at("samples"), where);
  auto labels = read_labels(model, class_count, static_cast<size_t>(samples.rows()), where);
  auto subspaces = model.at("subspaces").get<std::vector<std::vector<int64_t>>>();
  if (subspaces.empty()) throw Error(where, "model has no learners");
  for (const auto& subspace : subspaces)
    for (int64_t predictor : subspace)
      if (subspace.empty() || predictor < 0 || predictor >= samples.cols())
        throw Error(where, "model has a subspace outside its predictors");
  Standardizer standardizer;
  if (standardize_) {
    standardizer.load(model.at("standardizer"));
    if (standardizer.mean.size() != samples.cols())
      throw Error(where, "standardizer and samples differ in feature count");
  }
  class_count_ = class_count;
  samples_ = std::move(samples);
  labels_ = std::move(labels);
  subspaces_ = std::move(subspaces);
  standardizer_ = std::move(standardizer);
}

//---- Factories ------------------------------------------------------------------------------

namespace {

std::unique_ptr<Classifier> make_knn_from(const std::string& name, KnnSettings settings,
                                          const Parameters& parameters) {
  parameters.expect_only({"k", "metric", "weights", "standardize"});
  settings.k = positive_count(parameters, "k", settings.k, 1);
  settings.metric = parse_metric(parameters, settings.metric);
  const std::string weights = parameters.text("weights", weights_text(settings.weights));
  if (weights == "equal")
    settings.weights = KnnWeights::kEqual;
  else if (weights == "inverse")
    settings.weights = KnnWeights::kInverse;
  else if (weights == "squared-inverse")
    settings.weights = KnnWeights::kSquaredInverse;
  else
    throw Error(parameters.where(),
                "weights=" + weights + ": expected equal, inverse or squared-inverse");
  // standardize=true (z-scores), false, or range (each feature's training range onto [0, 1]).
  const std::string scaling = parameters.text("standardize", "");
  static const std::set<std::string> kKnown = {"",  "range", "true", "false", "1",
                                               "0", "yes",   "no",   "on",    "off"};
  if (!kKnown.contains(scaling))
    throw Error(parameters.where(), "standardize=" + scaling + ": expected true, false or range");
  if (scaling == "range") {
    settings.standardize = true;
    settings.range = true;
  } else {
    settings.standardize = parameters.flag("standardize", settings.standardize);
    settings.range = false;
  }
  return std::make_unique<KnnClassifier>(name, settings);
}

}  // namespace

std::unique_ptr<Classifier> make_knn_classifier(const Parameters& parameters) {
  return make_knn_from("knn", KnnSettings{}, parameters);
}

std::unique_ptr<Classifier> make_cosine_knn_classifier(const Parameters& parameters) {
  return make_knn_from("cosine-knn", {10, KnnMetric::kCosine, KnnWeights::kEqual, true},
                       parameters);
}

std::unique_ptr<Classifier> make_weighted_knn_classifier(const Parameters& parameters) {
  return make_knn_from("weighted-knn",
                       {10, KnnMetric::kEuclidean, KnnWeights::kSquaredInverse, true}, parameters);
}

std::unique_ptr<Classifier> make_subspace_knn_classifier(const Parameters& parameters) {
  parameters.expect_only({"learners", "dimensions", "metric", "standardize"});
  const int learners = positive_count(parameters, "learners", 30, 1);
  const int dimensions = positive_count(parameters, "dimensions", 0, 0);
  return std::make_unique<SubspaceKnnClassifier>(learners, dimensions,
                                                 parse_metric(parameters, KnnMetric::kEuclidean),
                                                 parameters.flag("standardize", true));
}

}  // namespace tactile::ml

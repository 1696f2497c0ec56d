#include "tactile/ml/som.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "model_json.h"
#include "tactile/error.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

const char* const kSomWhere = "som";

// Squared distance of two neurons on the grid (whole numbers, so comparisons are exact).
int grid_squared_distance(const SomMap& map, int from, int to) {
  const int dx = from % map.columns - to % map.columns;
  const int dy = from / map.columns - to / map.columns;
  return dx * dx + dy * dy;
}

Vector distances_to_neurons(const SomMap& map, const Vector& x) {
  return (map.weights.rowwise() - x.transpose()).rowwise().norm();
}

// theta for every (winner, neuron) pair at one radius: the same 49 x 49 numbers serve every
// input of an epoch.
Matrix neighbourhood_table(const SomMap& map, double radius) {
  const int neurons = map.rows * map.columns;
  Matrix table(neurons, neurons);
  for (int winner = 0; winner < neurons; ++winner)
    table.col(winner) = som_neighbourhood(map, winner, radius);
  return table;
}

// A SOM over inputs that lie in a space of fewer dimensions than they have columns (n rows,
// d > n columns), trained there exactly. Q (d x n, orthonormal columns) spans the rows. A
// neuron w splits into its part in that span, w Q (n numbers), and the part outside it, w_o.
// An update w += h (x - w) moves the first as the full weights would and only shrinks the
// second, w_o *= 1 - h, since x has no part outside; and |x - w|^2 = |x Q - w Q|^2 + |w_o|^2.
// So the map needs the n coordinates, |w_o|^2 and the product of the shrinks per neuron: each
// step costs neurons x n instead of neurons x d, and the full weights come back at the end.
struct SomSubspace {
  SomSubspace() = default;
  SomSubspace(const Matrix& rows, const Matrix& initial) {
    const Eigen::HouseholderQR<Matrix> qr(rows.transpose());
    basis = qr.householderQ() * Matrix::Identity(rows.cols(), rows.rows());
    inputs = rows * basis;
    weights = initial * basis;
    outside_initial = initial - weights * basis.transpose();
    outside = outside_initial.rowwise().squaredNorm();
  }
  // The full weights from the trained coordinates and each neuron's kept share of its
  // initial outside part.
  Matrix full_weights(const Matrix& trained, const Vector& kept) const {
    return trained * basis.transpose() + kept.asDiagonal() * outside_initial;
  }

  Matrix basis;            // d x n
  Matrix inputs;           // the rows in the basis, n x n
  Matrix weights;          // the initial weights in the basis, neurons x n
  Matrix outside_initial;  // the initial weights' parts outside the span, neurons x d
  Vector outside;          // their squared norms
};

}  // namespace

//---- Map steps (spec §5.10)

double SomSchedule::radius(int epoch) const {
  if (epochs <= 1) return radius_start;
  return radius_start - (radius_start - radius_end) * epoch / (epochs - 1);
}

double SomSchedule::rate(int epoch) const {
  if (epochs <= 1) return rate_start;
  return rate_start * std::pow(rate_end / rate_start, static_cast<double>(epoch) / (epochs - 1));
}

int som_winner(const SomMap& map, const Vector& x) {
  Eigen::Index winner = 0;
  (map.weights.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&winner);
  return static_cast<int>(winner);
}

// Flux paper eq 1, as printed (divides by r, not 2 r^2), with the text's hard bubble d < r.
Vector som_neighbourhood(const SomMap& map, int winner, double radius) {
  const int neurons = map.rows * map.columns;
  Vector theta(neurons);
  for (int neuron = 0; neuron < neurons; ++neuron) {
    const double squared = grid_squared_distance(map, neuron, winner);
    theta(neuron) = std::sqrt(squared) < radius ? std::exp(-squared / radius) : 0.0;
  }
  return theta;
}

// Flux paper eq 2: w_k <- w_k + alpha theta_k (x - w_k).
int som_step(SomMap& map, const Vector& x, double radius, double rate) {
  const int winner = som_winner(map, x);
  const Vector theta = som_neighbourhood(map, winner, radius);
  map.weights += (rate * theta).asDiagonal() * ((-map.weights).rowwise() + x.transpose());
  return winner;
}

//---- The classifier

SomClassifier::SomClassifier(const Parameters& parameters) {
  parameters.expect_only({"rows", "columns", "epochs", "radius_start", "radius_end", "rate_start",
                          "rate_end", "initial", "scale", "empty", "subspace"});
  const std::string where = parameters.where();
  const auto rows = parameters.integer("rows", 7);
  const auto columns = parameters.integer("columns", 7);
  if (rows < 1 || columns < 1 || rows * columns > 1000000)
    throw Error(where, "rows=" + std::to_string(rows) + ", columns=" + std::to_string(columns) +
                           ": the grid needs 1 to 1000000 neurons");
  map_.rows = static_cast<int>(rows);
  map_.columns = static_cast<int>(columns);
  const auto epochs = parameters.integer("epochs", 1000);
  if (epochs < 1 || epochs > 100000000)
    throw Error(where, "epochs=" + std::to_string(epochs) + ": must lie in 1..100000000");
  schedule_.epochs = static_cast<int>(epochs);
  // R_MAX = 7 on the paper's 7 x 7 grid: the bubble starts as wide as the map.
  schedule_.radius_start = parameters.number("radius_start", std::max(map_.rows, map_.columns));
  schedule_.radius_end = parameters.number("radius_end", 0.5);
  schedule_.rate_start = parameters.number("rate_start", 0.5);
  schedule_.rate_end = parameters.number("rate_end", 0.01);
  for (const auto& [key, value] : {std::pair{"radius_start", schedule_.radius_start},
                                   {"radius_end", schedule_.radius_end},
                                   {"rate_start", schedule_.rate_start},
                                   {"rate_end", schedule_.rate_end}})
    if (!(value > 0.0))
      throw Error(where,
                  std::string(key) + "=" + model_json::format_number(value) + ": must be > 0");
  const std::string initial = parameters.text("initial", "uniform");
  if (initial != "uniform" && initial != "normal")
    throw Error(where, "initial=" + initial + ": expected uniform or normal");
  normal_initial_ = initial == "normal";
  scale_inputs_ = parameters.flag("scale", true);
  const std::string empty = parameters.text("empty", "nearest");
  if (empty != "nearest" && empty != "unknown")
    throw Error(where, "empty=" + empty + ": expected nearest or unknown");
  empty_unknown_ = empty == "unknown";
  subspace_ = parameters.flag("subspace", true);
}

Parameters SomClassifier::parameters() const {
  Parameters parameters;
  parameters.set_where(kSomWhere);
  parameters.set("rows", std::to_string(map_.rows));
  parameters.set("columns", std::to_string(map_.columns));
  parameters.set("epochs", std::to_string(schedule_.epochs));
  parameters.set("radius_start", model_json::format_number(schedule_.radius_start));
  parameters.set("radius_end", model_json::format_number(schedule_.radius_end));
  parameters.set("rate_start", model_json::format_number(schedule_.rate_start));
  parameters.set("rate_end", model_json::format_number(schedule_.rate_end));
  parameters.set("initial", normal_initial_ ? "normal" : "uniform");
  parameters.set("scale", scale_inputs_ ? "true" : "false");
  parameters.set("empty", empty_unknown_ ? "unknown" : "nearest");
  parameters.set("subspace", subspace_ ? "true" : "false");
  return parameters;
}

// Spec §5.9: (x - min) / (max - min) with the training extremes, test values not clipped;
// spec §6.4: a range of 0 gives 0.
Matrix SomClassifier::scale(const Matrix& x) const {
  if (!scale_inputs_) return x;
  const Vector divisor = (range_.array() > 0.0).select(range_, 1.0);
  const Vector keep = (range_.array() > 0.0).select(Vector::Ones(range_.size()), 0.0);
  return ((x.rowwise() - minimum_.transpose()).array().rowwise() / divisor.transpose().array())
             .rowwise() *
         keep.transpose().array();
}

void SomClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                        uint64_t seed) {
  check_training_set(x, y, class_count, kSomWhere);
  minimum_ = x.colwise().minCoeff().transpose();
  range_ = x.colwise().maxCoeff().transpose() - minimum_;
  class_count_ = class_count;
  const Matrix scaled = scale(x);

  const int neurons = map_.rows * map_.columns;
  Random random{std::mt19937_64(seed)};
  map_.weights.resize(neurons, x.cols());
  for (int neuron = 0; neuron < neurons; ++neuron)
    for (Eigen::Index feature = 0; feature < x.cols(); ++feature)
      map_.weights(neuron, feature) =
          normal_initial_ ? random.truncated_normal(0.5, 0.2, 2.0) : random.uniform(0.1, 0.9);

  // A table wider than it is long (183 segments x 37,401 correlations) is trained in the
  // span of its rows, exactly (see SomSubspace): the same winners, the same weights, for a
  // fraction of the work.
  const bool reduce = subspace_ && scaled.cols() > scaled.rows();
  const SomSubspace subspace = reduce ? SomSubspace(scaled, map_.weights) : SomSubspace();
  const Matrix& inputs = reduce ? subspace.inputs : scaled;
  Matrix reduced_weights = subspace.weights;
  Matrix& weights = reduce ? reduced_weights : map_.weights;
  Vector outside = reduce ? subspace.outside : Vector::Zero(neurons);  // squared, per neuron
  Vector kept = Vector::Ones(neurons);  // what is left of each neuron's initial outside part

  std::vector<int64_t> order(static_cast<size_t>(x.rows()));
  std::iota(order.begin(), order.end(), 0);
  training_errors_.assign(static_cast<size_t>(schedule_.epochs), {});
  Vector sample(inputs.cols());
  for (int epoch = 0; epoch < schedule_.epochs; ++epoch) {
    shuffle(order, random.engine());
    const Matrix table = neighbourhood_table(map_, schedule_.radius(epoch));
    const double rate = schedule_.rate(epoch);
    SomEpochError& error = training_errors_[static_cast<size_t>(epoch)];
    for (const int64_t row : order) {
      sample = inputs.row(row).transpose();
      Eigen::Index winner = 0;
      const double squared =
          ((weights.rowwise() - sample.transpose()).rowwise().squaredNorm() + outside)
              .minCoeff(&winner);
      const double distance = std::sqrt(squared);
      error.mean += distance;
      error.max = std::max(error.max, distance);
      const Vector step = rate * table.col(winner);
      weights += step.asDiagonal() * ((-weights).rowwise() + sample.transpose());
      if (reduce) {
        const Vector shrink = Vector::Ones(neurons) - step;
        outside.array() *= shrink.array().square();
        kept.array() *= shrink.array();
      }
    }
    error.mean /= static_cast<double>(order.size());
    if (epoch_observer_) epoch_observer_(epoch + 1, schedule_.epochs);
  }
  if (reduce) map_.weights = subspace.full_weights(weights, kept);
  label_neurons(scaled, y, class_count);
}

// Spec §5.11: majority class of the inputs each neuron wins (ties: smallest mean quantisation
// error, then lowest class); neurons that win nothing take the nearest labelled neuron's class.
void SomClassifier::label_neurons(const Matrix& scaled, const std::vector<int>& y,
                                  int class_count) {
  const int neurons = map_.rows * map_.columns;
  Eigen::MatrixXi counts = Eigen::MatrixXi::Zero(neurons, class_count);
  Matrix error_sums = Matrix::Zero(neurons, class_count);
  for (Eigen::Index row = 0; row < scaled.rows(); ++row) {
    const Vector distances = distances_to_neurons(map_, scaled.row(row).transpose());
    Eigen::Index winner = 0;
    distances.minCoeff(&winner);
    const int label = y[static_cast<size_t>(row)];
    counts(winner, label) += 1;
    error_sums(winner, label) += distances(winner);
  }
  map_.hits.assign(static_cast<size_t>(neurons), 0);
  map_.neuron_class.assign(static_cast<size_t>(neurons), kUnknownClass);
  for (int neuron = 0; neuron < neurons; ++neuron) {
    map_.hits[static_cast<size_t>(neuron)] = counts.row(neuron).sum();
    int best = kUnknownClass;
    for (int label = 0; label < class_count; ++label) {
      const int count = counts(neuron, label);
      if (count == 0) continue;
      if (best == kUnknownClass || count > counts(neuron, best) ||
          (count == counts(neuron, best) &&
           error_sums(neuron, label) / count < error_sums(neuron, best) / counts(neuron, best)))
        best = label;
    }
    map_.neuron_class[static_cast<size_t>(neuron)] = best;
  }
  if (empty_unknown_) return;

  const std::vector<int> won = map_.neuron_class;
  for (int neuron = 0; neuron < neurons; ++neuron) {
    if (won[static_cast<size_t>(neuron)] != kUnknownClass) continue;
    int nearest = -1;
    int nearest_grid = 0;
    double nearest_weight = 0.0;
    for (int other = 0; other < neurons; ++other) {
      if (won[static_cast<size_t>(other)] == kUnknownClass) continue;
      const int grid = grid_squared_distance(map_, neuron, other);
      const double weight = (map_.weights.row(neuron) - map_.weights.row(other)).norm();
      if (nearest < 0 || grid < nearest_grid || (grid == nearest_grid && weight < nearest_weight)) {
        nearest = other;
        nearest_grid = grid;
        nearest_weight = weight;
      }
    }
    if (nearest >= 0)
      map_.neuron_class[static_cast<size_t>(neuron)] = won[static_cast<size_t>(nearest)];
  }
}

Matrix SomClassifier::scores(const Matrix& x) const {
  check_fitted(!map_.hits.empty(), kSomWhere);
  check_query(x, minimum_.size(), kSomWhere);
  const Matrix scaled = scale(x);
  Matrix values = Matrix::Constant(x.rows(), class_count_, std::numeric_limits<double>::lowest());
  for (Eigen::Index row = 0; row < scaled.rows(); ++row) {
    const Vector distances = distances_to_neurons(map_, scaled.row(row).transpose());
    for (Eigen::Index neuron = 0; neuron < distances.size(); ++neuron) {
      const int label = map_.neuron_class[static_cast<size_t>(neuron)];
      if (label != kUnknownClass)
        values(row, label) = std::max(values(row, label), -distances(neuron));
    }
  }
  return values;
}

// Spec §5.12: the winner's label.
std::vector<int> SomClassifier::predict(const Matrix& x) const {
  check_fitted(!map_.hits.empty(), kSomWhere);
  check_query(x, minimum_.size(), kSomWhere);
  const Matrix scaled = scale(x);
  std::vector<int> classes(static_cast<size_t>(x.rows()));
  for (Eigen::Index row = 0; row < scaled.rows(); ++row)
    classes[static_cast<size_t>(row)] =
        map_.neuron_class[static_cast<size_t>(som_winner(map_, scaled.row(row).transpose()))];
  return classes;
}

// Quantisation error: the mean distance of an input to its winner. Topographic error
// (Kiviluoto 1996): the share of inputs whose two nearest neurons are not neighbours on the
// grid (one step apart, diagonals included).
SomQuality som_quality(const SomMap& map, const Matrix& inputs) {
  SomQuality quality;
  if (inputs.rows() == 0 || map.weights.rows() < 2) return quality;
  for (Eigen::Index row = 0; row < inputs.rows(); ++row) {
    const Vector distances = distances_to_neurons(map, inputs.row(row).transpose());
    Eigen::Index first = 0;
    distances.minCoeff(&first);
    Eigen::Index second = first == 0 ? 1 : 0;
    for (Eigen::Index neuron = 0; neuron < distances.size(); ++neuron)
      if (neuron != first && distances(neuron) < distances(second)) second = neuron;
    quality.quantisation_error += distances(first);
    if (grid_squared_distance(map, static_cast<int>(first), static_cast<int>(second)) > 2)
      quality.topographic_error += 1.0;
  }
  quality.quantisation_error /= static_cast<double>(inputs.rows());
  quality.topographic_error /= static_cast<double>(inputs.rows());
  return quality;
}

std::vector<double> som_u_matrix(const SomMap& map) {
  std::vector<double> spread(static_cast<size_t>(map.rows * map.columns), 0.0);
  for (int y = 0; y < map.rows; ++y)
    for (int x = 0; x < map.columns; ++x) {
      const int k = y * map.columns + x;
      double sum = 0.0;
      int count = 0;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= map.columns || ny >= map.rows) continue;
        sum += (map.weights.row(k) - map.weights.row(ny * map.columns + nx)).norm();
        ++count;
      }
      spread[static_cast<size_t>(k)] = count ? sum / count : 0.0;
    }
  return spread;
}

SomQuality SomClassifier::quality(const Matrix& x) const {
  check_fitted(!map_.hits.empty(), kSomWhere);
  check_query(x, minimum_.size(), kSomWhere);
  return som_quality(map_, scale(x));
}

std::unique_ptr<Classifier> make_som_classifier(const Parameters& parameters) {
  return std::make_unique<SomClassifier>(parameters);
}

//---- Saved model

nlohmann::json SomClassifier::save() const {
  std::vector<double> means, maxima;
  for (const auto& error : training_errors_) {
    means.push_back(error.mean);
    maxima.push_back(error.max);
  }
  return {{"parameters", model_json::from_parameters(parameters())},
          {"class_count", class_count_},
          {"minimum", model_json::from_vector(minimum_)},
          {"range", model_json::from_vector(range_)},
          {"weights", model_json::from_matrix(map_.weights)},
          {"neuron_class", map_.neuron_class},
          {"hits", map_.hits},
          {"error_mean", means},
          {"error_max", maxima}};
}

void SomClassifier::load(const nlohmann::json& model) {
  const std::string where = "som model";
  try {
    SomClassifier restored(model_json::to_parameters(model.at("parameters"), where));
    restored.class_count_ = model.at("class_count").get<int>();
    restored.minimum_ = model_json::to_vector(model.at("minimum"));
    restored.range_ = model_json::to_vector(model.at("range"));
    restored.map_.weights = model_json::to_matrix(model.at("weights"), where);
    restored.map_.neuron_class = model.at("neuron_class").get<std::vector<int>>();
    restored.map_.hits = model.at("hits").get<std::vector<int>>();
    const auto means = model.at("error_mean").get<std::vector<double>>();
    const auto maxima = model.at("error_max").get<std::vector<double>>();
    const auto neurons = static_cast<size_t>(restored.map_.rows * restored.map_.columns);
    if (restored.map_.weights.rows() != static_cast<Eigen::Index>(neurons) ||
        restored.map_.weights.cols() != restored.minimum_.size() ||
        restored.range_.size() != restored.minimum_.size() ||
        restored.map_.neuron_class.size() != neurons || restored.map_.hits.size() != neurons ||
        means.size() != maxima.size())
      throw Error(where, "sizes of weights, labels, hits and scaling do not agree");
    for (const int label : restored.map_.neuron_class)
      if (label != kUnknownClass && (label < 0 || label >= restored.class_count_))
        throw Error(where, "neuron class " + std::to_string(label) + " is outside 0.." +
                               std::to_string(restored.class_count_ - 1));
    for (size_t epoch = 0; epoch < means.size(); ++epoch)
      restored.training_errors_.push_back({means[epoch], maxima[epoch]});
    *this = std::move(restored);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

}  // namespace tactile::ml

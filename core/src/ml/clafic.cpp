#include "tactile/ml/clafic.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "model_json.h"
#include "tactile/error.h"
#include "tactile/ml/checks.h"

namespace tactile::ml {

namespace {

const char* const kClaficWhere = "clafic";

// Flips each column so its largest-|.| entry (first on ties) is positive: the sign
// convention of the spec's test vectors.
void make_largest_entry_positive(Matrix& basis) {
  for (Eigen::Index column = 0; column < basis.cols(); ++column) {
    Eigen::Index largest = 0;
    basis.col(column).cwiseAbs().maxCoeff(&largest);
    if (basis(largest, column) < 0.0) basis.col(column) *= -1.0;
  }
}

// Spec §4.7: keep |u[p]| >= c2 * rho, renormalise, drop directions left empty.
Matrix sensor_bank_basis(const Matrix& basis, const ClaficOptions& options) {
  if (options.c2 == 0.0) return basis;
  const double size = static_cast<double>(basis.rows());
  Matrix kept(basis.rows(), basis.cols());
  Eigen::Index count = 0;
  for (Eigen::Index column = 0; column < basis.cols(); ++column) {
    const auto u = basis.col(column);
    double typical = 1.0 / std::sqrt(size);  // RMS of the entries of a unit vector
    if (options.element_scale == ClaficOptions::ElementScale::kStd)
      typical = std::sqrt((u.array() - u.mean()).square().mean());
    const double threshold = options.c2 * typical;
    const Vector thinned = (u.array().abs() >= threshold).select(u, 0.0);
    const double norm = thinned.norm();
    if (norm == 0.0) continue;
    kept.col(count++) = thinned / norm;
  }
  return kept.leftCols(count);
}

std::vector<int64_t> nonzero_rows(const Matrix& basis) {
  std::vector<int64_t> rows;
  for (Eigen::Index row = 0; row < basis.rows(); ++row)
    if ((basis.row(row).array() != 0.0).any()) rows.push_back(row);
  return rows;
}

std::vector<int> parse_dimensions(const std::string& text, const std::string& where) {
  std::vector<int> dimensions;
  if (text.empty()) return dimensions;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find('|', start), text.size());
    const std::string item = text.substr(start, end - start);
    int value = 0;
    const auto [rest, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (error != std::errc() || rest != item.data() + item.size() || value < 1)
      throw Error(where, "dimensions=" + text + ": '" + item +
                             "' is not a whole number of at least 1 (use 4 or 4|5|3)");
    dimensions.push_back(value);
    start = end + 1;
  }
  return dimensions;
}

std::string join_dimensions(const std::vector<int>& dimensions) {
  std::string text;
  for (const int dimension : dimensions) {
    if (!text.empty()) text += '|';
    text += std::to_string(dimension);
  }
  return text;
}

}  // namespace

//---- One class subspace (spec §4.4, §4.7)

ClaficSubspace fit_clafic_subspace(const Matrix& samples, const ClaficOptions& options) {
  ClaficSubspace subspace;
  const Eigen::Index count = samples.rows();
  const Eigen::Index size = samples.cols();
  subspace.basis = Matrix(size, 0);
  subspace.bank_basis = Matrix(size, 0);
  if (count == 0) return subspace;

  // Thin SVD of X_k = samples^T through the small p x p Gram matrix X_k^T X_k = V diag(d^2) V^T
  // (spec §4.4; D >> p for the Robovie features).
  Matrix gram = Matrix::Zero(count, count);
  gram.selfadjointView<Eigen::Lower>().rankUpdate(samples);
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(gram.selfadjointView<Eigen::Lower>());
  const Vector energies = solver.eigenvalues().reverse();  // d_j^2, descending
  const Matrix directions = solver.eigenvectors().rowwise().reverse();
  const double largest = energies.size() ? energies(0) : 0.0;
  if (!(largest > 0.0)) return subspace;  // all-zero training vectors span nothing

  // Numerical rank, judged on the Gram eigenvalues: forming X^T X squares the condition number,
  // so energies below this bound are rounding noise, not directions of the data.
  const double epsilon = std::numeric_limits<double>::epsilon();
  const double bound = static_cast<double>(std::max(size, count)) * epsilon * largest;
  Eigen::Index rank = 0;
  while (rank < energies.size() && energies(rank) > bound) ++rank;

  subspace.singular_values = energies.head(rank).cwiseSqrt();
  // Cumulative contribution ratio r_k(m) (spec §4.4): energy sum d_j^2 / sum d^2 by default.
  const Vector weights = options.contribution == ClaficOptions::Contribution::kEnergy
                             ? Vector(energies.head(rank))
                             : subspace.singular_values;
  subspace.cumulative_ratio.resize(rank);
  double running = 0.0;
  for (Eigen::Index index = 0; index < rank; ++index)
    subspace.cumulative_ratio(index) = (running += weights(index));
  subspace.cumulative_ratio /= running;

  Eigen::Index dimension = rank;
  if (options.dimension_override > 0) {
    dimension = std::min<Eigen::Index>(options.dimension_override, rank);
  } else {
    for (Eigen::Index index = 0; index < rank; ++index) {
      if (subspace.cumulative_ratio(index) >= options.c1 - 1e-12) {
        dimension = index + 1;
        break;
      }
    }
  }
  subspace.dimension = static_cast<int>(dimension);

  // u_j = X_k v_j / d_j, then re-orthonormalised in order (Householder QR) because the
  // Gram route leaves errors of order eps * (d_1/d_j)^2 in the small directions.
  const Matrix raw = samples.transpose() * directions.leftCols(dimension) *
                     subspace.singular_values.head(dimension).cwiseInverse().asDiagonal();
  const Eigen::HouseholderQR<Matrix> qr(raw);
  Matrix basis = qr.householderQ() * Matrix::Identity(size, dimension);
  for (Eigen::Index column = 0; column < dimension; ++column)
    if (qr.matrixQR()(column, column) < 0.0) basis.col(column) *= -1.0;
  make_largest_entry_positive(basis);
  subspace.basis = std::move(basis);

  subspace.bank_basis = sensor_bank_basis(subspace.basis, options);
  subspace.needed_features = nonzero_rows(subspace.bank_basis);
  return subspace;
}

// Spec eq 6: DF_k(x) = sum_j (x^T u_kj)^2.
Vector clafic_discrimination(const Matrix& x, const Matrix& basis) {
  if (basis.cols() == 0) return Vector::Zero(x.rows());
  return (x * basis).rowwise().squaredNorm();
}

// Spec eqs 7-8: l = argmax DF (first on ties); accept iff DF_l / DF_second > 1/tau.
int clafic_decide(const Vector& discrimination, double tau) {
  if (discrimination.size() == 0) return kUnknownClass;
  Eigen::Index best = 0;
  const double best_value = discrimination.maxCoeff(&best);
  double second = 0.0;
  for (Eigen::Index index = 0; index < discrimination.size(); ++index)
    if (index != best) second = std::max(second, discrimination(index));
  if (second == 0.0) return best_value > 0.0 ? static_cast<int>(best) : kUnknownClass;
  return best_value / second > 1.0 / tau ? static_cast<int>(best) : kUnknownClass;
}

//---- The classifier

ClaficClassifier::ClaficClassifier(const Parameters& parameters) {
  parameters.expect_only({"c1", "c2", "tau", "c1_mode", "c2_scale", "dimensions"});
  const std::string where = parameters.where();
  options_.c1 = parameters.number("c1", 0.15);
  if (!(options_.c1 > 0.0 && options_.c1 <= 1.0))
    throw Error(where, "c1=" + model_json::format_number(options_.c1) + ": must lie in (0, 1]");
  options_.c2 = parameters.number("c2", 0.0);
  if (!(options_.c2 >= 0.0))
    throw Error(where, "c2=" + model_json::format_number(options_.c2) + ": must be >= 0");
  tau_ = parameters.number("tau", 0.95);
  if (!(tau_ > 0.0)) throw Error(where, "tau=" + model_json::format_number(tau_) + ": must be > 0");
  const std::string mode = parameters.text("c1_mode", "energy");
  if (mode == "energy")
    options_.contribution = ClaficOptions::Contribution::kEnergy;
  else if (mode == "singular")
    options_.contribution = ClaficOptions::Contribution::kSingular;
  else
    throw Error(where, "c1_mode=" + mode + ": expected energy or singular");
  const std::string scale = parameters.text("c2_scale", "rms");
  if (scale == "rms")
    options_.element_scale = ClaficOptions::ElementScale::kRms;
  else if (scale == "std")
    options_.element_scale = ClaficOptions::ElementScale::kStd;
  else
    throw Error(where, "c2_scale=" + scale + ": expected rms or std");
  dimension_overrides_ = parse_dimensions(parameters.text("dimensions", ""), where);
}

Parameters ClaficClassifier::parameters() const {
  Parameters parameters;
  parameters.set_where(kClaficWhere);
  parameters.set("c1", model_json::format_number(options_.c1));
  parameters.set("c2", model_json::format_number(options_.c2));
  parameters.set("tau", model_json::format_number(tau_));
  parameters.set("c1_mode", options_.contribution == ClaficOptions::Contribution::kEnergy
                                ? "energy"
                                : "singular");
  parameters.set("c2_scale",
                 options_.element_scale == ClaficOptions::ElementScale::kRms ? "rms" : "std");
  if (!dimension_overrides_.empty())
    parameters.set("dimensions", join_dimensions(dimension_overrides_));
  return parameters;
}

// CLAFIC is deterministic: the seed is not used.
void ClaficClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                           uint64_t /*seed*/) {
  check_training_set(x, y, class_count, kClaficWhere);
  if (dimension_overrides_.size() > 1 &&
      dimension_overrides_.size() != static_cast<size_t>(class_count))
    throw Error(kClaficWhere, "dimensions lists " + std::to_string(dimension_overrides_.size()) +
                                  " values for " + std::to_string(class_count) + " classes");
  std::vector<std::vector<Eigen::Index>> rows(static_cast<size_t>(class_count));
  for (size_t row = 0; row < y.size(); ++row)
    rows[static_cast<size_t>(y[row])].push_back(static_cast<Eigen::Index>(row));

  std::vector<ClaficSubspace> subspaces;
  subspaces.reserve(rows.size());
  for (size_t k = 0; k < rows.size(); ++k)
    subspaces.push_back(fit_clafic_subspace(x(rows[k], Eigen::all), class_options(k)));
  subspaces_ = std::move(subspaces);
  feature_count_ = x.cols();
}

ClaficOptions ClaficClassifier::class_options(size_t class_index) const {
  ClaficOptions options = options_;
  if (!dimension_overrides_.empty())
    options.dimension_override =
        dimension_overrides_[dimension_overrides_.size() == 1 ? 0 : class_index];
  return options;
}

std::vector<int> ClaficClassifier::leave_one_out(const Matrix& x, const std::vector<int>& y,
                                                 int class_count) {
  fit(x, y, class_count, 0);
  // DF of every row on every class fitted with all rows: right for each class but the row's own.
  const Matrix all_rows = discrimination(x);
  std::vector<std::vector<Eigen::Index>> rows(static_cast<size_t>(class_count));
  for (size_t row = 0; row < y.size(); ++row)
    rows[static_cast<size_t>(y[row])].push_back(static_cast<Eigen::Index>(row));
  std::vector<int> answers(y.size(), kUnknownClass);
  for (size_t k = 0; k < rows.size(); ++k) {
    const std::vector<Eigen::Index>& members = rows[k];
    for (size_t held = 0; held < members.size(); ++held) {
      std::vector<Eigen::Index> others;
      for (size_t member = 0; member < members.size(); ++member)
        if (member != held) others.push_back(members[member]);
      const ClaficSubspace without = fit_clafic_subspace(x(others, Eigen::all), class_options(k));
      const Eigen::Index row = members[held];
      Vector values = all_rows.row(row).transpose();
      values(static_cast<Eigen::Index>(k)) =
          clafic_discrimination(x.row(row), without.bank_basis)(0);
      answers[static_cast<size_t>(row)] = clafic_decide(values, tau_);
    }
  }
  return answers;
}

Matrix ClaficClassifier::discrimination(const Matrix& x) const {
  check_fitted(!subspaces_.empty(), kClaficWhere);
  check_query(x, feature_count_, kClaficWhere);
  Matrix values(x.rows(), static_cast<Eigen::Index>(subspaces_.size()));
  for (size_t k = 0; k < subspaces_.size(); ++k)
    values.col(static_cast<Eigen::Index>(k)) = clafic_discrimination(x, subspaces_[k].bank_basis);
  return values;
}

Matrix ClaficClassifier::scores(const Matrix& x) const { return discrimination(x); }

std::vector<int> ClaficClassifier::predict(const Matrix& x) const {
  const Matrix values = discrimination(x);
  std::vector<int> classes(static_cast<size_t>(values.rows()));
  for (Eigen::Index row = 0; row < values.rows(); ++row)
    classes[static_cast<size_t>(row)] = clafic_decide(values.row(row).transpose(), tau_);
  return classes;
}

const ClaficSubspace& ClaficClassifier::subspace(int class_index) const {
  if (class_index < 0 || static_cast<size_t>(class_index) >= subspaces_.size())
    throw Error(kClaficWhere, "no subspace for class " + std::to_string(class_index));
  return subspaces_[static_cast<size_t>(class_index)];
}

std::vector<int> ClaficClassifier::subspace_dimensions() const {
  std::vector<int> dimensions;
  for (const auto& subspace : subspaces_) dimensions.push_back(subspace.dimension);
  return dimensions;
}

std::vector<int64_t> ClaficClassifier::sensor_bank_sizes() const {
  std::vector<int64_t> sizes;
  for (const auto& subspace : subspaces_)
    sizes.push_back(static_cast<int64_t>(subspace.needed_features.size()));
  return sizes;
}

std::vector<double> ClaficClassifier::feature_fractions() const {
  std::vector<double> fractions;
  for (const auto& subspace : subspaces_)
    fractions.push_back(feature_count_ ? static_cast<double>(subspace.needed_features.size()) /
                                             static_cast<double>(feature_count_)
                                       : 0.0);
  return fractions;
}

std::unique_ptr<Classifier> make_clafic_classifier(const Parameters& parameters) {
  return std::make_unique<ClaficClassifier>(parameters);
}

//---- Saved model

nlohmann::json ClaficClassifier::save() const {
  nlohmann::json classes = nlohmann::json::array();
  for (const auto& subspace : subspaces_) {
    classes.push_back({{"singular_values", model_json::from_vector(subspace.singular_values)},
                       {"cumulative_ratio", model_json::from_vector(subspace.cumulative_ratio)},
                       {"dimension", subspace.dimension},
                       {"basis", model_json::from_matrix(subspace.basis)},
                       {"bank_basis", model_json::from_matrix(subspace.bank_basis)},
                       {"needed_features", subspace.needed_features}});
  }
  return {{"parameters", model_json::from_parameters(parameters())},
          {"feature_count", feature_count_},
          {"classes", classes}};
}

void ClaficClassifier::load(const nlohmann::json& model) {
  const std::string where = "clafic model";
  try {
    ClaficClassifier restored(model_json::to_parameters(model.at("parameters"), where));
    restored.feature_count_ = model.at("feature_count").get<int64_t>();
    for (const auto& node : model.at("classes")) {
      ClaficSubspace subspace;
      subspace.singular_values = model_json::to_vector(node.at("singular_values"));
      subspace.cumulative_ratio = model_json::to_vector(node.at("cumulative_ratio"));
      subspace.dimension = node.at("dimension").get<int>();
      subspace.basis = model_json::to_matrix(node.at("basis"), where);
      subspace.bank_basis = model_json::to_matrix(node.at("bank_basis"), where);
      subspace.needed_features = node.at("needed_features").get<std::vector<int64_t>>();
      if (subspace.basis.rows() != restored.feature_count_ ||
          subspace.bank_basis.rows() != restored.feature_count_)
        throw Error(where, "a class basis does not have " +
                               std::to_string(restored.feature_count_) + " rows");
      restored.subspaces_.push_back(std::move(subspace));
    }
    *this = std::move(restored);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

//---- Sensor banks and rates

std::vector<int> pair_sensors(const std::vector<int64_t>& features, int sensor_count) {
  const int64_t sensors = sensor_count;
  const int64_t pairs = sensors * (sensors - 1) / 2;
  // Row i of the upper triangle starts at q = i N - i (i + 1) / 2 (spec §4.3, 0-based i).
  std::vector<int64_t> starts(static_cast<size_t>(std::max<int64_t>(sensors, 0)));
  for (int64_t i = 0; i < sensors; ++i)
    starts[static_cast<size_t>(i)] = i * sensors - i * (i + 1) / 2;
  std::vector<bool> used(starts.size(), false);
  for (const int64_t feature : features) {
    if (feature < 0 || feature >= pairs)
      throw Error("sensor bank", "feature " + std::to_string(feature) + " is not a pair of " +
                                     std::to_string(sensor_count) + " sensors (" +
                                     std::to_string(pairs) + " pairs)");
    const auto row = std::upper_bound(starts.begin(), starts.end(), feature) - starts.begin() - 1;
    const int64_t partner = feature - starts[static_cast<size_t>(row)] + row + 1;
    used[static_cast<size_t>(row)] = true;
    used[static_cast<size_t>(partner)] = true;
  }
  std::vector<int> bank;
  for (size_t sensor = 0; sensor < used.size(); ++sensor)
    if (used[sensor]) bank.push_back(static_cast<int>(sensor));
  return bank;
}

RecognitionRates recognition_rates(const Eigen::MatrixXi& confusion) {
  const Eigen::Index classes = confusion.rows();
  if (confusion.cols() != classes && confusion.cols() != classes + 1)
    throw Error("recognition rates", "confusion matrix of " + std::to_string(classes) + " x " +
                                         std::to_string(confusion.cols()) +
                                         " is neither square nor square plus an unknown column");
  RecognitionRates rates;
  for (Eigen::Index k = 0; k < classes; ++k) {
    const double samples = confusion.row(k).sum();  // unknown answers included
    const double correct = confusion(k, k);
    const double false_alarms = confusion.col(k).sum() - correct;
    rates.recognition.push_back(samples > 0 ? correct / samples : 0.0);
    rates.false_alarm.push_back(samples > 0 ? false_alarms / samples : 0.0);
  }
  return rates;
}

}  // namespace tactile::ml

#include "tactile/ml/naive_bayes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>

#include "probabilistic_support.h"
#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile::ml {

namespace {

const double kLogTwoPi = std::log(2.0 * std::numbers::pi);

std::string read_priors_mode(const Parameters& parameters) {
  const std::string mode = parameters.text("priors", "empirical");
  if (mode != "empirical" && mode != "uniform")
    throw Error(parameters.where(), "priors=" + mode + ": expected empirical or uniform");
  return mode;
}

// Width by Silverman's rule, falling back to the sample std when the MAD vanishes; 0 for a
// constant sample.
double width_or_zero(const Vector& values) {
  const double robust = silverman_width(values);
  if (robust > 0.0) return robust;
  const double count = static_cast<double>(values.size());
  if (values.size() < 2) return 0.0;
  const double deviation =
      std::sqrt((values.array() - values.mean()).square().sum() / (count - 1.0));
  if (deviation <= 1e-12 * std::max(1.0, std::abs(values.mean()))) return 0.0;
  return deviation * std::pow(4.0 / (3.0 * count), 0.2);
}

Matrix log_posterior_to_scores(Matrix log_joint, const Vector& priors) {
  for (Eigen::Index k = 0; k < priors.size(); ++k) {
    if (priors(k) > 0.0)
      log_joint.col(k).array() += std::log(priors(k));
    else
      log_joint.col(k).setConstant(kNegativeInfinity);
  }
  return support::normalise_log_rows(log_joint);
}

}  // namespace

double silverman_width(const Vector& values) {
  if (values.size() == 0) return 0.0;
  std::vector<double> samples(values.data(), values.data() + values.size());
  const double centre = stats::median(samples);
  for (double& value : samples) value = std::abs(value - centre);
  const double robust_deviation = stats::median(samples) / 0.6745;
  // Silverman's rule of thumb for a normal kernel: h = σ (4 / (3 n))^(1/5).
  return robust_deviation * std::pow(4.0 / (3.0 * static_cast<double>(values.size())), 0.2);
}

//---- gaussian-nb --------------------------------------------------------------------------

GaussianNaiveBayes::GaussianNaiveBayes(const Parameters& parameters) {
  parameters.expect_only({"var_smoothing", "priors"});
  variance_smoothing_ = support::positive_number(parameters, "var_smoothing", 1e-9);
  priors_mode_ = read_priors_mode(parameters);
}

Parameters GaussianNaiveBayes::parameters() const {
  Parameters parameters;
  parameters.set("var_smoothing", support::format_number(variance_smoothing_));
  parameters.set("priors", priors_mode_);
  return parameters;
}

void GaussianNaiveBayes::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                             uint64_t /*seed: the fit is deterministic*/) {
  check_training_set(x, y, class_count, name());
  const auto members = support::rows_by_class(y, class_count);
  priors_ = support::class_priors(members, priors_mode_, name());
  const Eigen::Index dimension = x.cols();
  // The means evaluated once: inside the expression Eigen would redo a column's mean for
  // every row of it (rows^2 x columns: minutes on 183 x 37,401).
  const Eigen::RowVectorXd column_means = x.colwise().mean();
  const Vector global_variance =
      (x.rowwise() - column_means).array().square().colwise().sum().transpose() /
      static_cast<double>(x.rows());
  const double largest_variance = global_variance.maxCoeff();
  // With every feature constant all classes look alike whatever ε is; 1 keeps it positive.
  const double smoothing = largest_variance > 0.0 ? variance_smoothing_ * largest_variance : 1.0;

  means_ = Matrix::Zero(class_count, dimension);
  variances_ = Matrix::Ones(class_count, dimension);
  Vector pooled_scatter = Vector::Zero(dimension);
  double pooled_degrees = 0.0;
  for (int k = 0; k < class_count; ++k) {
    const auto& rows = members[static_cast<size_t>(k)];
    if (rows.empty()) continue;
    const Matrix samples = support::select_rows(x, rows);
    means_.row(k) = samples.colwise().mean();
    if (rows.size() < 2) continue;
    const Vector scatter = (samples.rowwise() - means_.row(k)).array().square().colwise().sum();
    variances_.row(k) = scatter.transpose() / (static_cast<double>(rows.size()) - 1.0);
    pooled_scatter += scatter;
    pooled_degrees += static_cast<double>(rows.size()) - 1.0;
  }
  const Vector single_sample_variance =
      pooled_degrees > 0.0 ? Vector(pooled_scatter / pooled_degrees) : global_variance;
  for (int k = 0; k < class_count; ++k) {
    if (members[static_cast<size_t>(k)].size() == 1)
      variances_.row(k) = single_sample_variance.transpose();
    variances_.row(k).array() += smoothing;
  }
}

Matrix GaussianNaiveBayes::scores(const Matrix& x) const {
  if (priors_.size() == 0) throw Error(name(), "not fitted");
  check_query(x, means_.cols(), name());
  Matrix log_likelihood(x.rows(), priors_.size());
  for (Eigen::Index k = 0; k < priors_.size(); ++k) {
    // Σ_j ln N(x_j; μ_kj, σ²_kj) = -½ Σ_j [ln 2π σ²_kj + (x_j - μ_kj)² / σ²_kj].
    const double constant = (kLogTwoPi + variances_.row(k).array().log()).sum();
    const Vector squared =
        ((x.rowwise() - means_.row(k)).array().square().rowwise() / variances_.row(k).array())
            .rowwise()
            .sum();
    log_likelihood.col(k) = -0.5 * (squared.array() + constant);
  }
  return log_posterior_to_scores(log_likelihood, priors_);
}

nlohmann::json GaussianNaiveBayes::save() const {
  return {{"var_smoothing", variance_smoothing_},
          {"priors_mode", priors_mode_},
          {"priors", support::vector_to_json(priors_)},
          {"means", support::matrix_to_json(means_)},
          {"variances", support::matrix_to_json(variances_)}};
}

void GaussianNaiveBayes::load(const nlohmann::json& model) {
  const std::string where = name() + " model";
  try {
    variance_smoothing_ = model.at("var_smoothing").get<double>();
    priors_mode_ = model.at("priors_mode").get<std::string>();
    priors_ = support::vector_from_json(model.at("priors"), where + " priors");
    means_ = support::matrix_from_json(model.at("means"), where + " means");
    variances_ = support::matrix_from_json(model.at("variances"), where + " variances");
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  if (means_.rows() != priors_.size() || variances_.rows() != priors_.size() ||
      variances_.cols() != means_.cols())
    throw Error(where, "priors, means and variances differ in shape");
  if ((variances_.array() <= 0.0).any()) throw Error(where, "a variance is not positive");
}

//---- kernel-nb ----------------------------------------------------------------------------

KernelNaiveBayes::KernelNaiveBayes(const Parameters& parameters) {
  parameters.expect_only({"width", "priors"});
  fixed_width_ = support::positive_number(parameters, "width", 0.0, /*allow_zero=*/true);
  priors_mode_ = read_priors_mode(parameters);
}

Parameters KernelNaiveBayes::parameters() const {
  Parameters parameters;
  parameters.set("width", support::format_number(fixed_width_));
  parameters.set("priors", priors_mode_);
  return parameters;
}

void KernelNaiveBayes::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                           uint64_t /*seed: the fit is deterministic*/) {
  check_training_set(x, y, class_count, name());
  const auto members = support::rows_by_class(y, class_count);
  priors_ = support::class_priors(members, priors_mode_, name());
  dimension_ = x.cols();
  Vector global_width(dimension_);
  for (Eigen::Index feature = 0; feature < dimension_; ++feature) {
    const double width = width_or_zero(x.col(feature));
    global_width(feature) = width > 0.0 ? width : 1.0;
  }
  samples_.assign(static_cast<size_t>(class_count), Matrix());
  widths_ = Matrix::Ones(class_count, dimension_);
  for (int k = 0; k < class_count; ++k) {
    const auto& rows = members[static_cast<size_t>(k)];
    if (rows.empty()) continue;
    samples_[static_cast<size_t>(k)] = support::select_rows(x, rows);
    for (Eigen::Index feature = 0; feature < dimension_; ++feature) {
      const double width = fixed_width_ > 0.0
                               ? fixed_width_
                               : width_or_zero(samples_[static_cast<size_t>(k)].col(feature));
      widths_(k, feature) = width > 0.0 ? width : global_width(feature);
    }
  }
}

Matrix KernelNaiveBayes::scores(const Matrix& x) const {
  if (priors_.size() == 0) throw Error(name(), "not fitted");
  check_query(x, dimension_, name());
  Matrix log_likelihood = Matrix::Zero(x.rows(), priors_.size());
  for (Eigen::Index k = 0; k < priors_.size(); ++k) {
    const Matrix& members = samples_[static_cast<size_t>(k)];
    if (members.rows() == 0) continue;  // prior 0: the column becomes -infinity below
    const Eigen::RowVectorXd inverse_width = widths_.row(k).cwiseInverse();
    // ln f(x_j) = ln Σ_i φ((x_j - x_ij) / h_j) - ln n - ln h_j, φ the standard normal.
    const double constant = -static_cast<double>(dimension_) *
                                (std::log(static_cast<double>(members.rows())) + 0.5 * kLogTwoPi) -
                            widths_.row(k).array().log().sum();
    for (Eigen::Index row = 0; row < x.rows(); ++row) {
      const Matrix exponent =
          -0.5 *
          ((members.rowwise() - x.row(row)).array().rowwise() * inverse_width.array()).square();
      // Log-sum-exp per feature keeps far-away queries finite instead of underflowing to -inf.
      const Eigen::RowVectorXd largest = exponent.colwise().maxCoeff();
      const double log_sum =
          (largest.array() + (exponent.rowwise() - largest).array().exp().colwise().sum().log())
              .sum();
      log_likelihood(row, k) = log_sum + constant;
    }
  }
  return log_posterior_to_scores(log_likelihood, priors_);
}

nlohmann::json KernelNaiveBayes::save() const {
  nlohmann::json samples = nlohmann::json::array();
  for (const Matrix& members : samples_) samples.push_back(support::matrix_to_json(members));
  return {{"width", fixed_width_},
          {"priors_mode", priors_mode_},
          {"dimension", dimension_},
          {"priors", support::vector_to_json(priors_)},
          {"widths", support::matrix_to_json(widths_)},
          {"samples", samples}};
}

void KernelNaiveBayes::load(const nlohmann::json& model) {
  const std::string where = name() + " model";
  try {
    fixed_width_ = model.at("width").get<double>();
    priors_mode_ = model.at("priors_mode").get<std::string>();
    dimension_ = model.at("dimension").get<Eigen::Index>();
    priors_ = support::vector_from_json(model.at("priors"), where + " priors");
    widths_ = support::matrix_from_json(model.at("widths"), where + " widths");
    samples_.clear();
    for (const nlohmann::json& members : model.at("samples"))
      samples_.push_back(support::matrix_from_json(members, where + " samples"));
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  if (widths_.rows() != priors_.size() || widths_.cols() != dimension_ ||
      static_cast<Eigen::Index>(samples_.size()) != priors_.size())
    throw Error(where, "priors, widths and samples differ in shape");
  for (Eigen::Index k = 0; k < priors_.size(); ++k) {
    const Matrix& members = samples_[static_cast<size_t>(k)];
    if ((members.rows() > 0) != (priors_(k) > 0.0) ||
        (members.rows() > 0 && members.cols() != dimension_))
      throw Error(where, "class " + std::to_string(k) + " samples do not match its prior");
  }
  if ((widths_.array() <= 0.0).any()) throw Error(where, "a width is not positive");
}

//---- registry factories -------------------------------------------------------------------

std::unique_ptr<Classifier> make_gaussian_nb_classifier(const Parameters& parameters) {
  return std::make_unique<GaussianNaiveBayes>(parameters);
}

std::unique_ptr<Classifier> make_kernel_nb_classifier(const Parameters& parameters) {
  return std::make_unique<KernelNaiveBayes>(parameters);
}

}  // namespace tactile::ml

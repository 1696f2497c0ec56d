#include "tactile/ml/gaussian.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>

#include "probabilistic_support.h"
#include "tactile/error.h"

namespace tactile::ml {

namespace {

// Σ + ridge I is positive definite in exact arithmetic; rounding can still defeat Cholesky
// when ridge is tiny against the largest variance, so the ridge grows tenfold at most this
// many times before we give up.
constexpr int kRidgeAttempts = 40;

bool factorise(GaussianDensity& density) {
  density.cholesky.compute(density.covariance);
  if (density.cholesky.info() != Eigen::Success) return false;
  const Vector diagonal = density.cholesky.matrixLLT().diagonal();
  if (!diagonal.allFinite() || (diagonal.array() <= 0.0).any()) return false;
  density.log_determinant = 2.0 * diagonal.array().log().sum();
  return std::isfinite(density.log_determinant);
}

// Mean over features of the population variance of all training rows: the scale of the
// ridge for a class with too few samples to estimate its own covariance (spec §3.6).
double mean_global_variance(const Matrix& x) {
  const Vector mean = x.colwise().mean().transpose();
  return ((x.rowwise() - mean.transpose()).array().square().colwise().sum() /
          static_cast<double>(x.rows()))
      .mean();
}

std::string model_where(const std::string& name) { return name + " model"; }

}  // namespace

//---- Gaussian density (spec §6.9) --------------------------------------------------------

void GaussianDensity::set(const Vector& mean_vector, const Matrix& covariance_without_ridge,
                          double ridge_value) {
  mean = mean_vector;
  ridge = ridge_value;
  const Eigen::Index dimension = covariance_without_ridge.rows();
  for (int attempt = 0; attempt < kRidgeAttempts; ++attempt) {
    covariance = covariance_without_ridge;
    covariance.diagonal().array() += ridge;
    if (factorise(*this)) return;
    ridge *= 10.0;
  }
  throw Error("gaussian density", "covariance of dimension " + std::to_string(dimension) +
                                      " stays singular under the ridge");
}

Vector GaussianDensity::log_density(const Matrix& x) const {
  // No rows (a fold with nothing to score): Eigen's triangular solve must not be handed an
  // empty right-hand side (it binds a reference to its null data; found by UBSan).
  if (x.rows() == 0) return Vector(0);
  const double dimension = static_cast<double>(mean.size());
  const Matrix centred = (x.rowwise() - mean.transpose()).transpose();
  const Matrix whitened = cholesky.matrixL().solve(centred);
  const Vector mahalanobis = whitened.colwise().squaredNorm().transpose();
  const double constant = dimension * std::log(2.0 * std::numbers::pi) + log_determinant;
  return -0.5 * (mahalanobis.array() + constant);
}

nlohmann::json GaussianDensity::save() const {
  return {{"mean", support::vector_to_json(mean)},
          {"covariance", support::matrix_to_json(covariance)},
          {"ridge", ridge}};
}

void GaussianDensity::load(const nlohmann::json& model, const std::string& where) {
  mean = support::vector_from_json(model.at("mean"), where + " mean");
  covariance = support::matrix_from_json(model.at("covariance"), where + " covariance");
  ridge = model.at("ridge").get<double>();
  if (covariance.rows() != mean.size() || covariance.cols() != mean.size())
    throw Error(where, "covariance does not match the mean's dimension");
  if (!factorise(*this)) throw Error(where, "covariance is not positive definite");
}

Matrix scatter_covariance(const Matrix& x, const Vector& mean, double divisor) {
  const Matrix centred = x.rowwise() - mean.transpose();
  return (centred.transpose() * centred) / divisor;
}

double relative_ridge(const Matrix& covariance, double factor) {
  const double dimension = static_cast<double>(covariance.rows());
  return factor * std::max(covariance.trace() / dimension, 1e-12);
}

// QDA's ridge: factor times each feature's own variance. A ridge of factor · tr(Σ)/d on every
// feature swamps features of small units (fur: 0.07 against 2100) and made the decisions
// depend on the units (area in mm² vs µm²); λ·diag(Σ) scales with each feature, so z-scoring
// or changing a unit changes nothing. A feature constant in the class takes its variance
// over all training rows instead (same unit), or 1 when it is constant everywhere.
Matrix with_feature_ridge(const Matrix& covariance, const Vector& all_rows_variance,
                          double factor) {
  Matrix ridged = covariance;
  for (Eigen::Index feature = 0; feature < covariance.rows(); ++feature) {
    const double own = covariance(feature, feature);
    const double all = all_rows_variance(feature);
    ridged(feature, feature) += factor * (own > 1e-12 * all ? own : all > 0.0 ? all : 1.0);
  }
  return ridged;
}

// The ridge is in the matrix. The scalar only grows (x10) if rounding defeats Cholesky, and
// starts far below the smallest variance so that it does not bring the units back.
void set_with_feature_ridge(GaussianDensity& density, const Vector& mean, const Matrix& covariance,
                            const Vector& all_rows_variance, double factor) {
  const Matrix ridged = with_feature_ridge(covariance, all_rows_variance, factor);
  density.set(mean, ridged, 1e-12 * ridged.diagonal().minCoeff());
}

//---- gaussian-ml (spec §3.6) --------------------------------------------------------------

GaussianMaximumLikelihood::GaussianMaximumLikelihood(const Parameters& parameters) {
  parameters.expect_only({"ridge"});
  ridge_factor_ = support::positive_number(parameters, "ridge", 1e-6);
}

Parameters GaussianMaximumLikelihood::parameters() const {
  Parameters parameters;
  parameters.set("ridge", support::format_number(ridge_factor_));
  return parameters;
}

void GaussianMaximumLikelihood::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                                    uint64_t /*seed: the fit is deterministic*/) {
  check_training_set(x, y, class_count, name());
  const auto members = support::rows_by_class(y, class_count);
  const double small_class_ridge = ridge_factor_ * std::max(mean_global_variance(x), 1e-12);
  dimension_ = x.cols();
  densities_.clear();
  densities_.resize(static_cast<size_t>(class_count));
  present_.assign(static_cast<size_t>(class_count), false);
  for (int k = 0; k < class_count; ++k) {
    const auto& rows = members[static_cast<size_t>(k)];
    if (rows.empty()) continue;
    const Matrix samples = support::select_rows(x, rows);
    const Vector mean = samples.colwise().mean().transpose();
    GaussianDensity& density = densities_[static_cast<size_t>(k)];
    if (rows.size() < 2) {
      density.set(mean, Matrix::Zero(x.cols(), x.cols()), small_class_ridge);
    } else {
      // Spec §3.6: Σ_k = (1/N_k) Σ (x - μ_k)(x - μ_k)ᵀ + λ_k I.
      const Matrix covariance = scatter_covariance(samples, mean, static_cast<double>(rows.size()));
      density.set(mean, covariance, relative_ridge(covariance, ridge_factor_));
    }
    present_[static_cast<size_t>(k)] = true;
  }
}

Matrix GaussianMaximumLikelihood::log_likelihoods(const Matrix& x) const {
  if (densities_.empty()) throw Error(name(), "not fitted");
  check_query(x, dimension_, name());
  Matrix result(x.rows(), static_cast<Eigen::Index>(densities_.size()));
  for (size_t k = 0; k < densities_.size(); ++k)
    result.col(static_cast<Eigen::Index>(k)) =
        present_[k] ? densities_[k].log_density(x) : Vector::Constant(x.rows(), kNegativeInfinity);
  return result;
}

Matrix GaussianMaximumLikelihood::scores(const Matrix& x) const {
  return support::normalise_log_rows(log_likelihoods(x));
}

Vector GaussianMaximumLikelihood::significance(const Matrix& x) const {
  return scores(x).rowwise().maxCoeff();
}

nlohmann::json GaussianMaximumLikelihood::save() const {
  nlohmann::json classes = nlohmann::json::array();
  for (size_t k = 0; k < densities_.size(); ++k)
    classes.push_back(present_[k] ? densities_[k].save() : nlohmann::json(nullptr));
  return {{"ridge_factor", ridge_factor_}, {"classes", classes}};
}

void GaussianMaximumLikelihood::load(const nlohmann::json& model) {
  const std::string where = model_where(name());
  try {
    ridge_factor_ = model.at("ridge_factor").get<double>();
    const nlohmann::json& classes = model.at("classes");
    densities_.clear();
    densities_.resize(classes.size());
    present_.assign(classes.size(), false);
    Eigen::Index dimension = -1;
    for (size_t k = 0; k < classes.size(); ++k) {
      if (classes[k].is_null()) continue;
      densities_[k].load(classes[k], where + " class " + std::to_string(k));
      if (dimension >= 0 && densities_[k].mean.size() != dimension)
        throw Error(where, "classes differ in dimension");
      dimension = densities_[k].mean.size();
      present_[k] = true;
    }
    if (dimension < 0) throw Error(where, "no class has a model");
    dimension_ = dimension;
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

//---- qda ----------------------------------------------------------------------------------

QuadraticDiscriminant::QuadraticDiscriminant(const Parameters& parameters) {
  parameters.expect_only({"ridge", "priors"});
  ridge_factor_ = support::positive_number(parameters, "ridge", 1e-6);
  priors_mode_ = parameters.text("priors", "empirical");
  if (priors_mode_ != "empirical" && priors_mode_ != "uniform")
    throw Error(parameters.where(), "priors=" + priors_mode_ + ": expected empirical or uniform");
}

Parameters QuadraticDiscriminant::parameters() const {
  Parameters parameters;
  parameters.set("ridge", support::format_number(ridge_factor_));
  parameters.set("priors", priors_mode_);
  return parameters;
}

void QuadraticDiscriminant::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                                uint64_t /*seed: the fit is deterministic*/) {
  check_training_set(x, y, class_count, name());
  const auto members = support::rows_by_class(y, class_count);
  priors_ = support::class_priors(members, priors_mode_, name());
  const Eigen::Index dimension = x.cols();
  dimension_ = dimension;

  // Pooled within-class covariance of the classes that can estimate their own: the fallback
  // for a class with a single sample.
  Matrix pooled_scatter = Matrix::Zero(dimension, dimension);
  double pooled_degrees = 0.0;
  std::vector<Vector> means(static_cast<size_t>(class_count));
  for (int k = 0; k < class_count; ++k) {
    const auto& rows = members[static_cast<size_t>(k)];
    if (rows.empty()) continue;
    const Matrix samples = support::select_rows(x, rows);
    means[static_cast<size_t>(k)] = samples.colwise().mean().transpose();
    if (rows.size() < 2) continue;
    pooled_scatter += scatter_covariance(samples, means[static_cast<size_t>(k)], 1.0);
    pooled_degrees += static_cast<double>(rows.size()) - 1.0;
  }

  const Vector all_rows_mean = x.colwise().mean().transpose();
  const Vector all_rows_variance =
      (x.rowwise() - all_rows_mean.transpose()).array().square().colwise().sum().transpose() /
      static_cast<double>(x.rows());
  densities_.clear();
  densities_.resize(static_cast<size_t>(class_count));
  for (int k = 0; k < class_count; ++k) {
    const auto& rows = members[static_cast<size_t>(k)];
    if (rows.empty()) continue;
    GaussianDensity& density = densities_[static_cast<size_t>(k)];
    const Vector& mean = means[static_cast<size_t>(k)];
    if (rows.size() >= 2) {
      const Matrix samples = support::select_rows(x, rows);
      const Matrix covariance =
          scatter_covariance(samples, mean, static_cast<double>(rows.size()) - 1.0);
      set_with_feature_ridge(density, mean, covariance, all_rows_variance, ridge_factor_);
    } else if (pooled_degrees > 0.0) {
      const Matrix pooled = pooled_scatter / pooled_degrees;
      set_with_feature_ridge(density, mean, pooled, all_rows_variance, ridge_factor_);
    } else {
      density.set(mean, Matrix::Zero(dimension, dimension),
                  ridge_factor_ * std::max(mean_global_variance(x), 1e-12));
    }
  }
}

Matrix QuadraticDiscriminant::scores(const Matrix& x) const {
  if (densities_.empty()) throw Error(name(), "not fitted");
  check_query(x, dimension_, name());
  Matrix log_posterior(x.rows(), static_cast<Eigen::Index>(densities_.size()));
  for (size_t k = 0; k < densities_.size(); ++k) {
    const double prior = priors_(static_cast<Eigen::Index>(k));
    log_posterior.col(static_cast<Eigen::Index>(k)) =
        prior > 0.0 ? Vector(densities_[k].log_density(x).array() + std::log(prior))
                    : Vector::Constant(x.rows(), kNegativeInfinity);
  }
  return support::normalise_log_rows(log_posterior);
}

nlohmann::json QuadraticDiscriminant::save() const {
  nlohmann::json classes = nlohmann::json::array();
  for (size_t k = 0; k < densities_.size(); ++k)
    classes.push_back(priors_(static_cast<Eigen::Index>(k)) > 0.0 ? densities_[k].save()
                                                                  : nlohmann::json(nullptr));
  return {{"ridge_factor", ridge_factor_},
          {"priors_mode", priors_mode_},
          {"priors", support::vector_to_json(priors_)},
          {"classes", classes}};
}

void QuadraticDiscriminant::load(const nlohmann::json& model) {
  const std::string where = model_where(name());
  try {
    ridge_factor_ = model.at("ridge_factor").get<double>();
    priors_mode_ = model.at("priors_mode").get<std::string>();
    priors_ = support::vector_from_json(model.at("priors"), where + " priors");
    const nlohmann::json& classes = model.at("classes");
    if (static_cast<Eigen::Index>(classes.size()) != priors_.size())
      throw Error(where, "priors and classes differ in count");
    densities_.clear();
    densities_.resize(classes.size());
    Eigen::Index dimension = -1;
    for (size_t k = 0; k < classes.size(); ++k) {
      if (classes[k].is_null()) {
        if (priors_(static_cast<Eigen::Index>(k)) > 0.0)
          throw Error(where, "class " + std::to_string(k) + " has a prior but no model");
        continue;
      }
      densities_[k].load(classes[k], where + " class " + std::to_string(k));
      if (dimension >= 0 && densities_[k].mean.size() != dimension)
        throw Error(where, "classes differ in dimension");
      dimension = densities_[k].mean.size();
    }
    if (dimension < 0) throw Error(where, "no class has a model");
    dimension_ = dimension;
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

//---- registry factories -------------------------------------------------------------------

std::unique_ptr<Classifier> make_gaussian_ml_classifier(const Parameters& parameters) {
  return std::make_unique<GaussianMaximumLikelihood>(parameters);
}

std::unique_ptr<Classifier> make_qda_classifier(const Parameters& parameters) {
  return std::make_unique<QuadraticDiscriminant>(parameters);
}

}  // namespace tactile::ml

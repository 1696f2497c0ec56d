#pragma once
// Full-covariance Gaussian class models: the smart-fur maximum-likelihood classifier with
// the significance of its decision (spec §3.6, TV F4) and MATLAB's quadratic discriminant.
// Both share one Gaussian density with a ridge (spec §6.9).
//
// Presets:
//   gaussian-ml  Müller et al. (smart fur, paper 002) §3.6: one Gaussian per class, ML
//                covariance (1/N_k) plus ridge λ_k = ridge · max(trace(Σ_k)/d, 1e-12); equal
//                priors. scores() = posterior with equal priors (the "significance");
//                log_likelihoods() = ℓ_k. A class with one sample gets Σ = λ I with
//                λ = ridge · mean of the global per-feature variances (spec §3.6 edge case).
//                Parameters: ridge (default 1e-6).
//   qda          MATLAB Classification Learner "Quadratic Discriminant" (TSA paper 001,
//                Table 4): unbiased class covariances (1/(N_k-1)), empirical priors. MATLAB
//                refuses a singular class covariance; we regularise instead, with the same
//                ridge rule as gaussian-ml, and a class with one sample borrows the pooled
//                within-class covariance. Parameters: ridge (1e-6), priors (empirical|uniform).
// A class absent from the training data scores 0 (log-likelihood -infinity) and is never
// predicted.

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// Spec §6.9: N(μ, Σ) with Σ made positive definite by a ridge, evaluated through Cholesky.
struct GaussianDensity {
  Vector mean;
  Matrix covariance;  // ridge included
  double ridge = 0.0;
  double log_determinant = 0.0;
  Eigen::LLT<Matrix> cholesky;

  // Takes covariance (without ridge) and the ridge; adds it, factorises, and if rounding
  // still leaves Σ not positive definite, multiplies the ridge by 10 until it is.
  void set(const Vector& mean_vector, const Matrix& covariance_without_ridge, double ridge_value);
  // ln N(x; μ, Σ) = -½ [d ln 2π + ln det Σ + (x-μ)ᵀ Σ⁻¹ (x-μ)] for each row of x.
  Vector log_density(const Matrix& x) const;
  nlohmann::json save() const;
  void load(const nlohmann::json& model, const std::string& where);
};

// Covariance of the rows of x around `mean`, divided by `divisor` (N for ML, N-1 unbiased).
Matrix scatter_covariance(const Matrix& x, const Vector& mean, double divisor);
// Spec §3.6 ridge: factor · max(trace(Σ)/d, 1e-12).
double relative_ridge(const Matrix& covariance, double factor);

class GaussianMaximumLikelihood : public Classifier {
 public:
  explicit GaussianMaximumLikelihood(const Parameters& parameters = {});
  std::string name() const override { return "gaussian-ml"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  // Posterior with equal priors: p_k = exp(ℓ_k - ℓ_max) / Σ_j exp(ℓ_j - ℓ_max).
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // ℓ_k(x) per row and class; -infinity for a class absent from training.
  Matrix log_likelihoods(const Matrix& x) const;
  // The posterior of the winning class per row (the paper's "significance of the decision").
  Vector significance(const Matrix& x) const;
  const std::vector<GaussianDensity>& classes() const { return densities_; }
  const std::vector<bool>& present() const { return present_; }

 private:
  double ridge_factor_ = 1e-6;
  Eigen::Index dimension_ = 0;
  std::vector<GaussianDensity> densities_;
  std::vector<bool> present_;
};

class QuadraticDiscriminant : public Classifier {
 public:
  explicit QuadraticDiscriminant(const Parameters& parameters = {});
  std::string name() const override { return "qda"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  // Posterior P(k | x) ∝ π_k N(x; μ_k, Σ_k).
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

 private:
  double ridge_factor_ = 1e-6;
  std::string priors_mode_ = "empirical";
  Eigen::Index dimension_ = 0;
  Vector priors_;
  std::vector<GaussianDensity> densities_;
};

// Factories for the classifier registry (name -> factory table).
std::unique_ptr<Classifier> make_gaussian_ml_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_qda_classifier(const Parameters& parameters);

}  // namespace tactile::ml

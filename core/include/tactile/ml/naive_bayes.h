#pragma once
// Naive Bayes: features independent within a class, so log p(x | k) = Σ_j log p(x_j | k).
// scores() = posterior P(k | x) ∝ π_k p(x | k) (rows sum to 1).
//
// Presets (MATLAB Classification Learner, TSA paper 001 Table 4):
//   gaussian-nb  "Gaussian Naive Bayes": per class and feature a normal with the sample mean
//                and unbiased variance; empirical priors. Regularisation (MATLAB errors on a
//                zero within-class variance): every variance gets + var_smoothing · (largest
//                population variance of a feature over all training rows), as scikit-learn's
//                GaussianNB; a class with one sample takes the pooled within-class variance.
//                Parameters: var_smoothing (default 1e-9), priors (empirical|uniform).
//   kernel-nb    "Kernel Naive Bayes": normal kernel, unbounded support. Default width per
//                class and feature as MATLAB's ksdensity (Silverman's rule with a robust σ):
//                h = σ̂ (4 / (3 n))^(1/5), σ̂ = median|x - median(x)| / 0.6745. Where that σ̂ is
//                0 (more than half the values equal) we use the sample std; where the feature
//                is constant in the class, the width of that feature over all training rows
//                by the same rule; where it is constant everywhere, 1. Parameters: width (0 =
//                automatic, > 0 one fixed width for all), priors (empirical|uniform).
// A class absent from the training data gets prior 0 and is never predicted.

#include <Eigen/Core>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

class GaussianNaiveBayes : public Classifier {
 public:
  explicit GaussianNaiveBayes(const Parameters& parameters = {});
  std::string name() const override { return "gaussian-nb"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // rows = classes, columns = features (variances include the smoothing).
  const Matrix& means() const { return means_; }
  const Matrix& variances() const { return variances_; }

 private:
  double variance_smoothing_ = 1e-9;
  std::string priors_mode_ = "empirical";
  Vector priors_;
  Matrix means_;
  Matrix variances_;
};

class KernelNaiveBayes : public Classifier {
 public:
  explicit KernelNaiveBayes(const Parameters& parameters = {});
  std::string name() const override { return "kernel-nb"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // rows = classes, columns = features.
  const Matrix& widths() const { return widths_; }

 private:
  double fixed_width_ = 0.0;
  std::string priors_mode_ = "empirical";
  Eigen::Index dimension_ = 0;
  Vector priors_;
  Matrix widths_;
  std::vector<Matrix> samples_;  // training rows of each class
};

// MATLAB ksdensity's default normal-kernel width of one sample: σ̂ (4 / (3 n))^(1/5) with
// σ̂ = MAD / 0.6745; 0 when the MAD is 0 (the caller decides the fallback).
double silverman_width(const Vector& values);

// Factories for the classifier registry (name -> factory table).
std::unique_ptr<Classifier> make_gaussian_nb_classifier(const Parameters& parameters);
std::unique_ptr<Classifier> make_kernel_nb_classifier(const Parameters& parameters);

}  // namespace tactile::ml

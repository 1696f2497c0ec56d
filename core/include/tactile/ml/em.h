#pragma once
// EM Gaussian mixture with classes-to-clusters evaluation (Kaboli et al., spec §1.16, Fig. 4).
//
// Mixture (spec §1.16): K components, diagonal covariances by default (Weka-EM style) or
// full; initialised by k-means++ seeding on the data (each sample then hard-assigned to its
// nearest seed gives the first responsibilities); EM until the log-likelihood gains less than
// `tolerance` relative to its magnitude, or `max_iterations`; variance floor per dimension
// (added to the diagonal for full covariances); `restarts` runs, keep the highest
// log-likelihood (the first on ties). Every random draw comes from one std::mt19937_64
// seeded with the given seed. A component that loses all its samples keeps weight 0 and
// never wins a sample again.
//
// Classifier preset `em` (the paper's EM of Fig. 4): standardise with training statistics,
// fit K = class count clusters (parameter `clusters` overrides), map each cluster to the
// majority training class among the samples it wins (ties -> lowest class; a cluster that
// wins none answers "unknown", kUnknownClass), predict the mapped class of the most
// responsible cluster. `mapping=one-to-one` uses Weka's classes-to-clusters instead: each
// class at most once, chosen to maximise the correctly mapped training samples (Hungarian
// method). scores() = per class, the summed responsibility of the clusters mapped to it
// (rows sum to 1 minus the responsibility of unmapped clusters).
// Parameters: clusters (0 = class count), covariance (diagonal|full), restarts (10),
// iterations (100), tolerance (1e-6), variance_floor (1e-6), mapping (majority|one-to-one),
// standardize (true), init (kmeans++|classes).
//   init=classes is ours, a diagnostic, not the paper's unsupervised EM: the first
// responsibilities are the training labels (cluster k starts as class k's Gaussian), then EM
// runs unlabelled as usual. It shows what the descriptor's class clusters are worth to a
// mixture, against what k-means++ restarts find from scratch.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"
#include "tactile/ml/gaussian.h"

namespace tactile::ml {

enum class MixtureCovariance { kDiagonal, kFull };

struct MixtureOptions {
  int components = 9;
  MixtureCovariance covariance = MixtureCovariance::kDiagonal;
  int restarts = 10;
  int max_iterations = 100;
  double tolerance = 1e-6;
  double variance_floor = 1e-6;
};

struct GaussianMixture {
  MixtureCovariance covariance = MixtureCovariance::kDiagonal;
  Vector weights;                     // K, sum 1
  Matrix means;                       // K x d
  Matrix variances;                   // K x d (diagonal model)
  std::vector<GaussianDensity> full;  // K (full model)
  double log_likelihood = 0.0;        // Σ_i ln p(x_i) on the data it was fitted on
  int iterations = 0;                 // EM iterations of the kept restart

  int components() const { return static_cast<int>(weights.size()); }
  // ln w_k + ln N(x_i; μ_k, Σ_k), rows = samples, columns = components (-inf for weight 0).
  Matrix log_joint(const Matrix& x) const;
  // Posterior of each component per sample; rows sum to 1.
  Matrix responsibilities(const Matrix& x) const;
  // The most responsible component per sample (lowest on ties).
  std::vector<int> assign(const Matrix& x) const;
  nlohmann::json save() const;
  void load(const nlohmann::json& model, const std::string& where);
};

// Throws tactile::Error on no samples, fewer samples than components, NaN, or bad options.
GaussianMixture fit_gaussian_mixture(const Matrix& x, const MixtureOptions& options, uint64_t seed);
// One EM run whose first responsibilities are a hard grouping: sample i wholly in component
// groups[i] (0..components-1). No randomness, no restarts. Throws as above, and on a group
// count that differs from the samples or a group out of range.
GaussianMixture fit_gaussian_mixture_from(const Matrix& x, const std::vector<int>& groups,
                                          const MixtureOptions& options);

enum class ClusterMapping { kMajority, kOneToOne };

// Class of each cluster from the training labels of the samples it won (see the header
// comment); kUnknownClass for an unmapped cluster.
std::vector<int> map_clusters_to_classes(const std::vector<int>& clusters,
                                         const std::vector<int>& classes, int cluster_count,
                                         int class_count, ClusterMapping mapping);

// Minimum-cost assignment of rows to distinct columns (Hungarian method, rows <= columns):
// the column of each row.
std::vector<int> minimum_cost_assignment(const Matrix& cost);

class ExpectationMaximization : public Classifier {
 public:
  explicit ExpectationMaximization(const Parameters& parameters = {});
  std::string name() const override { return "em"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  // The mapped class of the most responsible cluster (kUnknownClass if it is unmapped).
  std::vector<int> predict(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  const GaussianMixture& mixture() const { return mixture_; }
  const std::vector<int>& cluster_classes() const { return cluster_classes_; }

 private:
  int requested_clusters_ = 0;
  MixtureOptions options_;
  ClusterMapping mapping_ = ClusterMapping::kMajority;
  bool standardize_ = true;
  bool start_from_classes_ = false;
  int class_count_ = 0;
  Standardizer standardizer_;
  GaussianMixture mixture_;
  std::vector<int> cluster_classes_;
};

// Factory for the classifier registry (name -> factory table).
std::unique_ptr<Classifier> make_em_classifier(const Parameters& parameters);

}  // namespace tactile::ml

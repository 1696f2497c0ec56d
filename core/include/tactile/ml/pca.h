#pragma once
// Principal component analysis (spec §6.5, TV X3): standardise (spec §6.4, training
// statistics), eigendecompose the covariance Zᵀ Z / (N-1) of the standardised data,
// eigenvalues descending, each loading column's largest-|.| entry made positive. Keep a
// fixed number of components, or the smallest k whose cumulative explained ratio reaches a
// fraction (1e-12 tolerance). Used by the flux experiment (90 %, spec §5.8) and the TSA
// presets (95 %, spec §2.12).

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

struct PcaOptions {
  // Components to keep; 0 = choose by variance_fraction.
  int components = 0;
  double variance_fraction = 0.90;
  // Spec §5.8 uses standardised (normed) PCA; false only centres.
  bool standardize = true;
};

struct Pca {
  Standardizer standardizer;  // mean and scale of the training data (scale 1 when not standardised)
  Vector eigenvalues;         // all P, descending, negatives from rounding clamped to 0
  Vector explained_ratio;     // λ_a / Σ λ, all P
  Matrix loadings;            // P x P, columns = components, sign-fixed; with fewer rows than
                              // features, only the R components that have variance (P x R)
  int kept = 0;               // components kept

  // Scores of new rows on the kept components: standardise, then Z V[:, :kept].
  Matrix transform(const Matrix& x) const;
  Vector cumulative_ratio() const;
  nlohmann::json save() const;
  void load(const nlohmann::json& model);
};

// Throws tactile::Error on fewer than 2 rows, NaN, bad options, or data with no variance at
// all (nothing to explain).
Pca fit_pca(const Matrix& x, const PcaOptions& options = {});

// Flip each column so that its entry of largest magnitude (first on ties) is positive; the
// sign convention shared by PCA loadings and MDS coordinates.
void fix_column_signs(Matrix& columns);

}  // namespace tactile::ml

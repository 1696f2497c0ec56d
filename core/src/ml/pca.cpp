#include "tactile/ml/pca.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "probabilistic_support.h"
#include "tactile/error.h"

namespace tactile::ml {

void fix_column_signs(Matrix& columns) {
  for (Eigen::Index column = 0; column < columns.cols(); ++column) {
    Eigen::Index largest = 0;
    columns.col(column).cwiseAbs().maxCoeff(&largest);  // first maximum on ties
    if (columns(largest, column) < 0.0) columns.col(column) = -columns.col(column);
  }
}

Pca fit_pca(const Matrix& x, const PcaOptions& options) {
  const std::string where = "pca";
  if (x.rows() < 2) throw Error(where, "needs at least 2 samples, got " + std::to_string(x.rows()));
  if (x.cols() < 1) throw Error(where, "no features");
  check_query(x, x.cols(), where);
  if (options.components < 0 || options.components > x.cols())
    throw Error(where, "components=" + std::to_string(options.components) + ": expected 0.." +
                           std::to_string(x.cols()));
  if (!(options.variance_fraction > 0.0 && options.variance_fraction <= 1.0))
    throw Error(where, "variance fraction " + support::format_number(options.variance_fraction) +
                           " is not in (0, 1]");

  Pca pca;
  if (options.standardize) {
    pca.standardizer.fit(x);
  } else {
    pca.standardizer.mean = x.colwise().mean().transpose();
    pca.standardizer.scale = Vector::Ones(x.cols());
  }
  const Matrix z = pca.standardizer.transform(x);
  const double n1 = static_cast<double>(x.rows() - 1);
  if (x.rows() - 1 >= x.cols()) {
    // Spec §6.5: Cz = Zᵀ Z / (N-1), eigenvalues descending.
    const Eigen::SelfAdjointEigenSolver<Matrix> solver((z.transpose() * z) / n1);
    if (solver.info() != Eigen::Success) throw Error(where, "eigendecomposition did not converge");
    pca.eigenvalues = solver.eigenvalues().reverse().cwiseMax(0.0);
    pca.loadings = solver.eigenvectors().rowwise().reverse();
  } else {
    // Fewer rows than features (454 segments x 1692 features): Cz has rank N-1 at most, and
    // its nonzero eigenvalues are those of the N x N Gram matrix Z Zᵀ / (N-1), whose
    // eigenvector u gives Cz's as v = Zᵀ u / sqrt((N-1) λ). The same components at N³
    // instead of P³ (0.1 s instead of 4.7 s at 454 x 1692); the directions of no variance
    // are left out of the loadings (their eigenvalues are 0).
    const Eigen::SelfAdjointEigenSolver<Matrix> solver((z * z.transpose()) / n1);
    if (solver.info() != Eigen::Success) throw Error(where, "eigendecomposition did not converge");
    const Vector gram = solver.eigenvalues().reverse().cwiseMax(0.0);
    const Matrix u = solver.eigenvectors().rowwise().reverse();
    const double floor = gram.size() > 0 ? gram(0) * 1e-12 : 0.0;
    Eigen::Index rank = 0;
    while (rank < gram.size() && gram(rank) > floor) ++rank;
    pca.eigenvalues = Vector::Zero(x.cols());
    pca.eigenvalues.head(rank) = gram.head(rank);
    pca.loadings = Matrix::Zero(x.cols(), std::max<Eigen::Index>(rank, options.components));
    for (Eigen::Index k = 0; k < rank; ++k)
      pca.loadings.col(k) = z.transpose() * u.col(k) / std::sqrt(n1 * gram(k));
  }
  fix_column_signs(pca.loadings);
  const double total = pca.eigenvalues.sum();
  if (!(total > 0.0)) throw Error(where, "every feature is constant: no variance to explain");
  pca.explained_ratio = pca.eigenvalues / total;

  if (options.components > 0) {
    pca.kept = options.components;
  } else {
    const Vector cumulative = pca.cumulative_ratio();
    pca.kept = static_cast<int>(cumulative.size());
    for (Eigen::Index k = 0; k < cumulative.size(); ++k) {
      if (cumulative(k) >= options.variance_fraction - 1e-12) {
        pca.kept = static_cast<int>(k + 1);
        break;
      }
    }
    pca.kept = std::min(pca.kept, static_cast<int>(pca.loadings.cols()));
  }
  return pca;
}

Vector Pca::cumulative_ratio() const {
  Vector cumulative(explained_ratio.size());
  double sum = 0.0;
  for (Eigen::Index k = 0; k < explained_ratio.size(); ++k)
    cumulative(k) = sum += explained_ratio(k);
  return cumulative;
}

Matrix Pca::transform(const Matrix& x) const {
  if (kept == 0) throw Error("pca", "not fitted");
  check_query(x, loadings.rows(), "pca");
  return standardizer.transform(x) * loadings.leftCols(kept);
}

nlohmann::json Pca::save() const {
  return {{"standardizer", standardizer.save()},
          {"eigenvalues", support::vector_to_json(eigenvalues)},
          {"explained_ratio", support::vector_to_json(explained_ratio)},
          {"loadings", support::matrix_to_json(loadings)},
          {"kept", kept}};
}

void Pca::load(const nlohmann::json& model) {
  const std::string where = "pca model";
  try {
    standardizer.load(model.at("standardizer"));
    eigenvalues = support::vector_from_json(model.at("eigenvalues"), where + " eigenvalues");
    explained_ratio =
        support::vector_from_json(model.at("explained_ratio"), where + " explained_ratio");
    loadings = support::matrix_from_json(model.at("loadings"), where + " loadings");
    kept = model.at("kept").get<int>();
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
  const Eigen::Index features = standardizer.mean.size();
  if (loadings.rows() != features || loadings.cols() != features ||
      eigenvalues.size() != features || explained_ratio.size() != features || kept < 1 ||
      kept > features)
    throw Error(where, "shapes do not match " + std::to_string(features) + " features");
}

}  // namespace tactile::ml

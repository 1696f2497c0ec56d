#include "ml_prob_test_data.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <numbers>

namespace tactile::ml::test_data {

double uniform_open(std::mt19937_64& random) {
  return (static_cast<double>(random() >> 11) + 0.5) * 0x1.0p-53;
}

double standard_normal(std::mt19937_64& random) {
  const double radius = std::sqrt(-2.0 * std::log(uniform_open(random)));
  return radius * std::cos(2.0 * std::numbers::pi * uniform_open(random));
}

// `count` rows drawn from N(mean, covariance).
Eigen::MatrixXd draw(const Blob& blob, int count, std::mt19937_64& random) {
  const Eigen::MatrixXd lower = blob.covariance.llt().matrixL();
  Eigen::MatrixXd rows(count, blob.mean.size());
  for (int row = 0; row < count; ++row) {
    Eigen::VectorXd z(blob.mean.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) z(j) = standard_normal(random);
    rows.row(row) = (blob.mean + lower * z).transpose();
  }
  return rows;
}

// Rows of each blob stacked in blob order, labels = blob index.
void draw_classes(const std::vector<Blob>& blobs, int per_class, std::mt19937_64& random,
                  Eigen::MatrixXd& x, std::vector<int>& y) {
  x.resize(static_cast<Eigen::Index>(blobs.size()) * per_class, blobs.front().mean.size());
  y.clear();
  for (size_t k = 0; k < blobs.size(); ++k) {
    x.middleRows(static_cast<Eigen::Index>(k) * per_class, per_class) =
        draw(blobs[k], per_class, random);
    y.insert(y.end(), static_cast<size_t>(per_class), static_cast<int>(k));
  }
}

// The Bayes rule with equal priors: the blob of highest true density.
std::vector<int> bayes_rule(const std::vector<Blob>& blobs, const Eigen::MatrixXd& x) {
  std::vector<int> decision(static_cast<size_t>(x.rows()), 0);
  for (Eigen::Index row = 0; row < x.rows(); ++row) {
    double best = -INFINITY;
    for (size_t k = 0; k < blobs.size(); ++k) {
      const Eigen::VectorXd centred = x.row(row).transpose() - blobs[k].mean;
      const double log_density = -0.5 * (std::log(blobs[k].covariance.determinant()) +
                                         centred.dot(blobs[k].covariance.ldlt().solve(centred)));
      if (log_density > best) {
        best = log_density;
        decision[static_cast<size_t>(row)] = static_cast<int>(k);
      }
    }
  }
  return decision;
}

double agreement(const std::vector<int>& a, const std::vector<int>& b) {
  int same = 0;
  for (size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
  return static_cast<double>(same) / static_cast<double>(a.size());
}

}  // namespace tactile::ml::test_data

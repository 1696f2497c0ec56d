#pragma once
// Synthetic data for the probabilistic classifier tests: Gaussian blobs drawn with our own
// Box-Muller transform (so the samples are the same on every standard library) and the
// Bayes rule of the true densities they were drawn from. Defined in ml_prob_test_data.cpp,
// so the Eigen factorisations are compiled once, not in every test that draws blobs.

#include <Eigen/Core>
#include <random>
#include <vector>

namespace tactile::ml::test_data {

double uniform_open(std::mt19937_64& random);
double standard_normal(std::mt19937_64& random);

struct Blob {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
};

// `count` rows drawn from N(mean, covariance).
Eigen::MatrixXd draw(const Blob& blob, int count, std::mt19937_64& random);

// Rows of each blob stacked in blob order, labels = blob index.
void draw_classes(const std::vector<Blob>& blobs, int per_class, std::mt19937_64& random,
                  Eigen::MatrixXd& x, std::vector<int>& y);

// The Bayes rule with equal priors: the blob of highest true density.
std::vector<int> bayes_rule(const std::vector<Blob>& blobs, const Eigen::MatrixXd& x);

double agreement(const std::vector<int>& a, const std::vector<int>& b);

}  // namespace tactile::ml::test_data

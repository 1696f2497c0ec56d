#pragma once
// Input checks shared by the SVM, tree and LogitBoost classifiers: every bad training or
// test matrix becomes a tactile::Error naming the classifier and the offending row, so no
// NaN reaches libsvm or a split search.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml::training_checks {

// Throws unless x has rows, y has one class index in [0, class_count) per row and every
// value of x is finite. Returns the number of training samples per class.
std::vector<int64_t> check_training(const std::string& classifier, const Matrix& x,
                                    const std::vector<int>& y, int class_count);
// Throws unless x has `feature_count` columns and only finite values; `fitted` says
// whether fit() or load() ran.
void check_prediction(const std::string& classifier, const Matrix& x, Eigen::Index feature_count,
                      bool fitted);

}  // namespace tactile::ml::training_checks

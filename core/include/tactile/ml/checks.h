#pragma once
// Input checks every classifier shares, so that bad input gives the same clear
// tactile::Error everywhere instead of a crash, a silent NaN in the scores, or a NaN that
// reaches libsvm or a split search.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// Throws tactile::Error(where, ...) unless x has at least one row and one column, every value
// is finite (the error names the row and feature), y has one entry per row and every entry is
// in 0..class_count-1. Returns the number of training samples per class.
std::vector<int64_t> check_training_set(const Matrix& x, const std::vector<int>& y, int class_count,
                                        const std::string& where);
// Throws tactile::Error(where, ...) unless x has `features` columns and only finite values.
void check_query(const Matrix& x, Eigen::Index features, const std::string& where);
// Throws tactile::Error(where, ...) when scores are asked of a classifier never fitted or loaded.
void check_fitted(bool fitted, const std::string& where);

}  // namespace tactile::ml

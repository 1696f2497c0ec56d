#pragma once
// What the SVM and its probabilities share of libsvm (Debian's libsvm-dev, an include path
// private to core): the model's owner and the cross-validated Platt sigmoid of one binary
// learner. Private to core/src/ml.

#include <svm.h>

#include <memory>
#include <random>
#include <string>

#include "tactile/ml/svm_probability.h"

namespace tactile::ml {

struct LibsvmModelDeleter {
  void operator()(svm_model* model) const { svm_free_and_destroy_model(&model); }
};
using LibsvmModel = std::unique_ptr<svm_model, LibsvmModelDeleter>;

// libsvm's svm_binary_svc_probability: the rows of `problem` (targets +1 / -1) in a shuffled
// order cut into 5 folds, each fold's decision values from a model of the other four (the
// same parameters), oriented so that f > 0 means the positive class, then Platt's sigmoid
// fitted to them (fit_platt_sigmoid). A fold whose training part holds one class only gives
// its rows f = +1 or -1, as libsvm does. libsvm shuffles with rand(), one generator for the
// whole process, which concurrent fits (an evaluation's fold threads) would share; the order
// here is drawn from `engine`, so a seed gives the same sigmoid on any thread. Stops between
// folds when the calling thread's job is cancelled (an Error naming `where`).
PlattSigmoid cross_validated_sigmoid(const svm_problem& problem, const svm_parameter& parameter,
                                     std::mt19937_64 engine, const std::string& where);

}  // namespace tactile::ml

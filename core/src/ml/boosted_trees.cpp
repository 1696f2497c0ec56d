#include "tactile/ml/boosted_trees.h"

#include <xgboost/c_api.h>

#include <algorithm>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "model_json.h"
#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/ml/checks.h"
#include "tactile/random.h"

namespace tactile::ml {

namespace {

// Throws tactile::Error with XGBoost's last message when a C API call failed.
void xgboost_check(int status, const char* what) {
  if (status != 0) throw Error("boosted-trees", std::string(what) + ": " + XGBGetLastError());
}

// XGBoost logs warnings to stderr from any thread; silenced once for the whole process.
void silence_xgboost() {
  static std::once_flag once;
  std::call_once(once, [] { XGBSetGlobalConfig(R"({"verbosity": 0})"); });
}

// A DMatrix of x (row-major floats), freed on scope exit.
class XgboostMatrix {
 public:
  explicit XgboostMatrix(const Matrix& x) {
    const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values =
        x.cast<float>();
    xgboost_check(XGDMatrixCreateFromMat(values.data(), static_cast<bst_ulong>(x.rows()),
                                         static_cast<bst_ulong>(x.cols()),
                                         std::numeric_limits<float>::quiet_NaN(), &handle_),
                  "DMatrix");
  }
  ~XgboostMatrix() { XGDMatrixFree(handle_); }
  XgboostMatrix(const XgboostMatrix&) = delete;
  XgboostMatrix& operator=(const XgboostMatrix&) = delete;
  DMatrixHandle handle() const { return handle_; }

 private:
  DMatrixHandle handle_ = nullptr;
};

int xgboost_threads(int threads) { return threads > 0 ? threads : thread_budget(); }

// XGBoost's "gain" importance per column ("f<index>" names), normalised to sum 1.
std::vector<double> xgboost_importances(BoosterHandle booster, Eigen::Index columns) {
  bst_ulong count = 0;
  const char** names = nullptr;
  bst_ulong dimensions = 0;
  const bst_ulong* shape = nullptr;
  const float* values = nullptr;
  xgboost_check(XGBoosterFeatureScore(booster, R"({"importance_type": "gain"})", &count, &names,
                                      &dimensions, &shape, &values),
                "feature score");
  std::vector<double> importances(static_cast<size_t>(columns), 0.0);
  for (bst_ulong index = 0; index < count; ++index) {
    const std::string name = names[index];
    if (name.size() < 2 || name[0] != 'f') continue;
    const long column = std::stol(name.substr(1));
    if (column >= 0 && column < columns) importances[static_cast<size_t>(column)] = values[index];
  }
  double sum = 0.0;
  for (const double value : importances) sum += value;
  if (sum > 0.0)
    for (double& value : importances) value /= sum;
  return importances;
}

}  // namespace

BoostedTrees::BoostedTrees(const std::string& preset, const Parameters& parameters) {
  if (preset != "boosted-trees")
    throw Error(parameters.where(), "no boosted trees preset named '" + preset + "'");
  parameters.expect_only({"rounds", "depth", "eta", "subsample", "colsample"});
  rounds_ = parameters.integer("rounds", rounds_);
  depth_ = parameters.integer("depth", depth_);
  eta_ = parameters.number("eta", eta_);
  subsample_ = parameters.number("subsample", subsample_);
  colsample_ = parameters.number("colsample", colsample_);
  if (rounds_ < 1) throw Error(parameters.where(), "rounds must be 1 or more");
  if (depth_ < 1) throw Error(parameters.where(), "depth must be 1 or more");
  if (!(eta_ > 0.0 && eta_ <= 1.0)) throw Error(parameters.where(), "eta must be in (0, 1]");
  if (!(subsample_ > 0.0 && subsample_ <= 1.0))
    throw Error(parameters.where(), "subsample must be in (0, 1]");
  if (!(colsample_ > 0.0 && colsample_ <= 1.0))
    throw Error(parameters.where(), "colsample must be in (0, 1]");
}

BoostedTrees::~BoostedTrees() { free_booster(); }

void BoostedTrees::free_booster() {
  if (booster_) XGBoosterFree(booster_);
  booster_ = nullptr;
}

Parameters BoostedTrees::parameters() const {
  Parameters parameters;
  parameters.set("rounds", std::to_string(rounds_));
  parameters.set("depth", std::to_string(depth_));
  parameters.set("eta", model_json::format_number(eta_));
  parameters.set("subsample", model_json::format_number(subsample_));
  parameters.set("colsample", model_json::format_number(colsample_));
  return parameters;
}

void BoostedTrees::fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) {
  check_training_set(x, y, class_count, "boosted-trees");
  silence_xgboost();
  free_booster();
  importances_.clear();
  class_count_ = class_count;
  feature_count_ = x.cols();

  const XgboostMatrix train(x);
  const std::vector<float> labels(y.begin(), y.end());
  xgboost_check(XGDMatrixSetFloatInfo(train.handle(), "label", labels.data(),
                                      static_cast<bst_ulong>(labels.size())),
                "labels");
  DMatrixHandle matrices[] = {train.handle()};
  BoosterHandle booster = nullptr;
  xgboost_check(XGBoosterCreate(matrices, 1, &booster), "booster");
  booster_ = booster;
  try {
    train_booster(train.handle(), class_count, seed);
  } catch (...) {
    free_booster();  // no half-trained model answers scores()
    throw;
  }
  importances_ = xgboost_importances(booster_, x.cols());
}

void BoostedTrees::train_booster(void* train, int class_count, uint64_t seed) {
  // XGBoost's seed is a 32-bit int.
  const auto xgboost_seed = static_cast<int32_t>(derive_seed(seed, 0) & 0x7fffffffu);
  const std::vector<std::pair<std::string, std::string>> settings = {
      {"verbosity", "0"},
      {"objective", "multi:softprob"},
      {"num_class", std::to_string(std::max(class_count, 2))},
      {"tree_method", "hist"},
      {"max_depth", std::to_string(depth_)},
      {"eta", model_json::format_number(eta_)},
      {"subsample", model_json::format_number(subsample_)},
      {"colsample_bytree", model_json::format_number(colsample_)},
      {"seed", std::to_string(xgboost_seed)},
      {"nthread", std::to_string(xgboost_threads(threads_))},
  };
  for (const auto& [key, value] : settings)
    xgboost_check(XGBoosterSetParam(booster_, key.c_str(), value.c_str()), key.c_str());
  for (int64_t round = 0; round < rounds_; ++round) {
    if (cancel_requested()) throw Error("boosted-trees", "cancelled");
    xgboost_check(XGBoosterUpdateOneIter(booster_, static_cast<int>(round), train),
                  "boosting round");
  }
}

Matrix BoostedTrees::scores(const Matrix& x) const {
  check_fitted(booster_ != nullptr, "boosted-trees");
  check_query(x, feature_count_, "boosted-trees");
  const XgboostMatrix query(x);
  bst_ulong length = 0;
  const float* values = nullptr;
  xgboost_check(XGBoosterPredict(booster_, query.handle(), 0, 0, 0, &length, &values), "predict");
  const int columns = std::max(class_count_, 2);
  if (length != static_cast<bst_ulong>(x.rows() * columns))
    throw Error("boosted-trees", "XGBoost gave " + std::to_string(length) + " probabilities for " +
                                     std::to_string(x.rows()) + " rows");
  const Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      probabilities(values, x.rows(), columns);
  return probabilities.leftCols(class_count_).cast<double>();
}

nlohmann::json BoostedTrees::save() const {
  if (!booster_) throw Error("boosted-trees", "save() before fit()");
  bst_ulong length = 0;
  const char* buffer = nullptr;
  xgboost_check(XGBoosterSaveModelToBuffer(booster_, R"({"format": "json"})", &length, &buffer),
                "save");
  return {{"class_count", class_count_},
          {"feature_count", feature_count_},
          {"importances", importances_},
          {"xgboost", std::string(buffer, length)}};
}

void BoostedTrees::load(const nlohmann::json& model) {
  const std::string where = "boosted-trees model";
  try {
    const int class_count = model.at("class_count").get<int>();
    const auto feature_count = model.at("feature_count").get<Eigen::Index>();
    if (class_count < 1 || feature_count < 1)
      throw Error(where, "bad class_count or feature_count");
    auto importances = model.at("importances").get<std::vector<double>>();
    if (static_cast<Eigen::Index>(importances.size()) != feature_count)
      throw Error(where, "importances do not match feature_count");
    const auto saved = model.at("xgboost").get<std::string>();
    silence_xgboost();
    BoosterHandle booster = nullptr;
    xgboost_check(XGBoosterCreate(nullptr, 0, &booster), "booster");
    if (XGBoosterLoadModelFromBuffer(booster, saved.data(), saved.size()) != 0) {
      const std::string message = XGBGetLastError();
      XGBoosterFree(booster);
      throw Error(where, "XGBoost cannot read the model: " + message);
    }
    XGBoosterSetParam(booster, "nthread", std::to_string(xgboost_threads(threads_)).c_str());
    free_booster();
    booster_ = booster;
    class_count_ = class_count;
    feature_count_ = feature_count;
    importances_ = std::move(importances);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, error.what());
  }
}

std::unique_ptr<Classifier> make_boosted_trees_classifier(const Parameters& parameters) {
  return std::make_unique<BoostedTrees>("boosted-trees", parameters);
}

}  // namespace tactile::ml

#include "tactile/ml/column_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "tactile/error.h"
#include "tactile/ml/checks.h"

namespace tactile::ml {

namespace {

const char* const kSelectWhere = "classifier select";

// "A-B+C-D" -> {{A, B}, {C, D}}; each block 0 <= A <= B.
std::vector<std::pair<int, int>> parse_column_blocks(const std::string& text) {
  std::vector<std::pair<int, int>> blocks;
  size_t start = 0;
  while (start < text.size()) {
    const size_t plus = std::min(text.find('+', start), text.size());
    const std::string block = text.substr(start, plus - start);
    const size_t dash = block.find('-');
    int first = -1, last = -1;
    try {
      size_t used = 0;
      first = std::stoi(block.substr(0, dash), &used);
      if (used != dash) first = -1;
      const std::string tail = block.substr(dash == std::string::npos ? block.size() : dash + 1);
      last = std::stoi(tail, &used);
      if (used != tail.size()) last = -1;
    } catch (const std::exception&) {
      first = -1;
    }
    if (dash == std::string::npos || first < 0 || last < first)
      throw Error(kSelectWhere, "columns=" + text + ": '" + block +
                                    "' is not a block A-B of 0-based columns, A <= B");
    blocks.emplace_back(first, last);
    start = plus + 1;
  }
  if (blocks.empty()) throw Error(kSelectWhere, "columns= is empty");
  return blocks;
}

}  // namespace

Vector anova_f(const Matrix& x, const std::vector<int>& y, int class_count) {
  const Eigen::Index n = x.rows();
  std::vector<double> count(static_cast<size_t>(class_count), 0.0);
  for (int label : y) count[static_cast<size_t>(label)] += 1.0;
  int present = 0;
  for (double c : count) present += c > 0.0 ? 1 : 0;
  Vector f = Vector::Zero(x.cols());
  if (present < 2 || n <= present) return f;
  Matrix sums = Matrix::Zero(class_count, x.cols());
  for (Eigen::Index r = 0; r < n; ++r) sums.row(y[static_cast<size_t>(r)]) += x.row(r);
  const Eigen::RowVectorXd mean = x.colwise().mean();
  Eigen::RowVectorXd between = Eigen::RowVectorXd::Zero(x.cols());
  Matrix class_mean = sums;
  for (int k = 0; k < class_count; ++k) {
    const double c = count[static_cast<size_t>(k)];
    if (c == 0.0) continue;
    class_mean.row(k) /= c;
    between += c * (class_mean.row(k) - mean).array().square().matrix();
  }
  Eigen::RowVectorXd within = Eigen::RowVectorXd::Zero(x.cols());
  for (Eigen::Index r = 0; r < n; ++r)
    within += (x.row(r) - class_mean.row(y[static_cast<size_t>(r)])).array().square().matrix();
  const double between_df = present - 1.0;
  const double within_df = static_cast<double>(n) - present;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    // Spreads below the rounding of the column's own scale count as none.
    const double scale = 1e-12 * (mean(j) * mean(j) + 1e-300) * static_cast<double>(n);
    if (between(j) <= scale) continue;
    f(j) = within(j) <= scale ? std::numeric_limits<double>::infinity()
                              : (between(j) / between_df) / (within(j) / within_df);
  }
  return f;
}

std::vector<int> top_columns(const Vector& f, int k) {
  std::vector<int> order(static_cast<size_t>(f.size()));
  std::iota(order.begin(), order.end(), 0);
  k = std::clamp(k, 0, static_cast<int>(order.size()));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return f(a) > f(b); });
  order.resize(static_cast<size_t>(k));
  std::sort(order.begin(), order.end());
  return order;
}

SelectedColumnsClassifier::SelectedColumnsClassifier(const Parameters& parameters) {
  parameters.expect_only({"columns", "k", "base"});
  block_text_ = parameters.text("columns", "");
  if (!block_text_.empty()) blocks_ = parse_column_blocks(block_text_);
  k_ = parameters.integer("k", 0);
  if (k_ < 0)
    throw Error(kSelectWhere, "k=" + std::to_string(k_) + ": must be 0 (every column) or more");
  base_ = parameters.text("base", "");
  std::replace(base_.begin(), base_.end(), ';', ',');
  if (base_.empty())
    throw Error(kSelectWhere, "base= is required, e.g. select:k=50,base=linear-svm");
  make_classifier(base_);  // an unknown base or parameter fails here, before any fit
}

Parameters SelectedColumnsClassifier::parameters() const {
  Parameters parameters;
  if (!block_text_.empty()) parameters.set("columns", block_text_);
  parameters.set("k", std::to_string(k_));
  std::string base = base_;
  std::replace(base.begin(), base.end(), ',', ';');
  parameters.set("base", base);
  return parameters;
}

void SelectedColumnsClassifier::fit(const Matrix& x, const std::vector<int>& y, int class_count,
                                    uint64_t seed) {
  check_training_set(x, y, class_count, kSelectWhere);
  std::vector<int> candidates;
  if (blocks_.empty()) {
    candidates.resize(static_cast<size_t>(x.cols()));
    std::iota(candidates.begin(), candidates.end(), 0);
  } else {
    for (const auto& [first, last] : blocks_) {
      if (last >= x.cols())
        throw Error(kSelectWhere, "columns=" + block_text_ + ": the table has " +
                                      std::to_string(x.cols()) + " columns (0-" +
                                      std::to_string(x.cols() - 1) + ")");
      for (int c = first; c <= last; ++c) candidates.push_back(c);
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  }
  if (k_ > 0 && k_ < static_cast<int64_t>(candidates.size())) {
    Matrix part(x.rows(), static_cast<Eigen::Index>(candidates.size()));
    for (size_t c = 0; c < candidates.size(); ++c)
      part.col(static_cast<Eigen::Index>(c)) = x.col(candidates[c]);
    std::vector<int> kept = top_columns(anova_f(part, y, class_count), static_cast<int>(k_));
    for (int& column : kept) column = candidates[static_cast<size_t>(column)];
    candidates = std::move(kept);
  }
  chosen_ = std::move(candidates);
  input_columns_ = static_cast<int>(x.cols());
  std::unique_ptr<Classifier> base = make_classifier(base_);
  base->fit(chosen_part(x), y, class_count, seed);
  fitted_ = std::move(base);
}

Matrix SelectedColumnsClassifier::chosen_part(const Matrix& x) const {
  if (x.cols() != input_columns_)
    throw Error(kSelectWhere, "fitted on " + std::to_string(input_columns_) + " columns, given " +
                                  std::to_string(x.cols()));
  Matrix part(x.rows(), static_cast<Eigen::Index>(chosen_.size()));
  for (size_t c = 0; c < chosen_.size(); ++c)
    part.col(static_cast<Eigen::Index>(c)) = x.col(chosen_[c]);
  return part;
}

const Classifier& SelectedColumnsClassifier::base() const {
  if (!fitted_) throw Error(kSelectWhere, "not fitted");
  return *fitted_;
}

Matrix SelectedColumnsClassifier::scores(const Matrix& x) const {
  return base().scores(chosen_part(x));
}

std::vector<int> SelectedColumnsClassifier::predict(const Matrix& x) const {
  return base().predict(chosen_part(x));
}

Classifier::Decisions SelectedColumnsClassifier::decide(const Matrix& x) const {
  return base().decide(chosen_part(x));
}

nlohmann::json SelectedColumnsClassifier::save() const {
  return {
      {"input_columns", input_columns_}, {"columns", chosen_}, {"base", save_classifier(base())}};
}

void SelectedColumnsClassifier::load(const nlohmann::json& model) {
  input_columns_ = model.at("input_columns").get<int>();
  chosen_ = model.at("columns").get<std::vector<int>>();
  for (int column : chosen_)
    if (column < 0 || column >= input_columns_)
      throw Error("model select", "column " + std::to_string(column) + " is outside the table's " +
                                      std::to_string(input_columns_) + " columns");
  fitted_ = load_classifier(model.at("base"));
}

std::unique_ptr<Classifier> make_select_classifier(const Parameters& parameters) {
  return std::make_unique<SelectedColumnsClassifier>(parameters);
}

}  // namespace tactile::ml

#pragma once
// `select`: a classifier that learns from some of the table's columns only, chosen inside
// each training fold, so the choice never sees a test row. Two ways, combinable:
//   columns=A-B[+C-D...]  a fixed block of columns (0-based, inclusive), e.g. the columns of
//                         one pipeline in a table that holds several (the pipeline search)
//   k=N                   of those, the N with the largest one-way ANOVA F statistic on the
//                         training rows (ties: the lower column), for tables whose columns
//                         outnumber their rows; k=0 or absent keeps them all
//   base=SPEC             the classifier fitted on the chosen columns; ';' stands for ','
//                         inside it, e.g. base=knn:k=3;standardize=true
// Scores and predictions are the base's on the chosen columns.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tactile/ml/classifier.h"

namespace tactile::ml {

// One-way ANOVA F of each column of x between the classes of y (class_count groups): the
// between-class mean square over the within-class mean square. A constant column scores 0;
// a column that separates the classes perfectly (no within-class spread) scores +infinity.
Vector anova_f(const Matrix& x, const std::vector<int>& y, int class_count);
// The k columns with the largest F (ties: the lower column), ascending.
std::vector<int> top_columns(const Vector& f, int k);

class SelectedColumnsClassifier : public Classifier {
 public:
  // Throws tactile::Error naming the parameter on a malformed block, a negative k, a missing
  // or unknown base.
  explicit SelectedColumnsClassifier(const Parameters& parameters);
  std::string name() const override { return "select"; }
  Parameters parameters() const override;
  void fit(const Matrix& x, const std::vector<int>& y, int class_count, uint64_t seed) override;
  Matrix scores(const Matrix& x) const override;
  std::vector<int> predict(const Matrix& x) const override;
  Decisions decide(const Matrix& x) const override;
  nlohmann::json save() const override;
  void load(const nlohmann::json& model) override;

  // The columns the last fit kept, ascending.
  const std::vector<int>& chosen_columns() const { return chosen_; }

 private:
  Matrix chosen_part(const Matrix& x) const;
  const Classifier& base() const;

  std::string block_text_;  // as given, "" = every column
  std::vector<std::pair<int, int>> blocks_;
  int64_t k_ = 0;
  std::string base_;  // with ',' (make_classifier's form)
  std::vector<int> chosen_;
  int input_columns_ = 0;
  std::unique_ptr<Classifier> fitted_;
};

std::unique_ptr<Classifier> make_select_classifier(const Parameters& parameters);

}  // namespace tactile::ml

// Agreement between two annotators, on a hand-computed case.
#include <gtest/gtest.h>

#include "tactile/labels/agreement.h"

namespace tactile {
namespace {

Label span(double t0, double t1, std::string class_name) {
  Label label;
  label.recording = std::string(1, 'r');
  label.t0 = t0;
  label.t1 = t1;
  label.class_name = std::move(class_name);
  return label;
}

TEST(Agreement, KappaOverTimeSegmentsAtIouAndTheirClasses) {
  // 100 samples at 10 Hz. A: pat [1, 3), slap [5, 7). B: pat [1, 3), stroke [5.5, 7)
  // (IoU 0.75 with A's slap), an extra pat [8, 9).
  // Samples (A, B): (pat, pat) 20, (slap, none) 5, (slap, stroke) 15, (none, pat) 10,
  // (none, none) 50. Observed 0.70; chance 0.2 x 0.3 + 0.6 x 0.55 = 0.39;
  // kappa = 0.31 / 0.61.
  const Agreement agreement = compute_agreement(
      {span(1, 3, "pat"), span(5, 7, "slap")},
      {span(1, 3, "pat"), span(5.5, 7, "stroke"), span(8, 9, "pat")}, {{"r", {0.0, 10.0, 10.0}}});
  EXPECT_EQ(agreement.samples, 100);
  EXPECT_NEAR(agreement.observed, 0.70, 1e-12);
  EXPECT_NEAR(agreement.expected, 0.39, 1e-12);
  EXPECT_NEAR(agreement.kappa, 0.31 / 0.61, 1e-12);
  EXPECT_EQ(agreement.matched, 2);
  EXPECT_NEAR(agreement.precision, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(agreement.recall, 1.0, 1e-12);
  EXPECT_NEAR(agreement.f1, 0.8, 1e-12);
  EXPECT_EQ(agreement.classes, (std::vector<std::string>{"pat", "slap", "stroke"}));
  EXPECT_EQ(agreement.confusion[0][0], 1);  // pat - pat
  EXPECT_EQ(agreement.confusion[1][2], 1);  // slap - stroke
  ASSERT_EQ(agreement.disagreements.size(), 2u);
  EXPECT_EQ(agreement.disagreements[0].kind, "class");
  EXPECT_EQ(agreement.disagreements[0].a_class, "slap");
  EXPECT_EQ(agreement.disagreements[0].b_class, "stroke");
  EXPECT_EQ(agreement.disagreements[1].kind, "extra");
  EXPECT_DOUBLE_EQ(agreement.disagreements[1].t0, 8.0);
}

TEST(Agreement, IdenticalAnnotationsAgreeFully) {
  const std::vector<Label> labels = {span(1, 2, "pat"), span(4, 6, "slap")};
  const Agreement agreement = compute_agreement(labels, labels, {{"r", {0.0, 10.0, 100.0}}});
  EXPECT_DOUBLE_EQ(agreement.kappa, 1.0);
  EXPECT_DOUBLE_EQ(agreement.f1, 1.0);
  EXPECT_TRUE(agreement.disagreements.empty());
  EXPECT_DOUBLE_EQ(time_iou(span(0, 2, "a"), span(1, 3, "b")), 1.0 / 3.0);
}

}  // namespace
}  // namespace tactile

// Quality checks of labels: overlap in a lane and region, implausible durations,
// segmenter events without a label, classes outside the vocabulary.
#include <gtest/gtest.h>

#include "tactile/labels/quality.h"

namespace tactile {
namespace {

Label make(int64_t id, double t0, double t1, std::string class_name, LabelSource source,
           std::string annotator, std::string region = std::string("all")) {
  Label label;
  label.id = id;
  label.recording = std::string(1, 'r');
  label.t0 = t0;
  label.t1 = t1;
  label.class_name = std::move(class_name);
  label.source = source;
  label.annotator = std::move(annotator);
  label.region = std::move(region);
  return label;
}

TEST(LabelQuality, EachKindOfIssueIsFoundAndNamed) {
  const std::vector<Label> labels = {
      // Ground truth: pat lasts about 1 s.
      make(1, 0, 1, "pat", LabelSource::kGroundTruth, "sim"),
      make(2, 2, 3, "pat", LabelSource::kGroundTruth, "sim"),
      make(3, 4, 5.1, "pat", LabelSource::kGroundTruth, "sim"),
      // ana: two overlapping labels on one region (an issue), one on another region
      // at the same time (multi-touch, fine), one far too long.
      make(4, 10, 11, "pat", LabelSource::kManual, "ana", "left"),
      make(5, 10.5, 11.5, "pat", LabelSource::kManual, "ana", "left"),
      make(6, 10.5, 11.5, "pat", LabelSource::kManual, "ana", "right"),
      make(7, 20, 30, "pat", LabelSource::kManual, "ana"),
      // A segmenter event nobody labelled, one that is labelled.
      make(8, 40, 41, "unknown", LabelSource::kSegmenter, "segmenter:threshold"),
      make(9, 2.1, 2.9, "unknown", LabelSource::kSegmenter, "segmenter:threshold"),
      // A class outside the vocabulary.
      make(10, 50, 51, "pet", LabelSource::kManual, "bob"),
  };
  QualityOptions options;
  options.vocabulary = {"pat", "slap"};
  const std::vector<LabelIssue> issues = check_labels(labels, options);
  std::vector<std::pair<std::string, int64_t>> found;
  for (const LabelIssue& issue : issues) found.emplace_back(issue.kind, issue.label);
  EXPECT_EQ(found, (std::vector<std::pair<std::string, int64_t>>{
                       {"overlap", 5}, {"duration", 7}, {"unlabelled", 8}, {"vocabulary", 10}}));
  EXPECT_NE(issues[0].what.find("overlaps label 4 in lane manual:ana, region left"),
            std::string::npos)
      << issues[0].what;
}

// With its recording's span known, a label that starts before the first sample, ends after
// the last one's period or is shorter than one sample is reported; one that ends exactly at the
// end is not.
TEST(LabelQuality, LabelsOutsideTheirRecordingOrShorterThanASampleAreReported) {
  const std::vector<Label> labels = {
      make(1, 0.0, 10.0, "pat", LabelSource::kManual, "ana"),                // the whole recording
      make(2, -0.5, 1.0, "pat", LabelSource::kManual, "ana"),                // before its start
      make(3, 9.5, 10.5, "pat", LabelSource::kManual, "ana"),                // after its end
      make(4, 0.8999999999999986, 0.9, "pat", LabelSource::kManual, "ana"),  // a sliver
  };
  QualityOptions options;
  options.spans["r"] = {0.0, 10.0, 0.01};
  std::vector<std::string> found;
  for (const LabelIssue& issue : check_labels(labels, options))
    if (issue.kind == "outside" || issue.kind == "short")
      found.push_back(issue.kind + " " + std::to_string(issue.label));
  EXPECT_EQ(found, (std::vector<std::string>{"outside 2", "short 4", "outside 3"}));
  // Without the span (the recording is not known) nothing of the kind is said.
  options.spans.clear();
  for (const LabelIssue& issue : check_labels(labels, options))
    EXPECT_TRUE(issue.kind != "outside" && issue.kind != "short") << issue.what;
  // The words name the label and the recording's end in full.
  EXPECT_EQ(span_problem(labels[2], {0.0, 10.0, 0.01}).what,
            "label 3 (pat, 9.5 s to 10.5 s) ends after its recording's end at 10.000 s");
}

}  // namespace
}  // namespace tactile

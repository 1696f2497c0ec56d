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

}  // namespace
}  // namespace tactile

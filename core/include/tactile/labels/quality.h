#pragma once
// Quality checks of a store's labels (`tactile labels check`, the QA panel): labels
// that overlap within one lane and region, durations outside the class's plausible
// range, segmenter events no label covers, classes outside the vocabulary.

#include <set>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

struct LabelIssue {
  std::string kind;  // "overlap", "duration", "unlabelled", "vocabulary"
  std::string recording;
  double t0 = 0.0, t1 = 0.0;
  int64_t label = 0;  // the label concerned (the later one of an overlap)
  std::string what;
};

struct QualityOptions {
  // A class's plausible durations: from `short_factor` to `long_factor` times the
  // median duration of its ground-truth labels (of all its labels when the store has
  // no ground truth for it); classes with fewer than 3 labels are not judged.
  double short_factor = 0.25;
  double long_factor = 4.0;
  // The vocabulary; empty: not checked. The segmenters' "unknown" is always allowed.
  std::set<std::string> vocabulary;
};

std::vector<LabelIssue> check_labels(const std::vector<Label>& labels,
                                     const QualityOptions& options);

}  // namespace tactile

#pragma once
// Quality checks of a store's labels (`tactile labels check`, the QA panel): labels
// that overlap within one lane and region, durations outside the class's plausible
// range, segmenter events no label covers, classes outside the vocabulary, and (where the
// recording is known) labels outside their recording or shorter than one of its samples.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"

namespace tactile {

// What a label of a recording must lie within: the time its samples cover (every stream's,
// on the recording's clock, as labels are) and its shortest sample period.
struct RecordingSpan {
  double start = 0.0;
  double end = 0.0;
  double sample_period = 0.0;  // of its fastest regularly sampled stream; 0: none
};
RecordingSpan recording_span(const Recording& recording);
// The span of the recording file at `path` (its streams' headers; no samples are read).
RecordingSpan recording_span(const std::string& path);

// Why `label` does not fit its recording's `span`: "outside" (it starts before the first
// sample or ends after the last one's period) or "short" (shorter than one sample period), with
// the words to say it; an empty kind when it fits.
struct SpanProblem {
  std::string kind;
  std::string what;
};
SpanProblem span_problem(const Label& label, const RecordingSpan& span);

struct LabelIssue {
  std::string kind;  // "overlap", "duration", "unlabelled", "vocabulary", "outside", "short"
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
  // The spans of the recordings known (by recording id); the labels of the others are not
  // checked against their recording.
  std::map<std::string, RecordingSpan> spans;
};

std::vector<LabelIssue> check_labels(const std::vector<Label>& labels,
                                     const QualityOptions& options);

}  // namespace tactile

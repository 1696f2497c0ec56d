#pragma once
// Agreement between two annotators (or an annotator and ground truth) on the same
// recordings: Cohen's kappa over time (each sample of the recording has the class of
// the label covering it, or "none"), segment-level precision, recall and F1 at
// IoU >= a threshold (B's segments against A's as the reference), the confusion of
// the classes of matched segments, and the disagreements one by one.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

// Where a recording's samples lie in time: [start, end) at rate_hz.
struct RecordingTiming {
  double start = 0.0;
  double end = 0.0;
  double rate_hz = 100.0;
};

struct Disagreement {
  std::string recording;
  double t0 = 0.0, t1 = 0.0;
  std::string a_class, b_class;  // "" for a segment the other side does not have
  std::string kind;              // "class", "missed" (only in A), "extra" (only in B)
};

struct Agreement {
  // Over time samples: Cohen's kappa, observed and chance agreement.
  double kappa = 0.0, observed = 0.0, expected = 0.0;
  int64_t samples = 0;
  // Segments: B's against A's at IoU >= threshold, matched one to one (best IoU first).
  int64_t a_segments = 0, b_segments = 0, matched = 0;
  double precision = 0.0, recall = 0.0, f1 = 0.0;
  // Classes of matched segments: rows A's class, columns B's, over `classes`.
  std::vector<std::string> classes;
  std::vector<std::vector<int64_t>> confusion;
  std::vector<Disagreement> disagreements;  // by recording and time
};

// `timing` gives each recording's span and rate; a recording missing from it is
// sampled at 100 Hz over the span of its labels.
Agreement compute_agreement(const std::vector<Label>& a, const std::vector<Label>& b,
                            const std::map<std::string, RecordingTiming>& timing,
                            double iou_threshold = 0.5);

// Intersection over union of two time spans.
double time_iou(const Label& x, const Label& y);

}  // namespace tactile

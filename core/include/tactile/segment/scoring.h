#pragma once
// Scores of a segmentation against ground truth, for benchmarks and tests.
//
// Frames: frame t (its time stamp start_time + t / rate) is a touch frame of a label list
// when some label holds it (t0 <= time < t1); precision, recall and F1 count frames.
// Events, one to one: a detected segment and a true touch may match when their intervals
// overlap with an intersection over union above `min_iou` (0: any overlap); the pairs are
// taken greedily, the largest IoU first (ties: the earlier touch, then the earlier segment),
// each segment and each touch at most once. Matched pairs are hits, detected segments left
// over false alarms, touches left over misses. So a segment spanning two touches is one hit
// and one miss, and a touch split in two segments one hit and one false alarm.

#include <cstdint>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

struct DetectionScore {
  int64_t hits = 0;          // true positives
  int64_t false_alarms = 0;  // false positives
  int64_t misses = 0;        // false negatives
  // 1 when there was nothing to find and nothing was found.
  double precision() const;
  double recall() const;
  double f1() const;
  DetectionScore& operator+=(const DetectionScore& other);
};

// Frames 0..frames-1 at `rate_hz` from `start_time`, labels of one recording (regions ignored).
DetectionScore score_frames(const std::vector<Label>& detected, const std::vector<Label>& truth,
                            double start_time, double rate_hz, int64_t frames);
DetectionScore score_events(const std::vector<Label>& detected, const std::vector<Label>& truth,
                            double min_iou = 0.0);

// Labelled touches against a segmentation, as people's labels are scored
// (shared/data/inflatable-grid-dev/README.md): each labelled touch, in time order, is matched
// to at most one segment, the one that overlaps it most and is not yet used (ties: the
// earlier segment); unmatched touches are misses, unmatched segments false alarms. A touch
// is split when two or more segments overlap it, merged when a segment that overlaps it
// overlaps another touch too.
struct TouchScore {
  DetectionScore frames;
  DetectionScore events;
  int64_t touches = 0;
  int64_t segments = 0;
  int64_t split = 0;   // touches that two or more segments overlap
  int64_t merged = 0;  // touches that share a segment with another touch
  TouchScore& operator+=(const TouchScore& other);
};

// One recording's segments and labelled touches (regions ignored); frames as score_frames.
TouchScore score_touches(const std::vector<Label>& detected, const std::vector<Label>& truth,
                         double start_time, double rate_hz, int64_t frames);

}  // namespace tactile

#pragma once
// Labels as the workbench's timeline shows them: one lane per tier (ground truth, each
// manual annotator, each segmenter method, each model), each lane indexed by time so
// that drawing costs what is visible, never the number of labels: a view of a lane
// with 100,000 labels is answered per pixel column from the index.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

// The tier a label belongs to: its source and, except for ground truth, its annotator
// (a manual annotator's name, "segmenter:METHOD", a model's name).
struct LaneKey {
  LabelSource source = LabelSource::kManual;
  std::string annotator;  // "" for ground truth
  bool operator==(const LaneKey&) const = default;
  // "ground-truth", "manual:ana", "segmenter:threshold", "model:svm", ... (settings keys)
  std::string id() const;
  // What a lane header shows: "ground truth", "ana", "threshold", "model svm".
  std::string title() const;
};

LaneKey lane_of(const Label& label);
// The lane a lane id names (LaneKey::id's inverse): "ground-truth", "manual:NAME",
// "segmenter:METHOD", "model:NAME"; anything else is a manual annotator of that name.
LaneKey lane_from_id(const std::string& id);

// One lane's labels sorted by start, with the running maximum of their ends, so that
// the labels meeting a time range are found by two binary searches.
class LaneIndex {
 public:
  LaneIndex() = default;
  explicit LaneIndex(std::vector<Label> labels);

  const std::vector<Label>& labels() const { return labels_; }
  size_t size() const { return labels_.size(); }

  // Indices (into labels()) of the labels that meet [t0, t1), in start order.
  std::vector<size_t> meeting(double t0, double t1) const;
  // How many labels meet [t0, t1), without listing them when there are more than
  // `limit` (the caller then draws per pixel column).
  size_t count_meeting(double t0, double t1, size_t limit) const;
  // A label that covers some of [t0, t1), or -1: the one starting last before t1 if it
  // reaches into the range, else the longest-reaching earlier one.
  int64_t any_meeting(double t0, double t1) const;
  // The label containing time t (the latest-starting one), or -1.
  int64_t at(double t) const;
  // The next label starting after t / the previous one starting before t, or -1.
  int64_t next_after(double t) const;
  int64_t previous_before(double t) const;

 private:
  std::vector<Label> labels_;
  std::vector<double> starts_;
  std::vector<double> reach_;        // reach_[k] = max end of labels_[0..k]
  std::vector<size_t> reach_label_;  // which label reaches that far
};

// A run of pixel columns [first, last) drawn for one label (in a dense lane, the
// label that covers those columns; shorter ones under it merge into it).
struct LaneSpan {
  int first = 0;
  int last = 0;
  size_t label = 0;  // index into LaneIndex::labels()
};

// The spans of a lane over [t0, t1) drawn `columns` pixels wide: one per visible label
// when they are fewer than the columns, else one per run of columns that the same
// label covers (a dense lane costs columns x log(labels), not labels).
std::vector<LaneSpan> lane_spans(const LaneIndex& lane, double t0, double t1, int columns);

// Labels grouped into lanes, in a stable order: ground truth, manual annotators,
// segmenters, models (each by name).
struct Lanes {
  std::vector<LaneKey> keys;
  std::vector<LaneIndex> lanes;
  // The lane of `key`, or -1.
  int find(const LaneKey& key) const;
};

Lanes group_into_lanes(const std::vector<Label>& labels);

}  // namespace tactile

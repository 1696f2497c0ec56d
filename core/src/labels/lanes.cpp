#include "tactile/labels/lanes.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace tactile {

std::string LaneKey::id() const {
  if (source == LabelSource::kGroundTruth) return "ground-truth";
  // A segmenter's annotator already says so ("segmenter:METHOD").
  if (source == LabelSource::kSegmenter && annotator.starts_with("segmenter:")) return annotator;
  return std::string(to_string(source)) + ":" + annotator;
}

std::string LaneKey::title() const {
  switch (source) {
    case LabelSource::kGroundTruth:
      return "ground truth";
    case LabelSource::kSegmenter:
      return annotator.starts_with("segmenter:") ? annotator.substr(10) : annotator;
    case LabelSource::kModel:
      return "model " + annotator;
    case LabelSource::kManual:
      break;
  }
  return annotator;
}

LaneKey lane_of(const Label& label) {
  if (label.source == LabelSource::kGroundTruth) return {label.source, ""};
  return {label.source, label.annotator};
}

LaneKey lane_from_id(const std::string& id) {
  if (id == "ground-truth") return {LabelSource::kGroundTruth, ""};
  if (id.starts_with("manual:")) return {LabelSource::kManual, id.substr(7)};
  if (id.starts_with("segmenter:")) return {LabelSource::kSegmenter, id};
  if (id.starts_with("model:")) return {LabelSource::kModel, id.substr(6)};
  return {LabelSource::kManual, id};
}

LaneIndex::LaneIndex(std::vector<Label> labels) : labels_(std::move(labels)) {
  std::stable_sort(labels_.begin(), labels_.end(), [](const Label& a, const Label& b) {
    return std::tie(a.t0, a.t1, a.id) < std::tie(b.t0, b.t1, b.id);
  });
  starts_.reserve(labels_.size());
  reach_.reserve(labels_.size());
  reach_label_.reserve(labels_.size());
  for (size_t k = 0; k < labels_.size(); ++k) {
    starts_.push_back(labels_[k].t0);
    if (k == 0 || labels_[k].t1 > reach_.back()) {
      reach_.push_back(labels_[k].t1);
      reach_label_.push_back(k);
    } else {
      reach_.push_back(reach_.back());
      reach_label_.push_back(reach_label_.back());
    }
  }
}

std::vector<size_t> LaneIndex::meeting(double t0, double t1) const {
  std::vector<size_t> found;
  // Labels starting before t1; among them those whose end is after t0. reach_ is
  // non-decreasing, so the first label that can reach t0 is found by binary search.
  const size_t end =
      static_cast<size_t>(std::lower_bound(starts_.begin(), starts_.end(), t1) - starts_.begin());
  const size_t begin = static_cast<size_t>(
      std::upper_bound(reach_.begin(), reach_.begin() + static_cast<std::ptrdiff_t>(end), t0) -
      reach_.begin());
  for (size_t k = begin; k < end; ++k)
    if (labels_[k].t1 > t0) found.push_back(k);
  return found;
}

size_t LaneIndex::count_meeting(double t0, double t1, size_t limit) const {
  const size_t end =
      static_cast<size_t>(std::lower_bound(starts_.begin(), starts_.end(), t1) - starts_.begin());
  const size_t begin = static_cast<size_t>(
      std::upper_bound(reach_.begin(), reach_.begin() + static_cast<std::ptrdiff_t>(end), t0) -
      reach_.begin());
  if (end - begin > limit) return end - begin;  // at least this many candidates
  size_t count = 0;
  for (size_t k = begin; k < end; ++k) count += labels_[k].t1 > t0;
  return count;
}

int64_t LaneIndex::any_meeting(double t0, double t1) const {
  const auto end = std::lower_bound(starts_.begin(), starts_.end(), t1) - starts_.begin();
  if (end == 0) return -1;
  const auto last = static_cast<size_t>(end - 1);
  if (labels_[last].t1 > t0) return static_cast<int64_t>(last);
  if (reach_[last] > t0) return static_cast<int64_t>(reach_label_[last]);
  return -1;
}

int64_t LaneIndex::at(double t) const {
  const auto end = std::upper_bound(starts_.begin(), starts_.end(), t) - starts_.begin();
  for (auto k = end - 1; k >= 0; --k) {
    if (labels_[static_cast<size_t>(k)].t1 > t) return k;
    if (reach_[static_cast<size_t>(k)] <= t) break;  // nothing earlier reaches t
  }
  return -1;
}

int64_t LaneIndex::next_after(double t) const {
  const auto k = std::upper_bound(starts_.begin(), starts_.end(), t) - starts_.begin();
  return k < static_cast<std::ptrdiff_t>(starts_.size()) ? k : -1;
}

int64_t LaneIndex::previous_before(double t) const {
  const auto k = std::lower_bound(starts_.begin(), starts_.end(), t) - starts_.begin();
  return k - 1;
}

std::vector<LaneSpan> lane_spans(const LaneIndex& lane, double t0, double t1, int columns) {
  std::vector<LaneSpan> spans;
  if (columns <= 0 || !(t1 > t0)) return spans;
  const double per_column = (t1 - t0) / columns;
  auto column_of = [&](double t) {
    return static_cast<int>(std::clamp((t - t0) / per_column, 0.0, static_cast<double>(columns)));
  };
  const auto limit = static_cast<size_t>(columns) / 2;
  if (lane.count_meeting(t0, t1, limit) <= limit) {
    for (size_t k : lane.meeting(t0, t1)) {
      const Label& label = lane.labels()[k];
      const int first = column_of(label.t0);
      spans.push_back({first, std::max(first + 1, column_of(label.t1)), k});
    }
    return spans;
  }
  // Dense: per pixel column, the label that covers it; runs of one label merge.
  for (int column = 0; column < columns; ++column) {
    const double a = t0 + column * per_column;
    const int64_t label = lane.any_meeting(a, a + per_column);
    if (label < 0) continue;
    const auto index = static_cast<size_t>(label);
    if (!spans.empty() && spans.back().last == column && spans.back().label == index)
      spans.back().last = column + 1;
    else
      spans.push_back({column, column + 1, index});
  }
  return spans;
}

int Lanes::find(const LaneKey& key) const {
  for (size_t k = 0; k < keys.size(); ++k)
    if (keys[k] == key) return static_cast<int>(k);
  return -1;
}

Lanes group_into_lanes(const std::vector<Label>& labels) {
  auto rank = [](LabelSource source) {
    switch (source) {
      case LabelSource::kGroundTruth:
        return 0;
      case LabelSource::kManual:
        return 1;
      case LabelSource::kSegmenter:
        return 2;
      case LabelSource::kModel:
        return 3;
    }
    return 4;
  };
  std::map<std::pair<int, std::string>, std::vector<Label>> grouped;
  for (const Label& label : labels) {
    const LaneKey key = lane_of(label);
    grouped[{rank(key.source), key.annotator}].push_back(label);
  }
  Lanes lanes;
  for (auto& [order, members] : grouped) {
    lanes.keys.push_back(lane_of(members.front()));
    lanes.lanes.emplace_back(std::move(members));
  }
  return lanes;
}

}  // namespace tactile

#include "tactile/labels/agreement.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "tactile/labels/lanes.h"

namespace tactile {

namespace {

constexpr const char* kNone = "none";

std::map<std::string, std::vector<Label>> by_recording(const std::vector<Label>& labels) {
  std::map<std::string, std::vector<Label>> grouped;
  for (const Label& label : labels) grouped[label.recording].push_back(label);
  return grouped;
}

std::string class_at(const LaneIndex& lane, double t) {
  const int64_t index = lane.at(t);
  return index < 0 ? kNone : lane.labels()[static_cast<size_t>(index)].class_name;
}

}  // namespace

double time_iou(const Label& x, const Label& y) {
  const double overlap = std::min(x.t1, y.t1) - std::max(x.t0, y.t0);
  if (overlap <= 0) return 0.0;
  const double united = std::max(x.t1, y.t1) - std::min(x.t0, y.t0);
  return united > 0 ? overlap / united : 0.0;
}

Agreement compute_agreement(const std::vector<Label>& a, const std::vector<Label>& b,
                            const std::map<std::string, RecordingTiming>& timing,
                            double iou_threshold) {
  Agreement result;
  const auto a_by = by_recording(a), b_by = by_recording(b);
  std::set<std::string> recordings;
  for (const auto& [name, labels] : a_by) recordings.insert(name);
  for (const auto& [name, labels] : b_by) recordings.insert(name);
  std::set<std::string> class_set;
  for (const Label& label : a) class_set.insert(label.class_name);
  for (const Label& label : b) class_set.insert(label.class_name);
  result.classes.assign(class_set.begin(), class_set.end());
  const size_t n = result.classes.size();
  result.confusion.assign(n, std::vector<int64_t>(n, 0));
  auto class_index = [&](const std::string& name) {
    return static_cast<size_t>(
        std::lower_bound(result.classes.begin(), result.classes.end(), name) -
        result.classes.begin());
  };
  // Time samples: a joint table of A's class x B's class, "none" included.
  std::map<std::pair<std::string, std::string>, int64_t> joint;
  static const std::vector<Label> kEmpty;
  for (const std::string& recording : recordings) {
    const auto a_found = a_by.find(recording), b_found = b_by.find(recording);
    const std::vector<Label>& a_labels = a_found == a_by.end() ? kEmpty : a_found->second;
    const std::vector<Label>& b_labels = b_found == b_by.end() ? kEmpty : b_found->second;
    RecordingTiming span;
    if (const auto known = timing.find(recording); known != timing.end()) {
      span = known->second;
    } else {
      span.start = 1e300, span.end = -1e300;
      for (const auto* labels : {&a_labels, &b_labels})
        for (const Label& label : *labels)
          span.start = std::min(span.start, label.t0), span.end = std::max(span.end, label.t1);
    }
    const LaneIndex a_lane(a_labels), b_lane(b_labels);
    if (span.rate_hz > 0 && span.end > span.start) {
      const auto count = static_cast<int64_t>(std::floor((span.end - span.start) * span.rate_hz));
      for (int64_t k = 0; k < count; ++k) {
        const double t = span.start + (static_cast<double>(k) + 0.5) / span.rate_hz;
        ++joint[{class_at(a_lane, t), class_at(b_lane, t)}];
      }
    }
    // Segments: all pairs above the threshold, best IoU first, one to one.
    std::vector<std::tuple<double, size_t, size_t>> pairs;
    for (size_t i = 0; i < a_labels.size(); ++i)
      for (size_t j = 0; j < b_labels.size(); ++j) {
        const double iou = time_iou(a_labels[i], b_labels[j]);
        if (iou >= iou_threshold) pairs.emplace_back(iou, i, j);
      }
    std::sort(pairs.begin(), pairs.end(),
              [](const auto& x, const auto& y) { return std::get<0>(x) > std::get<0>(y); });
    std::vector<char> a_used(a_labels.size(), 0), b_used(b_labels.size(), 0);
    for (const auto& [iou, i, j] : pairs) {
      if (a_used[i] || b_used[j]) continue;
      a_used[i] = b_used[j] = 1;
      ++result.matched;
      const Label& x = a_labels[i];
      const Label& y = b_labels[j];
      ++result.confusion[class_index(x.class_name)][class_index(y.class_name)];
      if (x.class_name != y.class_name)
        result.disagreements.push_back({recording, std::min(x.t0, y.t0), std::max(x.t1, y.t1),
                                        x.class_name, y.class_name, "class"});
    }
    for (size_t i = 0; i < a_labels.size(); ++i)
      if (!a_used[i])
        result.disagreements.push_back(
            {recording, a_labels[i].t0, a_labels[i].t1, a_labels[i].class_name, "", "missed"});
    for (size_t j = 0; j < b_labels.size(); ++j)
      if (!b_used[j])
        result.disagreements.push_back(
            {recording, b_labels[j].t0, b_labels[j].t1, "", b_labels[j].class_name, "extra"});
    result.a_segments += static_cast<int64_t>(a_labels.size());
    result.b_segments += static_cast<int64_t>(b_labels.size());
  }
  // Cohen's kappa from the joint table.
  std::map<std::string, int64_t> a_marginal, b_marginal;
  int64_t agree = 0;
  for (const auto& [pair, count] : joint) {
    result.samples += count;
    a_marginal[pair.first] += count;
    b_marginal[pair.second] += count;
    if (pair.first == pair.second) agree += count;
  }
  if (result.samples > 0) {
    const auto total = static_cast<double>(result.samples);
    result.observed = static_cast<double>(agree) / total;
    for (const auto& [name, count] : a_marginal) {
      const auto other = b_marginal.find(name);
      if (other != b_marginal.end())
        result.expected +=
            (static_cast<double>(count) / total) * (static_cast<double>(other->second) / total);
    }
    result.kappa =
        result.expected < 1.0 ? (result.observed - result.expected) / (1.0 - result.expected) : 1.0;
  }
  result.precision =
      result.b_segments > 0 ? static_cast<double>(result.matched) / result.b_segments : 0.0;
  result.recall =
      result.a_segments > 0 ? static_cast<double>(result.matched) / result.a_segments : 0.0;
  result.f1 = result.precision + result.recall > 0
                  ? 2 * result.precision * result.recall / (result.precision + result.recall)
                  : 0.0;
  std::sort(result.disagreements.begin(), result.disagreements.end(),
            [](const Disagreement& x, const Disagreement& y) {
              return std::tie(x.recording, x.t0) < std::tie(y.recording, y.t0);
            });
  return result;
}

}  // namespace tactile

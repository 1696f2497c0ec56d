#include "tactile/segment/scoring.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "tactile/error.h"

namespace tactile {

namespace {

// The frames a label list holds, as one flag per frame.
std::vector<uint8_t> scoring_frame_mask(const std::vector<Label>& labels, double start_time,
                                        double rate_hz, int64_t frames) {
  std::vector<uint8_t> mask(static_cast<size_t>(frames), 0);
  for (const Label& label : labels) {
    // The first frame whose time is >= t0, and the first whose time is >= t1.
    const auto first = static_cast<int64_t>(std::ceil((label.t0 - start_time) * rate_hz - 1e-9));
    const auto end = static_cast<int64_t>(std::ceil((label.t1 - start_time) * rate_hz - 1e-9));
    for (int64_t t = std::max<int64_t>(0, first); t < std::min(end, frames); ++t)
      mask[static_cast<size_t>(t)] = 1;
  }
  return mask;
}

double scoring_ratio(int64_t part, int64_t whole) {
  return whole == 0 ? 1.0 : static_cast<double>(part) / static_cast<double>(whole);
}

}  // namespace

double DetectionScore::precision() const { return scoring_ratio(hits, hits + false_alarms); }
double DetectionScore::recall() const { return scoring_ratio(hits, hits + misses); }
double DetectionScore::f1() const {
  return scoring_ratio(2 * hits, 2 * hits + false_alarms + misses);
}

DetectionScore& DetectionScore::operator+=(const DetectionScore& other) {
  hits += other.hits;
  false_alarms += other.false_alarms;
  misses += other.misses;
  return *this;
}

DetectionScore score_frames(const std::vector<Label>& detected, const std::vector<Label>& truth,
                            double start_time, double rate_hz, int64_t frames) {
  if (!(rate_hz > 0)) throw Error("score_frames", "needs a positive sample rate");
  const std::vector<uint8_t> found = scoring_frame_mask(detected, start_time, rate_hz, frames);
  const std::vector<uint8_t> wanted = scoring_frame_mask(truth, start_time, rate_hz, frames);
  DetectionScore score;
  for (size_t t = 0; t < found.size(); ++t) {
    score.hits += found[t] && wanted[t];
    score.false_alarms += found[t] && !wanted[t];
    score.misses += !found[t] && wanted[t];
  }
  return score;
}

DetectionScore score_events(const std::vector<Label>& detected, const std::vector<Label>& truth,
                            double min_iou) {
  // Every overlapping pair: (IoU, touch, segment).
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t touch = 0; touch < truth.size(); ++touch)
    for (size_t segment = 0; segment < detected.size(); ++segment) {
      const Label& a = truth[touch];
      const Label& b = detected[segment];
      const double overlap = std::min(a.t1, b.t1) - std::max(a.t0, b.t0);
      if (!(overlap > 0)) continue;
      const double joined = std::max(a.t1, b.t1) - std::min(a.t0, b.t0);
      const double iou = overlap / joined;
      if (iou > min_iou) pairs.emplace_back(iou, touch, segment);
    }
  std::sort(pairs.begin(), pairs.end(), [&](const auto& x, const auto& y) {
    if (std::get<0>(x) != std::get<0>(y)) return std::get<0>(x) > std::get<0>(y);
    const double touch_x = truth[std::get<1>(x)].t0, touch_y = truth[std::get<1>(y)].t0;
    if (touch_x != touch_y) return touch_x < touch_y;
    return detected[std::get<2>(x)].t0 < detected[std::get<2>(y)].t0;
  });
  std::vector<uint8_t> touch_taken(truth.size(), 0), segment_taken(detected.size(), 0);
  DetectionScore score;
  for (const auto& [iou, touch, segment] : pairs) {
    if (touch_taken[touch] || segment_taken[segment]) continue;
    touch_taken[touch] = segment_taken[segment] = 1;
    ++score.hits;
  }
  score.false_alarms = static_cast<int64_t>(detected.size()) - score.hits;
  score.misses = static_cast<int64_t>(truth.size()) - score.hits;
  return score;
}

TouchScore& TouchScore::operator+=(const TouchScore& other) {
  frames += other.frames;
  events += other.events;
  touches += other.touches;
  segments += other.segments;
  split += other.split;
  merged += other.merged;
  return *this;
}

TouchScore score_touches(const std::vector<Label>& detected, const std::vector<Label>& truth,
                         double start_time, double rate_hz, int64_t frames) {
  TouchScore score;
  score.frames = score_frames(detected, truth, start_time, rate_hz, frames);
  score.touches = static_cast<int64_t>(truth.size());
  score.segments = static_cast<int64_t>(detected.size());
  std::vector<const Label*> touches, segments;
  for (const Label& label : truth) touches.push_back(&label);
  for (const Label& label : detected) segments.push_back(&label);
  const auto by_time = [](const Label* a, const Label* b) {
    return std::tie(a->t0, a->t1) < std::tie(b->t0, b->t1);
  };
  std::stable_sort(touches.begin(), touches.end(), by_time);
  std::stable_sort(segments.begin(), segments.end(), by_time);
  const auto overlap = [](const Label* a, const Label* b) {
    return std::min(a->t1, b->t1) - std::max(a->t0, b->t0);
  };
  std::vector<uint8_t> used(segments.size(), 0);
  std::vector<int64_t> touches_of_segment(segments.size(), 0);
  for (const Label* touch : touches) {
    size_t best = segments.size();
    int64_t overlapping = 0;
    for (size_t s = 0; s < segments.size(); ++s) {
      const double shared = overlap(touch, segments[s]);
      if (!(shared > 0)) continue;
      ++overlapping;
      ++touches_of_segment[s];
      if (!used[s] && (best == segments.size() || shared > overlap(touch, segments[best])))
        best = s;
    }
    if (overlapping >= 2) ++score.split;
    if (best < segments.size()) {
      used[best] = 1;
      ++score.events.hits;
    } else {
      ++score.events.misses;
    }
  }
  score.events.false_alarms = score.segments - score.events.hits;
  for (const Label* touch : touches)
    for (size_t s = 0; s < segments.size(); ++s)
      if (overlap(touch, segments[s]) > 0 && touches_of_segment[s] >= 2) {
        ++score.merged;
        break;
      }
  return score;
}

}  // namespace tactile

#include "tactile/labels/quality.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>

#include "tactile/io/hdf5_file.h"
#include "tactile/labels/lanes.h"
#include "tactile/stats/statistics.h"
#include "tactile/text.h"

namespace tactile {

namespace {

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f s", t);
  return text;
}

// Label times are written with a few digits (CSV, ELAN's milliseconds) and sums of periods
// are not exact: a label is not outside its recording by less than this.
constexpr double kSpanTolerance = 1e-6;

// The span of several streams: from the first one's start to the last one's end, with the
// shortest period of those sampled regularly (`rate_hz` 0: time-stamped, no period).
struct SpanWidener {
  RecordingSpan span;
  bool empty = true;
  void operator()(double start, double end, double rate_hz) {
    span.start = empty ? start : std::min(span.start, start);
    span.end = empty ? end : std::max(span.end, end);
    empty = false;
    if (rate_hz > 0.0 && (span.sample_period == 0.0 || 1.0 / rate_hz < span.sample_period))
      span.sample_period = 1.0 / rate_hz;
  }
};

}  // namespace

RecordingSpan recording_span(const Recording& recording) {
  SpanWidener widen;
  for (const Stream& stream : recording.streams)
    if (stream.sample_count() > 0) {
      const double start =
          stream.timestamps.empty() ? stream.start_time : stream.timestamps.front();
      widen(start, start + stream.duration(), stream.timestamps.empty() ? stream.rate_hz : 0.0);
    }
  return widen.span;
}

RecordingSpan recording_span(const std::string& path) {
  SpanWidener widen;
  const RecordingFile file(path);
  for (const StreamInfo& stream : file.streams())
    if (stream.sample_count > 0) {
      const double start = stream.has_timestamps ? stream.first_timestamp : stream.start_time;
      widen(start, start + stream.duration(), stream.has_timestamps ? 0.0 : stream.rate_hz);
    }
  return widen.span;
}

SpanProblem span_problem(const Label& label, const RecordingSpan& span) {
  // Times in full: a sliver of 1e-15 s must not read as "0.900 s to 0.900 s".
  const std::string which = "label " + (label.id > 0 ? std::to_string(label.id) + " " : "") + "(" +
                            label.class_name + ", " + shortest_text(label.t0) + " s to " +
                            shortest_text(label.t1) + " s)";
  if (label.t0 < span.start - kSpanTolerance)
    return {"outside",
            which + " starts before its recording's first sample at " + seconds(span.start)};
  if (label.t1 > span.end + kSpanTolerance)
    return {"outside", which + " ends after its recording's end at " + seconds(span.end)};
  if (span.sample_period > 0.0 && label.t1 - label.t0 < span.sample_period - kSpanTolerance)
    return {"short", which + " is shorter than one sample (" + seconds(span.sample_period) + ")"};
  return {};
}

std::vector<LabelIssue> check_labels(const std::vector<Label>& labels,
                                     const QualityOptions& options) {
  std::vector<LabelIssue> issues;
  // Overlaps within one lane, one recording and one region.
  std::map<std::tuple<std::string, std::string, std::string>, std::vector<const Label*>> groups;
  for (const Label& label : labels)
    groups[{label.recording, lane_of(label).id(), label.region}].push_back(&label);
  for (auto& [key, members] : groups) {
    std::sort(members.begin(), members.end(), [](const Label* a, const Label* b) {
      return std::tie(a->t0, a->id) < std::tie(b->t0, b->id);
    });
    const Label* reaching = nullptr;  // the earlier label that ends last
    for (const Label* label : members) {
      if (reaching && label->t0 < reaching->t1)
        issues.push_back({"overlap", label->recording, label->t0, std::min(label->t1, reaching->t1),
                          label->id,
                          "label " + std::to_string(label->id) + " overlaps label " +
                              std::to_string(reaching->id) + " in lane " + std::get<1>(key) +
                              ", region " + label->region});
      if (!reaching || label->t1 > reaching->t1) reaching = label;
    }
  }
  // Durations against each class's typical one.
  std::map<std::string, std::vector<double>> truth, all;
  for (const Label& label : labels) {
    if (label.class_name == kUnknownClass) continue;
    all[label.class_name].push_back(label.t1 - label.t0);
    if (label.source == LabelSource::kGroundTruth)
      truth[label.class_name].push_back(label.t1 - label.t0);
  }
  std::map<std::string, double> typical;
  for (const auto& [name, durations] : all) {
    const auto found = truth.find(name);
    const std::vector<double>& basis =
        found != truth.end() && found->second.size() >= 3 ? found->second : durations;
    if (basis.size() >= 3) typical[name] = stats::median(basis);
  }
  for (const Label& label : labels) {
    const auto found = typical.find(label.class_name);
    if (found == typical.end()) continue;
    const double duration = label.t1 - label.t0;
    if (duration < options.short_factor * found->second ||
        duration > options.long_factor * found->second)
      issues.push_back({"duration", label.recording, label.t0, label.t1, label.id,
                        "label " + std::to_string(label.id) + " (" + label.class_name + ") lasts " +
                            seconds(duration) + "; its class typically " + seconds(found->second)});
  }
  // Segmenter events that no ground-truth or manual label overlaps.
  std::map<std::string, std::vector<const Label*>> covering;
  for (const Label& label : labels)
    if (label.source == LabelSource::kGroundTruth || label.source == LabelSource::kManual)
      covering[label.recording].push_back(&label);
  for (const Label& label : labels) {
    if (label.source != LabelSource::kSegmenter) continue;
    const auto& candidates = covering[label.recording];
    const bool covered = std::any_of(candidates.begin(), candidates.end(), [&](const Label* other) {
      return other->t0 < label.t1 && other->t1 > label.t0;
    });
    if (!covered)
      issues.push_back({"unlabelled", label.recording, label.t0, label.t1, label.id,
                        "segmenter event " + std::to_string(label.id) + " (" + label.annotator +
                            ") has no label"});
  }
  // Labels outside their recording, or shorter than one of its samples.
  for (const Label& label : labels) {
    const auto span = options.spans.find(label.recording);
    if (span == options.spans.end()) continue;
    SpanProblem problem = span_problem(label, span->second);
    if (!problem.kind.empty())
      issues.push_back(
          {problem.kind, label.recording, label.t0, label.t1, label.id, std::move(problem.what)});
  }
  // Classes outside the vocabulary.
  if (!options.vocabulary.empty())
    for (const Label& label : labels)
      if (label.class_name != kUnknownClass && options.vocabulary.count(label.class_name) == 0)
        issues.push_back({"vocabulary", label.recording, label.t0, label.t1, label.id,
                          "label " + std::to_string(label.id) + " has class '" + label.class_name +
                              "', which is not in the vocabulary"});
  std::sort(issues.begin(), issues.end(), [](const LabelIssue& a, const LabelIssue& b) {
    return std::tie(a.recording, a.t0, a.kind) < std::tie(b.recording, b.t0, b.kind);
  });
  return issues;
}

}  // namespace tactile

#include "tactile/segment/threshold.h"

#include <algorithm>
#include <cmath>

#include "tactile/dsp/fur_preprocess.h"
#include "tactile/error.h"
#include "tactile/signal/taxel_values.h"

namespace tactile {

const char* to_string(SegmentEnd end) {
  switch (end) {
    case SegmentEnd::kQuiet:
      return "quiet";
    case SegmentEnd::kForced:
      return "forced";
    case SegmentEnd::kOpen:
      return "open";
  }
  return "open";
}

std::vector<SampleSegment> threshold_segments(const std::vector<uint8_t>& active,
                                              int64_t quiet_samples, int64_t max_samples) {
  std::vector<SampleSegment> segments;
  bool in_segment = false;
  int64_t start = 0;
  int64_t last = 0;
  const auto count = static_cast<int64_t>(active.size());
  for (int64_t t = 0; t < count; ++t) {
    if (!in_segment) {
      if (active[t]) {
        start = last = t;
        in_segment = true;
      }
      continue;
    }
    if (active[t]) last = t;
    if (t - start + 1 >= max_samples) {
      segments.push_back({start, t, SegmentEnd::kForced});
      in_segment = false;
    } else if (t - last >= quiet_samples) {
      segments.push_back({start, last, SegmentEnd::kQuiet});
      in_segment = false;
    }
  }
  if (in_segment) segments.push_back({start, last, SegmentEnd::kOpen});
  return segments;
}

std::vector<Label> segment_threshold(const Recording& recording, const SkinLayout& layout,
                                     const Parameters& parameters) {
  std::vector<std::string> known = dsp::fur_preprocess_keys();
  known.insert(known.end(), {"threshold", "quiet_seconds", "max_seconds", "keep_open"});
  parameters.expect_only(known);
  const double threshold = parameters.number("threshold", 0.1);
  const double quiet_seconds = parameters.number("quiet_seconds", 1.0);
  const double max_seconds = parameters.number("max_seconds", 4.0);
  const bool keep_open = parameters.flag("keep_open", true);
  if (!(threshold >= 0.0 && threshold < 1.0))
    throw Error(parameters.where(), "threshold must lie in [0, 1) (values are normalised)");
  if (!(quiet_seconds > 0.0)) throw Error(parameters.where(), "quiet_seconds must be positive");
  if (!(max_seconds > 0.0)) throw Error(parameters.where(), "max_seconds must be positive");

  const Recording normalised =
      dsp::fur_preprocess(recording, layout, dsp::fur_preprocess_options(parameters));
  const Stream& stream = dsp::fur_stream(normalised);
  const int64_t samples = stream.sample_count();
  // Q = 1 s · fs and L_max = 4 s · fs samples at the defaults (15 and 60 at 15 Hz).
  const auto quiet_samples = std::max<int64_t>(1, std::llround(quiet_seconds * stream.rate_hz));
  const auto max_samples = std::max<int64_t>(1, std::llround(max_seconds * stream.rate_hz));

  // active(t) = max_c v_c(t) > threshold; a missing sample is not a contact.
  std::vector<uint8_t> active(samples, 0);
  for (Eigen::Index column = 0; column < stream.samples.cols(); ++column) {
    const float* values = stream.samples.col(column).data();
    for (int64_t t = 0; t < samples; ++t) active[t] |= values[t] > threshold;
  }

  // Region groups and the stream columns of their cells.
  std::vector<const Group*> regions;
  std::vector<std::vector<int>> region_columns;
  const std::vector<int> columns = taxel_columns(layout, stream.channels, 0);
  for (const Group& group : layout.groups) {
    if (group.kind != "region") continue;
    std::vector<int> member_columns;
    for (size_t k = 0; k < layout.taxels.size(); ++k)
      if (columns[k] >= 0 && std::find(group.taxels.begin(), group.taxels.end(),
                                       layout.taxels[k].id) != group.taxels.end())
        member_columns.push_back(columns[k]);
    regions.push_back(&group);
    region_columns.push_back(std::move(member_columns));
  }

  std::vector<Label> labels;
  for (const SampleSegment& segment : threshold_segments(active, quiet_samples, max_samples)) {
    if (segment.end == SegmentEnd::kOpen && !keep_open) continue;
    Label label;
    label.recording = recording.id;
    label.t0 = stream.time_of(segment.first);
    label.t1 = segment.last + 1 < samples ? stream.time_of(segment.last + 1)
                                          : stream.time_of(segment.last) + 1.0 / stream.rate_hz;
    label.region = "all";
    double most = 0.0;
    for (size_t r = 0; r < regions.size(); ++r) {
      double pressure = 0.0;
      for (int column : region_columns[r])
        for (int64_t t = segment.first; t <= segment.last; ++t) {
          const float value = stream.samples(t, column);
          if (std::isfinite(value)) pressure += value;
        }
      if (pressure > most) {
        most = pressure;
        label.region = regions[r]->id;
      }
    }
    label.annotator = "segmenter:threshold";
    label.source = LabelSource::kSegmenter;
    label.note = std::string("end=") + to_string(segment.end);
    labels.push_back(std::move(label));
  }
  return labels;
}

}  // namespace tactile

#include "tactile/segment/proximity.h"

#include <algorithm>
#include <cstdint>

#include "tactile/error.h"
#include "tactile/segment/nao_window.h"

namespace tactile {

namespace {

struct Run {
  int64_t first = 0;  // first contact sample
  int64_t last = 0;   // last contact sample
};

double non_negative(const Parameters& parameters, const std::string& key, double fallback) {
  const double value = parameters.number(key, fallback);
  if (value < 0.0)
    throw Error(parameters.where(), key + "=" + parameters.text(key, "") + ": must be >= 0");
  return value;
}

// Samples at which any cell of the body part is closer than contact_mm, as runs.
std::vector<Run> contact_runs(const Stream& stream, const BodyPart& part, double contact_mm) {
  const int64_t count = stream.sample_count();
  std::vector<char> contact(static_cast<size_t>(count), 0);
  for (const CellColumns& cell : part.cells) {
    const float* proximity = stream.samples.col(cell.proximity).data();
    for (int64_t t = 0; t < count; ++t) contact[t] |= proximity[t] < contact_mm;  // NaN: no contact
  }
  std::vector<Run> runs;
  for (int64_t t = 0; t < count; ++t) {
    if (!contact[t]) continue;
    if (!runs.empty() && runs.back().last == t - 1)
      runs.back().last = t;
    else
      runs.push_back({t, t});
  }
  return runs;
}

}  // namespace

std::vector<Label> segment_proximity(const Recording& recording, const SkinLayout& layout,
                                     const Parameters& parameters) {
  parameters.expect_only({"threshold_mm", "pad_s", "merge_gap_s", "min_duration_s"});
  const double contact_mm =
      positive_parameter(parameters, "threshold_mm", kDefaultContactDistanceMm);
  const double pad = non_negative(parameters, "pad_s", 0.1);
  const double merge_gap = non_negative(parameters, "merge_gap_s", 0.2);
  const double min_duration = non_negative(parameters, "min_duration_s", 0.05);

  const NaoSkin skin = locate_nao_skin(recording, layout);
  const Stream& stream = *skin.stream;
  const double period = stream.rate_hz > 0.0 ? 1.0 / stream.rate_hz : 0.0;
  const double begin = stream.sample_count() > 0 ? stream.time_of(0) : stream.start_time;
  const double end = begin + stream.duration();

  std::vector<Label> labels;
  std::vector<size_t> part_order;  // body part index per label, to sort ties
  for (size_t p = 0; p < skin.body_parts.size(); ++p) {
    const BodyPart& part = skin.body_parts[p];
    std::vector<Run> merged;
    for (const Run& run : contact_runs(stream, part, contact_mm)) {
      // The gap runs from the last contact sample of one run to the first of the next.
      if (!merged.empty() &&
          stream.time_of(run.first) - stream.time_of(merged.back().last) < merge_gap)
        merged.back().last = run.last;
      else
        merged.push_back(run);
    }
    for (const Run& run : merged) {
      const double first_time = stream.time_of(run.first);
      const double last_time = stream.time_of(run.last);
      if (last_time - first_time + period < min_duration) continue;
      Label label;
      label.recording = recording.id;
      // Spec §1.1: [t_first - pad, t_last + pad], half-open so the last contact sample is inside.
      label.t0 = std::max(begin, first_time - pad);
      label.t1 = std::min(end, last_time + period + pad);
      label.region = part.id;
      label.annotator = "segmenter:proximity";
      label.source = LabelSource::kSegmenter;
      labels.push_back(std::move(label));
      part_order.push_back(p);
    }
  }
  std::vector<size_t> order(labels.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (labels[a].t0 != labels[b].t0) return labels[a].t0 < labels[b].t0;
    return part_order[a] < part_order[b];
  });
  std::vector<Label> sorted;
  sorted.reserve(labels.size());
  for (size_t k : order) sorted.push_back(std::move(labels[k]));
  return sorted;
}

}  // namespace tactile

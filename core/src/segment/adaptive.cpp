#include "tactile/segment/adaptive.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "tactile/error.h"
#include "tactile/segment/threshold.h"
#include "tactile/signal/display_scale.h"

namespace tactile {

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters) {
  parameters.expect_only({"margin", "quiet_seconds", "max_seconds", "min_seconds"});
  const double margin = parameters.number("margin", 2.0);
  const double quiet_seconds = parameters.number("quiet_seconds", 0.25);
  const double max_seconds = parameters.number("max_seconds", 10.0);
  const double min_seconds = parameters.number("min_seconds", 0.05);
  if (!(margin > 0)) throw Error("parameter margin", "must be positive");
  if (recording.streams.empty()) throw Error(recording.id, "no stream to segment");
  const Stream& stream = recording.streams.front();
  if (!(stream.rate_hz > 0)) throw Error(recording.id + ":/streams/" + stream.name, "needs a sample rate");
  const int channels = static_cast<int>(stream.channel_count());
  std::vector<int> columns(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) columns[static_cast<size_t>(c)] = c;
  const RestScale scale = rest_scale(stream, columns);
  const int64_t samples = stream.sample_count();
  // A flat channel has no noise band: the smallest change a float can tell apart counts.
  std::vector<float> limit(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const float rest = scale.rest[static_cast<size_t>(c)];
    const float band = std::max(scale.noise_band[static_cast<size_t>(c)],
                                1e-6f * std::max(1.0f, std::fabs(rest)));
    limit[static_cast<size_t>(c)] = static_cast<float>(margin) * band;
  }
  std::vector<uint8_t> active(static_cast<size_t>(samples), 0);
  for (int c = 0; c < channels; ++c) {
    const float rest = scale.rest[static_cast<size_t>(c)];
    if (std::isnan(rest)) continue;
    const float* column = stream.samples.col(c).data();
    for (int64_t t = 0; t < samples; ++t)
      if (std::fabs(column[t] - rest) > limit[static_cast<size_t>(c)]) active[static_cast<size_t>(t)] = 1;
  }
  const auto quiet = std::max<int64_t>(1, std::llround(quiet_seconds * stream.rate_hz));
  const auto longest = std::max<int64_t>(1, std::llround(max_seconds * stream.rate_hz));
  // Which group a channel's taxel belongs to, for the region.
  std::map<std::string, int> channel_of_name;
  for (int c = 0; c < channels; ++c) channel_of_name[stream.channels[static_cast<size_t>(c)]] = c;
  std::vector<std::vector<int>> group_channels(layout.groups.size());
  for (size_t g = 0; g < layout.groups.size(); ++g)
    for (int64_t taxel_id : layout.groups[g].taxels)
      if (const Taxel* taxel = layout.find_taxel(taxel_id))
        for (int channel : taxel->channels)
          if (channel >= 0 && channel < static_cast<int>(layout.channels.size())) {
            const auto found = channel_of_name.find(layout.channels[static_cast<size_t>(channel)].name);
            if (found != channel_of_name.end()) group_channels[g].push_back(found->second);
          }
  std::vector<Label> labels;
  for (const SampleSegment& segment : threshold_segments(active, quiet, longest)) {
    const double t0 = stream.time_of(segment.first);
    const double t1 = stream.time_of(segment.last) + 1.0 / stream.rate_hz;
    if (t1 - t0 < min_seconds) continue;
    Label label;
    label.recording = recording.id;
    label.t0 = t0;
    label.t1 = t1;
    label.class_name = kUnknownClass;
    label.note = to_string(segment.end);
    // The group whose channels left their band the most, summed over the segment.
    double best = 0.0;
    for (size_t g = 0; g < group_channels.size(); ++g) {
      double moved = 0.0;
      for (int c : group_channels[g]) {
        const float rest = scale.rest[static_cast<size_t>(c)];
        for (int64_t t = segment.first; t <= segment.last; ++t)
          moved += std::max(0.0f, std::fabs(stream.samples(t, c) - rest) - limit[static_cast<size_t>(c)]);
      }
      if (moved > best) best = moved, label.region = layout.groups[g].id;
    }
    labels.push_back(std::move(label));
  }
  return labels;
}

}  // namespace tactile

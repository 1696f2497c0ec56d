#include "tactile/features/feature_extractor.h"

#include <algorithm>
#include <numeric>

#include "tactile/error.h"

namespace tactile {

Recording FeatureExtractor::preprocess(const Recording& recording, const SkinLayout&) const {
  return recording;
}

FeatureExtractor::Segments FeatureExtractor::extract_segments(
    const Recording& raw, const SkinLayout& layout, const std::vector<Label>& segments,
    const std::function<void(size_t)>& each) const {
  const Recording recording = preprocess(raw, layout);
  Segments extracted;
  extracted.metadata = recording.metadata;
  extracted.results.reserve(segments.size());
  for (const Label& segment : segments) {
    extracted.results.push_back(extract(SegmentInput{recording, layout, segment}));
    if (each) each(extracted.results.size());
  }
  return extracted;
}
std::string FeatureExtractor::layout_note(const SkinLayout&) const { return {}; }

FeatureExtractor::Segments extract_source_segments(const FeatureExtractor& extractor,
                                                   const SampleSource& source,
                                                   const SkinLayout& layout,
                                                   const std::vector<Label>& segments,
                                                   const std::function<void(size_t)>& each,
                                                   const std::function<void(double)>& read_step) {
  if (!extractor.reads_segment_only())
    return extractor.extract_segments(read_all(source, read_step), layout, segments, each);
  FeatureExtractor::Segments extracted;
  extracted.metadata = source.info().metadata;
  extracted.results.reserve(segments.size());
  const int64_t count = source.sample_count();
  for (const Label& segment : segments) {
    // A sample either side of [t0, t1): the window's own sample range finds the same samples.
    const int64_t first = std::max<int64_t>(0, source.first_index_at_or_after(segment.t0) - 1);
    const int64_t last = std::min(count, source.first_index_at_or_after(segment.t1) + 1);
    const Recording window = read_window(source, first, std::max<int64_t>(0, last - first));
    extracted.results.push_back(extractor.extract(SegmentInput{window, layout, segment}));
    if (each) each(extracted.results.size());
  }
  return extracted;
}

const Stream& pipeline_stream(const Recording& recording, const std::string& name) {
  const Stream* stream = name.empty()
                             ? (recording.streams.empty() ? nullptr : &recording.streams.front())
                             : recording.find_stream(name);
  if (stream == nullptr)
    throw Error("recording " + recording.id,
                name.empty() ? "has no streams" : "has no stream '" + name + "'");
  return *stream;
}

std::vector<int64_t> layout_columns(const Stream& stream, const SkinLayout& layout) {
  const int64_t channel_count = static_cast<int64_t>(layout.channels.size());
  std::vector<int64_t> columns(layout.channels.size(), -1);
  const auto stranger =
      std::find_if(stream.channels.begin(), stream.channels.end(),
                   [&](const std::string& name) { return layout.channel_index(name) < 0; });
  // Unnamed channels, or names of another's (an import's header), are the layout's in order.
  if (stream.channels.empty() || stranger != stream.channels.end()) {
    if (stream.channel_count() != channel_count)
      throw Error(
          "stream " + stream.name,
          std::to_string(stream.channel_count()) + " channels, but layout " + layout.id + " has " +
              std::to_string(channel_count) +
              (stranger != stream.channels.end() ? " and no channel " + *stranger
                                                 : std::string(" and the stream's are unnamed")));
    std::iota(columns.begin(), columns.end(), int64_t{0});
    return columns;
  }
  for (size_t channel = 0; channel < layout.channels.size(); ++channel) {
    const auto found =
        std::find(stream.channels.begin(), stream.channels.end(), layout.channels[channel].name);
    if (found != stream.channels.end()) columns[channel] = found - stream.channels.begin();
  }
  return columns;
}

bool in_layout_order(const Stream& stream, const SkinLayout& layout) {
  if (stream.channel_count() != static_cast<int64_t>(layout.channels.size())) return false;
  bool named_in_order = true;
  for (size_t channel = 0; channel < stream.channels.size() && named_in_order; ++channel)
    named_in_order = stream.channels[channel] == layout.channels[channel].name;
  if (named_in_order) return true;
  const std::vector<int64_t> columns = layout_columns(stream, layout);
  for (size_t channel = 0; channel < columns.size(); ++channel)
    if (columns[channel] != static_cast<int64_t>(channel)) return false;
  return true;
}

Stream layout_ordered(const Stream& stream, const SkinLayout& layout) {
  const std::vector<int64_t> columns = layout_columns(stream, layout);
  Stream ordered;
  ordered.name = stream.name;
  ordered.rate_hz = stream.rate_hz;
  ordered.start_time = stream.start_time;
  ordered.timestamps = stream.timestamps;
  ordered.samples =
      SampleMatrix::Zero(stream.sample_count(), static_cast<Eigen::Index>(columns.size()));
  for (size_t channel = 0; channel < columns.size(); ++channel) {
    ordered.channels.push_back(layout.channels[channel].name);
    const bool held = columns[channel] >= 0;
    ordered.units.push_back(held && static_cast<size_t>(columns[channel]) < stream.units.size()
                                ? stream.units[static_cast<size_t>(columns[channel])]
                                : layout.channels[channel].unit);
    if (held)
      ordered.samples.col(static_cast<Eigen::Index>(channel)) =
          stream.samples.col(columns[channel]);
  }
  return ordered;
}

const Stream& ordered_stream(const Recording& recording, const SkinLayout& layout,
                             const std::string& name, const std::string& rate_need) {
  const Stream& stream = pipeline_stream(recording, name);
  const std::string where = "recording " + recording.id + " stream " + stream.name;
  if (!in_layout_order(stream, layout))
    throw Error(where, std::to_string(stream.channel_count()) + " channels, not layout " +
                           layout.id + "'s " + std::to_string(layout.channels.size()) +
                           " in order (preprocess() puts them in order)");
  if (!(stream.rate_hz > 0.0)) throw Error(where, "no sample rate, which " + rate_need);
  return stream;
}

Recording with_layout_stream(const Recording& recording, const SkinLayout& layout,
                             const std::string& name) {
  const Stream& stream = pipeline_stream(recording, name);
  Recording copy = recording;
  if (!in_layout_order(stream, layout))
    copy.streams[static_cast<size_t>(&stream - recording.streams.data())] =
        layout_ordered(stream, layout);
  return copy;
}

}  // namespace tactile

// The raw-sample pipeline: each channel resampled to a fixed number of points, referenced
// to its rest level and scaled (raw.h says which scaling happens where).
#include "tactile/features/raw.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "tactile/error.h"
#include "tactile/features/generic.h"
#include "tactile/stats/statistics.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// The scale factor is this quantile of |x - baseline| over the recording: the size of a
// firm touch, not of a single spike.
constexpr double kRawScaleQuantile = 0.99;

double raw_excursion_quantile(std::vector<double> magnitudes) {
  if (magnitudes.empty()) return 1.0;
  const auto at = static_cast<size_t>(
      std::floor(kRawScaleQuantile * static_cast<double>(magnitudes.size() - 1)));
  const double factor = stats::nth_smallest(magnitudes, at);
  return factor > 0.0 && std::isfinite(factor) ? factor : 1.0;
}

std::string raw_modality_of(const SkinLayout& layout, const std::string& modality) {
  if (modality != "display") return modality;
  if (!layout.display_modality.empty()) return layout.display_modality;
  return layout.modalities.empty() ? std::string() : layout.modalities.front();
}

}  // namespace

std::vector<double> resample_linear(std::span<const double> values, int64_t count) {
  std::vector<double> points(static_cast<size_t>(std::max<int64_t>(count, 0)), 0.0);
  if (values.empty() || count <= 0) return points;
  const auto n = static_cast<int64_t>(values.size());
  if (n == 1 || count == 1) {
    std::fill(points.begin(), points.end(), values.front());
    return points;
  }
  const double step = static_cast<double>(n - 1) / static_cast<double>(count - 1);
  for (int64_t k = 0; k < count; ++k) {
    const double position = static_cast<double>(k) * step;
    const auto left = std::min(static_cast<int64_t>(position), n - 2);
    const double fraction = position - static_cast<double>(left);
    points[static_cast<size_t>(k)] = values[static_cast<size_t>(left)] * (1.0 - fraction) +
                                     values[static_cast<size_t>(left + 1)] * fraction;
  }
  return points;
}

RawReading read_raw_parameters(const Parameters& parameters, int64_t default_samples,
                               int64_t minimum_samples) {
  RawReading reading;
  reading.modality = parameters.text("modality", "all");
  reading.stream = parameters.text("stream", "");
  reading.samples = parameters.integer("samples", default_samples);
  if (reading.samples < minimum_samples || reading.samples > 100000)
    throw Error(parameters.where(), "samples=" + std::to_string(reading.samples) +
                                        ": must be in [" + std::to_string(minimum_samples) +
                                        ", 100000]");
  const std::string baseline = parameters.text("baseline", "rest");
  if (baseline != "rest" && baseline != "none")
    throw Error(parameters.where(), "baseline=" + baseline + ": expected rest or none");
  reading.subtract_rest = baseline == "rest";
  const std::string scale = parameters.text("scale", "global");
  if (scale == "none")
    reading.scale = RawScale::none;
  else if (scale == "global")
    reading.scale = RawScale::global;
  else if (scale == "channel")
    reading.scale = RawScale::channel;
  else if (scale == "feature")
    throw Error(parameters.where(),
                "scale=feature: per-feature standardisation needs the other rows of the table, so "
                "the classifier does it on its training fold (ridge, the SVMs, knn standardize); "
                "a pipeline offers none, global or channel");
  else
    throw Error(parameters.where(), "scale=" + scale + ": expected none, global or channel");
  return reading;
}

std::vector<int> raw_channels(const SkinLayout& layout, const RawReading& reading,
                              const std::string& where) {
  std::vector<int> channels;
  const std::string modality = raw_modality_of(layout, reading.modality);
  for (size_t index = 0; index < layout.channels.size(); ++index)
    if (reading.modality == "all" || layout.channels[index].modality == modality)
      channels.push_back(static_cast<int>(index));
  if (channels.empty())
    throw Error(where, "modality=" + reading.modality + ": layout " + layout.id +
                           " has no channel of it (has: " + joined(layout.modalities) +
                           "; or all, display)");
  return channels;
}

const Stream& raw_stream(const Recording& recording, const SkinLayout& layout,
                         const RawReading& reading) {
  const Stream* stream = reading.stream.empty()
                             ? (recording.streams.empty() ? nullptr : &recording.streams.front())
                             : recording.find_stream(reading.stream);
  if (stream == nullptr)
    throw Error("recording " + recording.id, reading.stream.empty()
                                                 ? "has no streams"
                                                 : "has no stream '" + reading.stream + "'");
  if (stream->channels.empty() &&
      stream->channel_count() != static_cast<int64_t>(layout.channels.size()))
    throw Error("recording " + recording.id + " stream " + stream->name,
                std::to_string(stream->channel_count()) + " unnamed channels, but layout " +
                    layout.id + " has " + std::to_string(layout.channels.size()));
  return *stream;
}

std::vector<int64_t> raw_stream_columns(const Stream& stream, const SkinLayout& layout,
                                        const std::vector<int>& channels) {
  std::vector<int64_t> columns;
  bool any = false;
  for (int channel : channels) {
    int64_t column = -1;
    if (stream.channels.empty()) {
      column = channel;
    } else {
      const auto found = std::find(stream.channels.begin(), stream.channels.end(),
                                   layout.channels[static_cast<size_t>(channel)].name);
      if (found != stream.channels.end()) column = found - stream.channels.begin();
    }
    any = any || column >= 0;
    columns.push_back(column);
  }
  if (!any)
    throw Error("stream " + stream.name,
                "holds none of the chosen channels of layout " + layout.id);
  return columns;
}

Recording add_raw_levels(const Recording& recording, const SkinLayout& layout,
                         const RawReading& reading, const std::string& where) {
  const Stream& stream = raw_stream(recording, layout, reading);
  const std::vector<int> channels = raw_channels(layout, reading, where);
  const std::vector<int64_t> columns = raw_stream_columns(stream, layout, channels);
  const bool reversed = layout.display_min > layout.display_max;
  // One column per layout channel (not per stream column).
  Stream levels;
  levels.name = reading.levels_stream;
  levels.rate_hz = stream.rate_hz;
  for (const Channel& channel : layout.channels) {
    levels.channels.push_back(channel.name);
    levels.units.push_back(channel.unit);
  }
  levels.samples = SampleMatrix::Zero(2, static_cast<Eigen::Index>(layout.channels.size()));
  levels.samples.row(1).setOnes();
  // global: one pool of magnitudes per modality (channels of one modality share units).
  std::map<std::string, std::vector<double>> modality_magnitudes;
  for (size_t position = 0; position < channels.size(); ++position) {
    const int channel = channels[position];
    if (columns[position] < 0) continue;
    std::vector<double> values =
        stats::to_double(stream.samples.col(columns[position]).data(), stream.sample_count());
    const bool channel_reversed =
        reversed &&
        layout.channels[static_cast<size_t>(channel)].modality == layout.display_modality;
    const double rest = reading.subtract_rest ? quiet_level(values, channel_reversed) : 0.0;
    levels.samples(0, channel) = static_cast<float>(rest);
    std::vector<double> magnitudes;
    magnitudes.reserve(values.size());
    for (double value : values)
      if (std::isfinite(value)) magnitudes.push_back(std::abs(value - rest));
    if (reading.scale == RawScale::channel)
      levels.samples(1, channel) = static_cast<float>(raw_excursion_quantile(magnitudes));
    else if (reading.scale == RawScale::global) {
      std::vector<double>& pool =
          modality_magnitudes[layout.channels[static_cast<size_t>(channel)].modality];
      pool.insert(pool.end(), magnitudes.begin(), magnitudes.end());
    }
  }
  if (reading.scale == RawScale::global) {
    std::map<std::string, double> factors;
    for (auto& [modality, pool] : modality_magnitudes)
      factors[modality] = raw_excursion_quantile(std::move(pool));
    for (int channel : channels)
      levels.samples(1, channel) =
          static_cast<float>(factors[layout.channels[static_cast<size_t>(channel)].modality]);
  }
  Recording prepared = recording;
  prepared.streams.push_back(std::move(levels));
  return prepared;
}

Eigen::MatrixXd raw_segment(const SegmentInput& input, const RawReading& reading,
                            const std::vector<int>& channels, std::string& skip_reason) {
  const Stream& stream = raw_stream(input.recording, input.layout, reading);
  const auto [first, last] = sample_range(stream, input.segment.t0, input.segment.t1);
  if (last <= first) {
    skip_reason = "segment holds no samples";
    return {};
  }
  const Stream* levels = input.recording.find_stream(reading.levels_stream);
  if (levels != nullptr &&
      levels->channel_count() != static_cast<int64_t>(input.layout.channels.size()))
    levels = nullptr;
  const std::vector<int64_t> columns = raw_stream_columns(stream, input.layout, channels);
  Eigen::MatrixXd points =
      Eigen::MatrixXd::Zero(reading.samples, static_cast<Eigen::Index>(channels.size()));
  for (size_t position = 0; position < channels.size(); ++position) {
    const int channel = channels[position];
    if (columns[position] < 0) continue;  // a layout channel the stream lacks reads as 0
    const std::vector<double> values =
        stats::to_double(stream.samples.col(columns[position]).data() + first, last - first);
    const auto bad = std::find_if(values.begin(), values.end(),
                                  [](double value) { return !std::isfinite(value); });
    if (bad != values.end()) {
      skip_reason = "NaN or infinite sample in channel " +
                    input.layout.channels[static_cast<size_t>(channel)].name +
                    " at t=" + std::to_string(stream.time_of(first + (bad - values.begin()))) +
                    " s";
      return {};
    }
    const double rest = levels ? levels->samples(0, channel) : 0.0;
    const double scale = levels ? levels->samples(1, channel) : 1.0;
    const std::vector<double> resampled = resample_linear(values, reading.samples);
    points.col(static_cast<Eigen::Index>(position)) =
        (Eigen::Map<const Eigen::ArrayXd>(resampled.data(), reading.samples) - rest) / scale;
  }
  return points;
}

//---- The extractor

namespace {

class RawExtractor : public FeatureExtractor {
 public:
  RawExtractor(RawReading reading, std::string where)
      : reading_(std::move(reading)), where_(std::move(where)) {}

  std::string name() const override { return "raw"; }
  std::string description() const override {
    return "Any layout: each channel of one modality resampled to a fixed number of points over "
           "the segment (linear interpolation), minus its rest level, scaled per recording "
           "(global) or per channel";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    std::vector<FeatureColumn> columns;
    const std::string scaled = reading_.scale == RawScale::none     ? ""
                               : reading_.scale == RawScale::global ? ", over the recording's scale"
                                                                    : ", over the channel's scale";
    const std::string referenced = reading_.subtract_rest ? " minus its rest level" : "";
    for (int channel : raw_channels(layout, reading_, where_)) {
      const Channel& info = layout.channels[static_cast<size_t>(channel)];
      for (int64_t k = 0; k < reading_.samples; ++k)
        columns.push_back({info.name + ".s" + std::to_string(k),
                           info.name + referenced + scaled + ", point " + std::to_string(k) +
                               " of " + std::to_string(reading_.samples) +
                               " spread linearly over the segment"});
    }
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return add_raw_levels(recording, layout, reading_, where_);
  }

  FeatureResult extract(const SegmentInput& input) const override {
    std::string skip_reason;
    const Eigen::MatrixXd points =
        raw_segment(input, reading_, raw_channels(input.layout, reading_, where_), skip_reason);
    if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
    // Column-major: channel by channel, as columns() names them.
    return {std::vector<double>(points.data(), points.data() + points.size()), {}};
  }

 private:
  RawReading reading_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_raw_extractor(const Parameters& parameters) {
  parameters.expect_only({"modality", "stream", "samples", "baseline", "scale"});
  return std::make_unique<RawExtractor>(read_raw_parameters(parameters, 32, 2), parameters.where());
}

}  // namespace tactile

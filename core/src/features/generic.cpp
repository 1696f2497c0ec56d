// The generic descriptor set: per-channel statistics for any layout, contact area and
// centroid motion where the taxels spread over a 2-D map.
#include "tactile/features/generic.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include "tactile/error.h"

namespace tactile {

namespace {

// The rest level of a channel: this percentile of its recording (the complement when
// reversed).
constexpr double kQuietPercentile = 0.1;
// The stream preprocess() adds: one sample, each channel's rest level.
constexpr const char* kRestStream = "generic.rest";

}  // namespace

//---- Pure functions

ChannelSummary summarise_channel(std::span<const double> values, double rate_hz, bool reversed) {
  ChannelSummary summary;
  if (values.empty()) return summary;
  // Kaboli et al. eqs. (2)-(4): activity, mobility, complexity.
  summary.hjorth = stats::hjorth(values);
  summary.peak_index = reversed ? stats::argmin(values) : stats::argmax(values);
  summary.peak = values[static_cast<size_t>(summary.peak_index)];
  summary.mean = stats::mean(values);
  // Rectangle rule: each sample stands for 1 / rate seconds.
  const Eigen::Map<const Eigen::ArrayXd> samples(values.data(),
                                                 static_cast<Eigen::Index>(values.size()));
  summary.integral = rate_hz > 0.0 ? samples.sum() / rate_hz : 0.0;
  return summary;
}

double quiet_level(std::span<const double> values, bool reversed) {
  std::vector<double> finite;
  finite.reserve(values.size());
  for (double value : values)
    if (std::isfinite(value)) finite.push_back(value);
  if (finite.empty()) return 0.0;
  // Touch is rare over a recording: a low percentile is the rest level, and unlike the
  // minimum it ignores single noise spikes.
  const double position = (reversed ? 1.0 - kQuietPercentile : kQuietPercentile) *
                          static_cast<double>(finite.size() - 1);
  const auto index = static_cast<size_t>(reversed ? std::ceil(position) : std::floor(position));
  std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(index),
                   finite.end());
  return finite[index];
}

ContactMotion contact_motion(const Eigen::MatrixXd& values, const Eigen::RowVectorXd& rest,
                             const std::vector<Point2>& positions, const Eigen::VectorXd& areas,
                             double threshold, bool reversed) {
  ContactMotion motion;
  if (values.size() == 0) return motion;
  // Taxels of one skin rest at different levels, so each has its own; its excursion past
  // rest is compared with the largest of any taxel, so that untouched taxels' noise does
  // not count as contact. Values on the far side of rest are no touch at all.
  Eigen::RowVectorXd level = rest;
  if (level.size() != values.cols())
    level = reversed ? Eigen::RowVectorXd(values.colwise().maxCoeff())
                     : Eigen::RowVectorXd(values.colwise().minCoeff());
  const Eigen::ArrayXXd past_rest = (reversed ? Eigen::ArrayXXd((-values).rowwise() + level)
                                              : Eigen::ArrayXXd(values.rowwise() - level))
                                        .cwiseMax(0.0);
  const double largest = past_rest.maxCoeff();
  // Spec §0 zero test, on the excursion: a flat segment has no contact.
  if (largest <= 1e-12 * std::max(1.0, values.cwiseAbs().maxCoeff())) return motion;
  const Eigen::ArrayXXd contact = (past_rest > threshold * largest).cast<double>();
  const Eigen::VectorXd area = contact.matrix() * areas;
  motion.max_area = area.maxCoeff();
  motion.mean_area = area.mean();

  const Eigen::MatrixXd weights = (past_rest * contact).matrix();
  Eigen::VectorXd x(static_cast<Eigen::Index>(positions.size()));
  Eigen::VectorXd y(x.size());
  for (size_t index = 0; index < positions.size(); ++index) {
    x(static_cast<Eigen::Index>(index)) = positions[index].x;
    y(static_cast<Eigen::Index>(index)) = positions[index].y;
  }
  const Eigen::VectorXd total = weights.rowwise().sum();
  const Eigen::VectorXd weighted_x = weights * x;
  const Eigen::VectorXd weighted_y = weights * y;
  bool seen = false;
  Point2 first, previous;
  for (Eigen::Index sample = 0; sample < values.rows(); ++sample) {
    if (!(total(sample) > 0.0)) continue;
    const Point2 centroid{weighted_x(sample) / total(sample), weighted_y(sample) / total(sample)};
    if (seen)
      motion.path_length += std::hypot(centroid.x - previous.x, centroid.y - previous.y);
    else
      first = centroid;
    previous = centroid;
    seen = true;
  }
  if (seen) motion.displacement = std::hypot(previous.x - first.x, previous.y - first.y);
  return motion;
}

bool spans_two_dimensions(const std::vector<Point2>& points) {
  if (points.size() < 3) return false;
  // Collinear points have a singular position covariance.
  double mean_x = 0.0, mean_y = 0.0;
  for (const Point2& point : points) {
    mean_x += point.x;
    mean_y += point.y;
  }
  mean_x /= static_cast<double>(points.size());
  mean_y /= static_cast<double>(points.size());
  double xx = 0.0, yy = 0.0, xy = 0.0;
  for (const Point2& point : points) {
    xx += (point.x - mean_x) * (point.x - mean_x);
    yy += (point.y - mean_y) * (point.y - mean_y);
    xy += (point.x - mean_x) * (point.y - mean_y);
  }
  const double trace = xx + yy;
  return trace > 0.0 && xx * yy - xy * xy > 1e-9 * trace * trace;
}

//---- The extractor

namespace {

std::string shortest_text(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// Which channels a layout gives the generic set, decided from the layout alone so that
// columns() and extract() agree.
struct ChannelPlan {
  std::vector<int> value_channels;  // layout channel indices, per-channel features
  bool has_map = false;             // contact features present
  std::vector<int> map_channels;    // one per map taxel
  std::vector<int64_t> map_taxels;  // taxel ids
  std::vector<Point2> positions;
  Eigen::VectorXd areas;
  bool reversed = false;             // small values mean contact (display_min > display_max)
  std::vector<bool> value_reversed;  // per value channel: of the reversed map modality
};

class GenericExtractor : public FeatureExtractor {
 public:
  GenericExtractor(std::string modality, double threshold, std::string stream, std::string where)
      : modality_(std::move(modality)),
        threshold_(threshold),
        stream_(std::move(stream)),
        where_(std::move(where)) {}

  std::string name() const override { return "generic"; }
  std::string description() const override {
    return "Any layout: per channel the Hjorth triple, peak, mean, integral and time of peak; "
           "on 2-D maps the contact area (max, mean) and the contact centroid's path length and "
           "net displacement";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    const ChannelPlan plan = plan_for(layout);
    std::vector<FeatureColumn> columns;
    for (size_t position = 0; position < plan.value_channels.size(); ++position) {
      const Channel& channel = layout.channels[static_cast<size_t>(plan.value_channels[position])];
      // For modalities where small means touch, the peak is the smallest value.
      const std::string extreme = plan.value_reversed[position] ? "smallest" : "largest";
      const std::string unit = channel.unit.empty() ? "units" : channel.unit;
      const std::string& name = channel.name;
      columns.push_back({name + ".hjorth_activity",
                         "Kaboli eq. (2): population variance of " + name + ", " + unit + "^2"});
      columns.push_back({name + ".hjorth_mobility",
                         "Kaboli eq. (3): sqrt(var(diff x) / var(x)) of " + name + ", per sample"});
      columns.push_back(
          {name + ".hjorth_complexity",
           "Kaboli eq. (4): mobility(diff x) / mobility(x) of " + name + ", dimensionless"});
      columns.push_back({name + ".peak", extreme + " value of " + name + ", " + unit});
      columns.push_back({name + ".mean", "mean of " + name + ", " + unit});
      columns.push_back(
          {name + ".integral", "sum of " + name + " / sample rate, " + unit + " x s"});
      columns.push_back({name + ".peak_time", "time of the first " + extreme + " value of " + name +
                                                  " after the segment's start, s"});
    }
    if (plan.has_map) {
      const std::string unit = layout.map_unit.empty() ? "map units" : layout.map_unit;
      const std::string level = "taxels of " + map_modality(layout) + " past their rest level by " +
                                shortest_text(threshold_) + " of the segment's largest excursion";
      columns.push_back(
          {"contact.max_area", "largest contact area (" + level + "), " + unit + "^2"});
      columns.push_back(
          {"contact.mean_area", "mean contact area over the segment's samples, " + unit + "^2"});
      columns.push_back(
          {"centroid.path_length",
           "distance the value-weighted contact centroid moves, sample to sample, " + unit});
      columns.push_back({"centroid.displacement",
                         "distance from the first to the last contact centroid, " + unit});
    }
    return columns;
  }

  // Adds a one-sample stream with each channel's rest level over the whole recording, so
  // a segment inside a long press still knows where rest is.
  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    const Stream& stream = find_stream(recording, layout);
    const ChannelPlan plan = plan_for(layout);
    std::vector<bool> reversed(static_cast<size_t>(stream.channel_count()), false);
    if (plan.reversed)
      for (int channel : plan.map_channels) reversed[static_cast<size_t>(channel)] = true;
    Stream rest;
    rest.name = kRestStream;
    rest.rate_hz = stream.rate_hz;
    rest.channels = stream.channels;
    rest.units = stream.units;
    rest.samples.resize(1, stream.channel_count());
    for (int64_t channel = 0; channel < stream.channel_count(); ++channel) {
      const std::vector<double> values =
          stats::to_double(stream.samples.col(channel).data(), stream.sample_count());
      rest.samples(0, channel) =
          static_cast<float>(quiet_level(values, reversed[static_cast<size_t>(channel)]));
    }
    Recording prepared = recording;
    prepared.streams.push_back(std::move(rest));
    return prepared;
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = find_stream(input.recording, input.layout);
    const ChannelPlan plan = plan_for(input.layout);
    const auto [first, last] = sample_range(stream, input.segment.t0, input.segment.t1);
    const int64_t count = last - first;
    // Shorter segments still have defined values: Hjorth of fewer than 3 samples is 0
    // where its differences are missing (spec §1.4).
    if (count < 1) return FeatureResult::skip("segment holds no samples");
    std::vector<std::vector<double>> channel_values;
    channel_values.reserve(plan.value_channels.size());
    for (int index : plan.value_channels) {
      channel_values.push_back(stats::to_double(stream.samples.col(index).data() + first, count));
      const std::vector<double>& values = channel_values.back();
      const auto bad = std::find_if(values.begin(), values.end(),
                                    [](double value) { return !std::isfinite(value); });
      if (bad != values.end())
        return FeatureResult::skip(
            "NaN or infinite sample in channel " +
            input.layout.channels[static_cast<size_t>(index)].name +
            " at t=" + std::to_string(stream.time_of(first + (bad - values.begin()))) + " s");
    }

    FeatureResult result;
    for (size_t position = 0; position < channel_values.size(); ++position) {
      const ChannelSummary summary = summarise_channel(channel_values[position], stream.rate_hz,
                                                       plan.value_reversed[position]);
      const double peak_time = stream.time_of(first + summary.peak_index) - input.segment.t0;
      result.values.insert(result.values.end(), {summary.hjorth.activity, summary.hjorth.mobility,
                                                 summary.hjorth.complexity, summary.peak,
                                                 summary.mean, summary.integral, peak_time});
    }
    if (plan.has_map) {
      std::string skip_reason;
      const ContactMotion motion = map_motion(input, stream, plan, first, count, skip_reason);
      if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
      result.values.insert(result.values.end(), {motion.max_area, motion.mean_area,
                                                 motion.path_length, motion.displacement});
    }
    return result;
  }

 private:
  std::string map_modality(const SkinLayout& layout) const {
    if (modality_ == "all" || modality_ == "display")
      return layout.display_modality.empty() && !layout.modalities.empty()
                 ? layout.modalities.front()
                 : layout.display_modality;
    return modality_;
  }

  ChannelPlan plan_for(const SkinLayout& layout) const {
    ChannelPlan plan;
    const std::string modality = map_modality(layout);
    const int slot = layout.modality_index(modality);
    if (slot < 0 && !(modality_ == "all" && modality.empty())) {
      std::string known;
      for (const std::string& name : layout.modalities) known += (known.empty() ? "" : ", ") + name;
      throw Error(where_, "modality=" + modality + ": layout " + layout.id +
                              " has no such modality (has: " + known + "; or all, display)");
    }
    for (const Taxel& taxel : layout.taxels) {
      if (slot < 0 || static_cast<size_t>(slot) >= taxel.channels.size()) continue;
      const int channel = taxel.channels[static_cast<size_t>(slot)];
      if (channel < 0) continue;
      plan.map_channels.push_back(channel);
      plan.map_taxels.push_back(taxel.id);
      plan.positions.push_back(taxel.position);
    }
    if (modality_ == "all") {
      for (size_t index = 0; index < layout.channels.size(); ++index)
        plan.value_channels.push_back(static_cast<int>(index));
    } else {
      plan.value_channels = plan.map_channels;
    }
    plan.has_map = spans_two_dimensions(plan.positions);
    plan.areas.resize(static_cast<Eigen::Index>(plan.map_taxels.size()));
    for (size_t index = 0; index < plan.map_taxels.size(); ++index) {
      const Taxel& taxel = *layout.find_taxel(plan.map_taxels[index]);
      plan.areas(static_cast<Eigen::Index>(index)) =
          taxel.area > 0.0 ? taxel.area : taxel.size.x * taxel.size.y;
    }
    plan.reversed = layout.display_min > layout.display_max && modality == layout.display_modality;
    for (int channel : plan.value_channels)
      plan.value_reversed.push_back(
          plan.reversed && layout.channels[static_cast<size_t>(channel)].modality == modality);
    return plan;
  }

  const Stream& find_stream(const Recording& recording, const SkinLayout& layout) const {
    const Stream* stream = nullptr;
    if (stream_.empty()) {
      if (!recording.streams.empty()) stream = &recording.streams.front();
    } else {
      stream = recording.find_stream(stream_);
    }
    if (stream == nullptr)
      throw Error("recording " + recording.id,
                  stream_.empty() ? "has no streams" : "has no stream '" + stream_ + "'");
    if (stream->channel_count() != static_cast<int64_t>(layout.channels.size()))
      throw Error("recording " + recording.id + " stream " + stream->name,
                  std::to_string(stream->channel_count()) + " channels, but layout " + layout.id +
                      " has " + std::to_string(layout.channels.size()));
    if (!(stream->rate_hz > 0.0))
      throw Error("recording " + recording.id + " stream " + stream->name,
                  "no sample rate, which the integral needs");
    return *stream;
  }

  // The contact features over the segment's region: the taxels of its layout group, or
  // every map taxel for "all".
  ContactMotion map_motion(const SegmentInput& input, const Stream& stream, const ChannelPlan& plan,
                           int64_t first, int64_t count, std::string& skip_reason) const {
    std::vector<size_t> members;
    if (input.segment.region == "all" || input.segment.region.empty()) {
      for (size_t index = 0; index < plan.map_taxels.size(); ++index) members.push_back(index);
    } else {
      const Group* group = input.layout.find_group(input.segment.region);
      if (group == nullptr) {
        skip_reason =
            "region '" + input.segment.region + "' is not a group of layout " + input.layout.id;
        return {};
      }
      const std::set<int64_t> in_group(group->taxels.begin(), group->taxels.end());
      for (size_t index = 0; index < plan.map_taxels.size(); ++index)
        if (in_group.count(plan.map_taxels[index])) members.push_back(index);
    }
    // Without preprocess() the segment's own quietest values stand in for rest.
    const Stream* rest_stream = input.recording.find_stream(kRestStream);
    Eigen::MatrixXd values(count, static_cast<Eigen::Index>(members.size()));
    Eigen::RowVectorXd rest(rest_stream ? values.cols() : 0);
    std::vector<Point2> positions;
    Eigen::VectorXd areas(static_cast<Eigen::Index>(members.size()));
    for (size_t column = 0; column < members.size(); ++column) {
      const size_t member = members[column];
      const auto index = static_cast<Eigen::Index>(column);
      values.col(index) =
          stream.samples.col(plan.map_channels[member]).segment(first, count).cast<double>();
      if (rest_stream) rest(index) = rest_stream->samples(0, plan.map_channels[member]);
      positions.push_back(plan.positions[member]);
      areas(index) = plan.areas(static_cast<Eigen::Index>(member));
    }
    return contact_motion(values, rest, positions, areas, threshold_, plan.reversed);
  }

  std::string modality_;
  double threshold_;
  std::string stream_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_generic_extractor(const Parameters& parameters) {
  parameters.expect_only({"modality", "threshold", "stream"});
  const double threshold = parameters.number("threshold", 0.2);
  if (!(threshold >= 0.0 && threshold < 1.0))
    throw Error(parameters.where(),
                "threshold=" + parameters.text("threshold", "") + ": must be in [0, 1)");
  return std::make_unique<GenericExtractor>(parameters.text("modality", "display"), threshold,
                                            parameters.text("stream", ""), parameters.where());
}

}  // namespace tactile

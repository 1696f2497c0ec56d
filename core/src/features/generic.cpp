// The generic descriptor set: per-channel statistics for any layout, contact area and
// centroid motion where the taxels spread over a 2-D map.
#include "tactile/features/generic.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include "tactile/error.h"

namespace tactile {

//---- Pure functions

ChannelSummary summarise_channel(std::span<const double> values, double rate_hz) {
  ChannelSummary summary;
  if (values.empty()) return summary;
  // Kaboli et al. eqs. (2)-(4): activity, mobility, complexity.
  summary.hjorth = stats::hjorth(values);
  summary.peak_index = stats::argmax(values);
  summary.peak = values[static_cast<size_t>(summary.peak_index)];
  summary.mean = stats::mean(values);
  // Rectangle rule: each sample stands for 1 / rate seconds.
  const Eigen::Map<const Eigen::ArrayXd> samples(values.data(),
                                                 static_cast<Eigen::Index>(values.size()));
  summary.integral = rate_hz > 0.0 ? samples.sum() / rate_hz : 0.0;
  return summary;
}

ContactMotion contact_motion(const Eigen::MatrixXd& values, const std::vector<Point2>& positions,
                             const Eigen::VectorXd& areas, double threshold, bool reversed) {
  ContactMotion motion;
  if (values.size() == 0) return motion;
  const double low = values.minCoeff();
  const double high = values.maxCoeff();
  const double range = high - low;
  // Spec §0 zero test, on the range: a flat segment has no contact.
  if (range <= 1e-12 * std::max({1.0, std::abs(low), std::abs(high)})) return motion;

  // How far each value is past the rest level, in the direction of touch.
  const Eigen::ArrayXXd past_rest =
      reversed ? Eigen::ArrayXXd(high - values.array()) : Eigen::ArrayXXd(values.array() - low);
  const Eigen::ArrayXXd contact = (past_rest > threshold * range).cast<double>();
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
  bool reversed = false;  // small values mean contact (display_min > display_max)
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
    for (int index : plan.value_channels) {
      const Channel& channel = layout.channels[static_cast<size_t>(index)];
      const std::string unit = channel.unit.empty() ? "units" : channel.unit;
      const std::string& name = channel.name;
      columns.push_back({name + ".hjorth_activity",
                         "Kaboli eq. (2): population variance of " + name + ", " + unit + "^2"});
      columns.push_back({name + ".hjorth_mobility",
                         "Kaboli eq. (3): sqrt(var(diff x) / var(x)) of " + name + ", per sample"});
      columns.push_back(
          {name + ".hjorth_complexity",
           "Kaboli eq. (4): mobility(diff x) / mobility(x) of " + name + ", dimensionless"});
      columns.push_back({name + ".peak", "largest value of " + name + ", " + unit});
      columns.push_back({name + ".mean", "mean of " + name + ", " + unit});
      columns.push_back(
          {name + ".integral", "sum of " + name + " / sample rate, " + unit + " x s"});
      columns.push_back({name + ".peak_time", "time of the first largest value of " + name +
                                                  " after the segment's start, s"});
    }
    if (plan.has_map) {
      const std::string unit = layout.map_unit.empty() ? "map units" : layout.map_unit;
      const std::string level = "taxels past " + shortest_text(threshold_) +
                                " of the segment's range of " + map_modality(layout);
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

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = find_stream(input.recording, input.layout);
    const ChannelPlan plan = plan_for(input.layout);
    const auto [first, last] = sample_range(stream, input.segment.t0, input.segment.t1);
    const int64_t count = last - first;
    // Hjorth complexity needs second differences.
    if (count < 3)
      return FeatureResult::skip("segment holds " + std::to_string(count) +
                                 " samples; generic needs at least 3");
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
    for (const std::vector<double>& values : channel_values) {
      const ChannelSummary summary = summarise_channel(values, stream.rate_hz);
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
    Eigen::MatrixXd values(count, static_cast<Eigen::Index>(members.size()));
    std::vector<Point2> positions;
    Eigen::VectorXd areas(static_cast<Eigen::Index>(members.size()));
    for (size_t column = 0; column < members.size(); ++column) {
      const size_t member = members[column];
      values.col(static_cast<Eigen::Index>(column)) =
          stream.samples.col(plan.map_channels[member]).segment(first, count).cast<double>();
      positions.push_back(plan.positions[member]);
      areas(static_cast<Eigen::Index>(column)) = plan.areas(static_cast<Eigen::Index>(member));
    }
    return contact_motion(values, positions, areas, threshold_, plan.reversed);
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

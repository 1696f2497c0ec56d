// The generic descriptor set: per-channel statistics for any layout, contact area and
// centroid motion where the taxels spread over a 2-D map.
#include "tactile/features/generic.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <set>
#include <unsupported/Eigen/FFT>

#include "tactile/error.h"
#include "tactile/stats/statistics.h"

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
  return stats::nth_smallest(finite, index);
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
  double spread_sum = 0.0;
  int64_t spread_count = 0;
  for (Eigen::Index sample = 0; sample < values.rows(); ++sample) {
    if (!(total(sample) > 0.0)) continue;
    const Point2 centroid{weighted_x(sample) / total(sample), weighted_y(sample) / total(sample)};
    double spread = 0.0;
    for (Eigen::Index taxel = 0; taxel < weights.cols(); ++taxel)
      spread += weights(sample, taxel) * std::hypot(x(taxel) - centroid.x, y(taxel) - centroid.y);
    spread_sum += spread / total(sample);
    ++spread_count;
    if (seen)
      motion.path_length += std::hypot(centroid.x - previous.x, centroid.y - previous.y);
    else
      first = centroid;
    previous = centroid;
    seen = true;
  }
  if (seen) motion.displacement = std::hypot(previous.x - first.x, previous.y - first.y);
  if (spread_count > 0) motion.spread = spread_sum / static_cast<double>(spread_count);
  return motion;
}

namespace {

double quantile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  const auto at =
      static_cast<size_t>(std::llround(fraction * static_cast<double>(values.size() - 1)));
  return stats::nth_smallest(values, at);
}

}  // namespace

ChannelShape channel_shape(std::span<const double> values, double rate_hz, double rest,
                           bool reversed) {
  ChannelShape shape;
  const auto n = static_cast<int64_t>(values.size());
  if (n == 0) return shape;
  const std::vector<double> all(values.begin(), values.end());
  shape.median = stats::median(all);
  shape.q10 = quantile(all, 0.1);
  shape.q90 = quantile(all, 0.9);
  if (!std::isfinite(rest)) rest = reversed ? shape.q90 : shape.q10;
  std::vector<double> excursion(values.size());
  for (size_t k = 0; k < values.size(); ++k)
    excursion[k] = reversed ? std::max(0.0, rest - values[k]) : std::abs(values[k] - rest);
  const double seconds = static_cast<double>(n) / rate_hz;
  // Energy by band, from the spectrum of the mean-removed segment.
  double mean = 0.0;
  for (double value : values) mean += value;
  mean /= static_cast<double>(n);
  if (n >= 4) {
    std::vector<double> centred(values.size());
    for (size_t k = 0; k < values.size(); ++k) centred[k] = values[k] - mean;
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, centred);
    double low = 0.0, mid = 0.0, high = 0.0;
    for (int64_t bin = 1; bin <= n / 2; ++bin) {
      const double frequency = static_cast<double>(bin) * rate_hz / static_cast<double>(n);
      const double energy = std::norm(spectrum[static_cast<size_t>(bin)]);
      (frequency < rate_hz / 16.0 ? low : frequency < rate_hz / 8.0 ? mid : high) += energy;
    }
    const double total = low + mid + high;
    if (total > 0.0)
      shape.band_low = low / total, shape.band_mid = mid / total, shape.band_high = high / total;
  }
  // Sign changes of the mean-removed signal; samples within rounding of the mean carry none.
  double scale = 0.0;
  for (double value : values) scale = std::max(scale, std::abs(value - mean));
  int64_t crossings = 0;
  int last_sign = 0;
  for (double value : values) {
    const double centred = value - mean;
    const int sign = std::abs(centred) <= 1e-9 * scale ? 0 : (centred > 0.0 ? 1 : -1);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) ++crossings;
    last_sign = sign;
  }
  shape.zero_crossings = static_cast<double>(crossings) / seconds;
  // Peaks: the times the excursion rises through half its largest (a noisy plateau is one).
  const double largest = *std::max_element(excursion.begin(), excursion.end());
  int64_t peaks = 0;
  bool above = false;
  for (double value : excursion) {
    if (!above && largest > 0.0 && value > 0.5 * largest) ++peaks;
    above = largest > 0.0 && value > 0.5 * largest;
  }
  shape.peaks = static_cast<double>(peaks) / seconds;
  for (int64_t k = 1; k < n; ++k) {
    const double step =
        (excursion[static_cast<size_t>(k)] - excursion[static_cast<size_t>(k - 1)]) * rate_hz;
    if (k <= n / 2)
      shape.onset_slope = std::max(shape.onset_slope, step);
    else
      shape.release_slope = std::min(shape.release_slope, step);
  }
  // Noise from the first differences: their RMS without the largest fifth (the touch's own
  // transitions), over sqrt 2 (a difference holds two samples' noise). Robust also for
  // quantised counts, where a median absolute deviation is often 0.
  std::vector<double> differences;
  for (int64_t k = 1; k < n; ++k)
    differences.push_back(
        std::abs(values[static_cast<size_t>(k)] - values[static_cast<size_t>(k - 1)]));
  std::sort(differences.begin(), differences.end());
  const size_t kept = differences.size() - differences.size() / 5;
  double squares = 0.0;
  for (size_t k = 0; k < kept; ++k) squares += differences[k] * differences[k];
  const double noise = kept > 0 ? std::sqrt(squares / static_cast<double>(kept) / 2.0) : 0.0;
  int64_t active = 0;
  for (double value : excursion)
    if (value > 3.0 * noise && value > 0.0) ++active;
  shape.active_seconds = static_cast<double>(active) / rate_hz;
  for (int bin = 0; bin < kEnvelopeBins; ++bin) {
    const int64_t from = n * bin / kEnvelopeBins,
                  to = std::max(from + 1, n * (bin + 1) / kEnvelopeBins);
    double sum = 0.0;
    for (int64_t k = from; k < std::min(to, n); ++k) sum += excursion[static_cast<size_t>(k)];
    shape.envelope[bin] = sum / static_cast<double>(std::min(to, n) - from);
  }
  return shape;
}

double correlation(std::span<const double> a, std::span<const double> b) {
  const size_t n = std::min(a.size(), b.size());
  if (n < 2) return 0.0;
  double mean_a = 0.0, mean_b = 0.0;
  for (size_t k = 0; k < n; ++k) mean_a += a[k], mean_b += b[k];
  mean_a /= static_cast<double>(n);
  mean_b /= static_cast<double>(n);
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (size_t k = 0; k < n; ++k) {
    ab += (a[k] - mean_a) * (b[k] - mean_b);
    aa += (a[k] - mean_a) * (a[k] - mean_a);
    bb += (b[k] - mean_b) * (b[k] - mean_b);
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : 0.0;
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
  std::vector<size_t> neighbour;     // per value channel: its nearest neighbour's position
  bool whole_grid = false;           // whole-grid columns instead of the per-channel block
};

// Values per channel: 7 summary, 11 shape, the envelope (add_channel_columns, extract()).
constexpr size_t kChannelColumns = 18 + kEnvelopeBins;

// The per-channel columns of one channel: `name` prefixes the column, `what` describes it.
void add_channel_columns(const std::string& name, const std::string& what, const std::string& unit,
                         const std::string& extreme, std::vector<FeatureColumn>& columns) {
  columns.push_back({name + ".hjorth_activity",
                     "Kaboli eq. (2): population variance of " + what + ", " + unit + "^2"});
  columns.push_back({name + ".hjorth_mobility",
                     "Kaboli eq. (3): sqrt(var(diff x) / var(x)) of " + what + ", per sample"});
  columns.push_back(
      {name + ".hjorth_complexity",
       "Kaboli eq. (4): mobility(diff x) / mobility(x) of " + what + ", dimensionless"});
  columns.push_back({name + ".peak", extreme + " value of " + what + ", " + unit});
  columns.push_back({name + ".mean", "mean of " + what + ", " + unit});
  columns.push_back({name + ".integral", "sum of " + what + " / sample rate, " + unit + " x s"});
  columns.push_back({name + ".peak_time", "time of the first " + extreme + " value of " + what +
                                              " after the segment's start, s"});
  const std::string excursion = "the excursion of " + what + " from its rest level";
  columns.push_back({name + ".median", "median of " + what + ", " + unit});
  columns.push_back({name + ".q10", "10th percentile of " + what + ", " + unit});
  columns.push_back({name + ".q90", "90th percentile of " + what + ", " + unit});
  columns.push_back(
      {name + ".band_low", "share of the mean-removed energy of " + what + " below fs/16"});
  columns.push_back(
      {name + ".band_mid", "share of the mean-removed energy of " + what + " in [fs/16, fs/8)"});
  columns.push_back(
      {name + ".band_high", "share of the mean-removed energy of " + what + " from fs/8 up"});
  columns.push_back({name + ".zero_crossings", "crossings of the mean by " + what + ", per s"});
  columns.push_back(
      {name + ".peaks", "rises of " + excursion + " through half its largest, per s"});
  columns.push_back({name + ".onset_slope",
                     "steepest rise of " + excursion + " in the first half, " + unit + "/s"});
  columns.push_back({name + ".release_slope",
                     "steepest fall of " + excursion + " in the second half, " + unit + "/s"});
  columns.push_back(
      {name + ".active_time", "time " + excursion +
                                  " exceeds 3 noise deviations (RMS of the differences without "
                                  "their largest fifth / sqrt 2), s"});
  for (int bin = 0; bin < kEnvelopeBins; ++bin)
    columns.push_back({name + ".envelope_" + std::to_string(bin),
                       "mean " + excursion + " in part " + std::to_string(bin + 1) + " of " +
                           std::to_string(kEnvelopeBins) + " equal parts of the segment, " + unit});
}

class GenericExtractor : public FeatureExtractor {
 public:
  GenericExtractor(std::string modality, double threshold, std::string stream,
                   std::string per_channel, std::string where)
      : modality_(std::move(modality)),
        threshold_(threshold),
        per_channel_(std::move(per_channel)),
        stream_(std::move(stream)),
        where_(std::move(where)) {}

  std::string name() const override { return "generic"; }
  std::string description() const override {
    return "Any layout: per channel the Hjorth triple, peak, mean, integral, time of peak, median "
           "and "
           "deciles, energy in three bands, zero crossings, peaks, onset and release slopes, time "
           "above the noise band and the envelope in 8 parts; across channels the same figures of "
           "the busiest channel (wherever the touch landed) and its share of the activity, and the "
           "correlation of neighbouring channels; on 2-D maps the contact area (max, mean), "
           "spread, and the contact centroid's "
           "path length and net displacement; over " +
           std::to_string(kGridTaxelsForGeneric) +
           " channels on a 2-D map (per_channel=auto), the grid pipeline's whole-grid columns "
           "instead of the "
           "per-channel block";
  }

  std::string layout_note(const SkinLayout& layout) const override {
    const ChannelPlan plan = plan_for(layout);
    const std::string channels = std::to_string(plan.value_channels.size()) + " channels";
    if (plan.whole_grid)
      return "generic on " + layout.id +
             ": whole-grid columns (grid.*) instead of the per-channel block (" + channels +
             (per_channel_ == "auto" ? " > " + std::to_string(kGridTaxelsForGeneric) : "") +
             "; per_channel=yes keeps it)";
    return "generic on " + layout.id + ": per-channel block (" + channels + ")";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    const ChannelPlan plan = plan_for(layout);
    std::vector<FeatureColumn> columns;
    std::set<std::string> units;
    for (size_t position = 0; position < plan.value_channels.size(); ++position) {
      const Channel& channel = layout.channels[static_cast<size_t>(plan.value_channels[position])];
      if (plan.whole_grid) {
        units.insert(channel.unit.empty() ? "units" : channel.unit);
        continue;
      }
      // For modalities where small means touch, the peak is the smallest value.
      const std::string extreme = plan.value_reversed[position] ? "smallest" : "largest";
      const std::string unit = channel.unit.empty() ? "units" : channel.unit;
      units.insert(unit);
      add_channel_columns(channel.name, channel.name, unit, extreme, columns);
    }
    if (plan.value_channels.size() >= 2) {
      // Across channels: wherever the touch landed, its channel's figures in the same columns.
      const bool reversed = std::find(plan.value_reversed.begin(), plan.value_reversed.end(),
                                      true) != plan.value_reversed.end();
      add_channel_columns("busiest", "the busiest channel (largest Hjorth activity)",
                          units.size() == 1 ? *units.begin() : "units",
                          reversed ? "smallest (reversed channels) or largest" : "largest",
                          columns);
      columns.push_back({"busiest.activity_share",
                         "the busiest channel's Hjorth activity over the sum of every channel's"});
    }
    if (plan.value_channels.size() >= 2)
      columns.push_back(
          {"neighbours.correlation",
           "mean Pearson correlation of each channel with its nearest neighbour on the map "
           "(the next channel without one), over the segment"});
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
      columns.push_back(
          {"contact.spread",
           "excursion-weighted distance of the contact taxels from the centroid, mean over "
           "the samples with contact, " +
               unit});
    }
    if (plan.whole_grid) {
      const std::vector<FeatureColumn> grid =
          grid_columns("grid.", units.size() == 1 ? *units.begin() : "units",
                       layout.map_unit.empty() ? "map units" : layout.map_unit);
      columns.insert(columns.end(), grid.begin(), grid.end());
    }
    return columns;
  }

  // Adds a one-sample stream with each channel's rest level over the whole recording, so
  // a segment inside a long press still knows where rest is.
  Recording preprocess(const Recording& original, const SkinLayout& layout) const override {
    Recording prepared = with_layout_stream(original, layout, stream_);
    prepared.streams.reserve(prepared.streams.size() + 2);  // `stream` stays valid below
    const Stream& stream = find_stream(prepared, layout);
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
    prepared.streams.push_back(std::move(rest));
    if (plan.whole_grid)
      add_grid_rest(prepared, stream, grid_map(layout, map_modality(layout), where_));
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
    const size_t block = kChannelColumns;
    for (size_t position = 0; position < channel_values.size(); ++position) {
      const ChannelSummary summary = summarise_channel(channel_values[position], stream.rate_hz,
                                                       plan.value_reversed[position]);
      const double peak_time = stream.time_of(first + summary.peak_index) - input.segment.t0;
      result.values.insert(result.values.end(), {summary.hjorth.activity, summary.hjorth.mobility,
                                                 summary.hjorth.complexity, summary.peak,
                                                 summary.mean, summary.integral, peak_time});
      const int channel = plan.value_channels[position];
      const Stream* rest_stream = input.recording.find_stream(kRestStream);
      const double rest = rest_stream ? rest_stream->samples(0, channel) : std::nan("");
      const ChannelShape shape = channel_shape(channel_values[position], stream.rate_hz, rest,
                                               plan.value_reversed[position]);
      result.values.insert(result.values.end(),
                           {shape.median, shape.q10, shape.q90, shape.band_low, shape.band_mid,
                            shape.band_high, shape.zero_crossings, shape.peaks, shape.onset_slope,
                            shape.release_slope, shape.active_seconds});
      result.values.insert(result.values.end(), std::begin(shape.envelope),
                           std::end(shape.envelope));
    }
    if (channel_values.size() >= 2) {
      // The busiest channel's block again, then its share of all the channels' activity.
      size_t busiest = 0;
      double total = 0.0;
      for (size_t position = 0; position < channel_values.size(); ++position) {
        const double activity = result.values[position * block];
        total += activity;
        if (activity > result.values[busiest * block]) busiest = position;
      }
      const size_t start = busiest * block;
      for (size_t k = 0; k < block; ++k) result.values.push_back(result.values[start + k]);
      result.values.push_back(total > 0.0 ? result.values[start] / total : 0.0);
    }
    if (channel_values.size() >= 2) {
      double sum = 0.0;
      for (size_t position = 0; position < channel_values.size(); ++position)
        sum += correlation(channel_values[position], channel_values[plan.neighbour[position]]);
      result.values.push_back(sum / static_cast<double>(channel_values.size()));
    }
    // Whole grid: the per-channel block served the busiest channel's figures only.
    if (plan.whole_grid)
      result.values.erase(
          result.values.begin(),
          result.values.begin() + static_cast<std::ptrdiff_t>(channel_values.size() * block));
    if (plan.has_map) {
      std::string skip_reason;
      const ContactMotion motion = map_motion(input, stream, plan, first, count, skip_reason);
      if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
      result.values.insert(result.values.end(),
                           {motion.max_area, motion.mean_area, motion.path_length,
                            motion.displacement, motion.spread});
    }
    if (plan.whole_grid) {
      std::string skip_reason;
      const GridMap map = grid_region(grid_map(input.layout, map_modality(input.layout), where_),
                                      input.layout, input.segment.region, skip_reason);
      const std::vector<double> grid = skip_reason.empty()
                                           ? grid_segment(input.recording, stream, map, first,
                                                          count, kGridDefaultThreshold, skip_reason)
                                           : std::vector<double>{};
      if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
      result.values.insert(result.values.end(), grid.begin(), grid.end());
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
    if (per_channel_ == "no" && !plan.has_map)
      throw Error(where_,
                  "per_channel=no: layout " + layout.id + "'s taxels do not spread over a 2-D map");
    plan.whole_grid = per_channel_ == "no" || (per_channel_ == "auto" && plan.has_map &&
                                               plan.value_channels.size() > kGridTaxelsForGeneric);
    plan.areas.resize(static_cast<Eigen::Index>(plan.map_taxels.size()));
    for (size_t index = 0; index < plan.map_taxels.size(); ++index) {
      const Taxel& taxel = *layout.find_taxel(plan.map_taxels[index]);
      plan.areas(static_cast<Eigen::Index>(index)) =
          taxel.area > 0.0 ? taxel.area : taxel.size.x * taxel.size.y;
    }
    plan.reversed = layout.display_min > layout.display_max && modality == layout.display_modality;
    // Each value channel's nearest neighbour on the map (by its taxel's position), else the
    // next channel.
    std::map<int, Point2> position_of;
    for (const Taxel& taxel : layout.taxels)
      for (int channel : taxel.channels)
        if (channel >= 0) position_of.emplace(channel, taxel.position);
    for (size_t position = 0; position < plan.value_channels.size(); ++position) {
      size_t best = (position + 1) % plan.value_channels.size();
      const auto here = position_of.find(plan.value_channels[position]);
      if (here != position_of.end()) {
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t other = 0; other < plan.value_channels.size(); ++other) {
          const auto there = position_of.find(plan.value_channels[other]);
          if (other == position || there == position_of.end()) continue;
          const double distance =
              std::hypot(there->second.x - here->second.x, there->second.y - here->second.y);
          if (distance > 1e-12 && distance < nearest) nearest = distance, best = other;
        }
      }
      plan.neighbour.push_back(best);
    }
    for (int channel : plan.value_channels)
      plan.value_reversed.push_back(
          plan.reversed && layout.channels[static_cast<size_t>(channel)].modality == modality);
    return plan;
  }

  const Stream& find_stream(const Recording& recording, const SkinLayout& layout) const {
    return ordered_stream(recording, layout, stream_, "the integral needs");
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
  std::string per_channel_;
  std::string stream_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_generic_extractor(const Parameters& parameters) {
  parameters.expect_only({"modality", "threshold", "stream", "per_channel"});
  const double threshold = parameters.number("threshold", 0.2);
  const std::string per_channel = parameters.text("per_channel", "auto");
  if (per_channel != "auto" && per_channel != "yes" && per_channel != "no")
    throw Error(parameters.where(), "per_channel=" + per_channel + ": must be auto, yes or no");
  if (!(threshold >= 0.0 && threshold < 1.0))
    throw Error(parameters.where(),
                "threshold=" + parameters.text("threshold", "") + ": must be in [0, 1)");
  return std::make_unique<GenericExtractor>(parameters.text("modality", "display"), threshold,
                                            parameters.text("stream", ""), per_channel,
                                            parameters.where());
}

}  // namespace tactile

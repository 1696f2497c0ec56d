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
                               int64_t minimum_samples, const std::string& default_series) {
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
  const std::string series = parameters.text("series", default_series);
  if (series == "channels")
    reading.series = RawSeries::channels;
  else if (series == "summary")
    reading.series = RawSeries::summary;
  else if (series == "auto")
    reading.series = RawSeries::automatic;
  else
    throw Error(parameters.where(), "series=" + series + ": expected channels, summary or auto");
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
  const Stream& stream = pipeline_stream(recording, reading.stream);
  layout_columns(stream, layout);  // throws when the stream's channels are not the layout's
  return stream;
}

std::vector<int64_t> raw_stream_columns(const Stream& stream, const SkinLayout& layout,
                                        const std::vector<int>& channels) {
  const std::vector<int64_t> of_layout = layout_columns(stream, layout);
  std::vector<int64_t> columns;
  for (int channel : channels) columns.push_back(of_layout[static_cast<size_t>(channel)]);
  if (std::all_of(columns.begin(), columns.end(), [](int64_t column) { return column < 0; }))
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

//---- The summary series

namespace {

// Per layout channel, the index of the taxel that owns it (-1: none).
std::vector<int> raw_summary_channel_taxels(const SkinLayout& layout) {
  std::vector<int> owner(layout.channels.size(), -1);
  for (size_t taxel = 0; taxel < layout.taxels.size(); ++taxel)
    for (int channel : layout.taxels[taxel].channels)
      if (channel >= 0 && static_cast<size_t>(channel) < owner.size())
        owner[static_cast<size_t>(channel)] = static_cast<int>(taxel);
  return owner;
}

}  // namespace

bool raw_reads_summary(const SkinLayout& layout, const RawReading& reading,
                       const std::vector<int>& channels) {
  if (reading.series != RawSeries::automatic) return reading.series == RawSeries::summary;
  const std::vector<int> owner = raw_summary_channel_taxels(layout);
  std::vector<int> taxels;
  for (int channel : channels)
    if (owner[static_cast<size_t>(channel)] >= 0)
      taxels.push_back(owner[static_cast<size_t>(channel)]);
  std::sort(taxels.begin(), taxels.end());
  taxels.erase(std::unique(taxels.begin(), taxels.end()), taxels.end());
  return taxels.size() > kGridTaxelsForGeneric;
}

RawSummaryPlan plan_raw_summary(const SkinLayout& layout, const std::vector<int>& channels) {
  const std::vector<int> owner = raw_summary_channel_taxels(layout);
  std::vector<std::string> kinds;
  for (const Group& group : layout.groups)
    if (std::find(kinds.begin(), kinds.end(), group.kind) == kinds.end())
      kinds.push_back(group.kind);
  RawSummaryPlan plan;
  for (size_t position = 0; position < channels.size(); ++position) {
    const std::string& modality = layout.channels[static_cast<size_t>(channels[position])].modality;
    auto block =
        std::find_if(plan.blocks.begin(), plan.blocks.end(),
                     [&](const RawSummaryPlan::Block& b) { return b.modality == modality; });
    if (block == plan.blocks.end()) {
      plan.blocks.push_back({});
      plan.blocks.back().modality = modality;
      block = plan.blocks.end() - 1;
    }
    block->members.push_back(static_cast<int>(position));
    const int taxel = owner[static_cast<size_t>(channels[position])];
    block->positions.push_back(taxel >= 0 ? layout.taxels[static_cast<size_t>(taxel)].position
                                          : Point2{});
  }
  for (RawSummaryPlan::Block& block : plan.blocks) {
    const std::string& m = block.modality;
    plan.names.insert(plan.names.end(), {m + ".total", m + ".peak", m + ".active",
                                         m + ".centroid_x", m + ".centroid_y"});
    plan.descriptions.insert(
        plan.descriptions.end(),
        {"sum over the " + m + " channels of the excursion |x|",
         "largest excursion |x| of a " + m + " channel",
         "share of the " + m + " channels with |x| above 0.2 of the segment's largest",
         "map x of the |x|-weighted centre of the active " + m +
             " channels minus its mean over the segment, map units",
         "map y of that centre minus its mean over the segment, map units"});
    for (const std::string& kind : kinds) {
      RawSummaryPlan::Kind entry;
      for (const Group& group : layout.groups) {
        if (group.kind != kind) continue;
        std::vector<int> members;
        for (size_t k = 0; k < block.members.size(); ++k) {
          const int taxel =
              owner[static_cast<size_t>(channels[static_cast<size_t>(block.members[k])])];
          if (taxel >= 0 &&
              std::find(group.taxels.begin(), group.taxels.end(),
                        layout.taxels[static_cast<size_t>(taxel)].id) != group.taxels.end())
            members.push_back(static_cast<int>(k));
        }
        if (members.empty()) continue;
        entry.ids.push_back(group.id);
        entry.groups.push_back(std::move(members));
      }
      entry.ranked = std::min<int>(kRawSummaryGroups, static_cast<int>(entry.groups.size()));
      entry.placed = entry.groups.size() <= kRawSummaryPlacedGroups;
      for (int rank = 1; rank <= entry.ranked; ++rank) {
        plan.names.push_back(m + "." + kind + "." + std::to_string(rank));
        plan.descriptions.push_back("sum of |x| over the " + m + " channels of the " + kind +
                                    " with the " + std::to_string(rank) +
                                    (rank == 1   ? "st"
                                     : rank == 2 ? "nd"
                                                 : "rd") +
                                    " largest such sum over the segment");
      }
      if (entry.placed)
        for (const std::string& id : entry.ids) {
          plan.names.push_back(m + "." + id);
          plan.descriptions.push_back("sum of |x| over the " + m + " channels of " + kind + " " +
                                      id);
        }
      block.kinds.push_back(std::move(entry));
    }
    block.top_channels = std::min<int>(kRawSummaryChannels, static_cast<int>(block.members.size()));
    for (int rank = 1; rank <= block.top_channels; ++rank) {
      plan.names.push_back(m + ".top." + std::to_string(rank));
      plan.descriptions.push_back("the " + m + " channel with the " + std::to_string(rank) +
                                  (rank == 1   ? "st"
                                   : rank == 2 ? "nd"
                                   : rank == 3 ? "rd"
                                               : "th") +
                                  " largest sum of x^2 over the segment, x signed");
    }
  }
  return plan;
}

Eigen::MatrixXd raw_summary(const RawSummaryPlan& plan, const Eigen::MatrixXd& points) {
  const Eigen::Index samples = points.rows();
  Eigen::MatrixXd series =
      Eigen::MatrixXd::Zero(samples, static_cast<Eigen::Index>(plan.names.size()));
  Eigen::Index out = 0;
  // Ranks `totals` descending (ties: the lower index first) and returns the first `count`.
  const auto ranked = [](const std::vector<double>& totals, int count) {
    std::vector<int> order(totals.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return totals[static_cast<size_t>(a)] > totals[static_cast<size_t>(b)];
    });
    order.resize(static_cast<size_t>(count));
    return order;
  };
  for (const RawSummaryPlan::Block& block : plan.blocks) {
    const auto members = static_cast<Eigen::Index>(block.members.size());
    Eigen::MatrixXd x(samples, members);
    for (Eigen::Index k = 0; k < members; ++k)
      x.col(k) = points.col(block.members[static_cast<size_t>(k)]);
    const Eigen::MatrixXd e = x.cwiseAbs();
    const double largest = members > 0 && samples > 0 ? e.maxCoeff() : 0.0;
    const double level = kRawSummaryActive * largest;
    Eigen::VectorXd cx = Eigen::VectorXd::Zero(samples), cy = Eigen::VectorXd::Zero(samples);
    std::vector<bool> valid(static_cast<size_t>(samples), false);
    double mean_x = 0.0, mean_y = 0.0;
    int valid_count = 0;
    for (Eigen::Index t = 0; t < samples; ++t) {
      double weight = 0.0, wx = 0.0, wy = 0.0;
      int active = 0;
      for (Eigen::Index k = 0; k < members; ++k) {
        const double value = e(t, k);
        if (!(largest > 0.0) || value <= level) continue;
        ++active;
        weight += value;
        wx += value * block.positions[static_cast<size_t>(k)].x;
        wy += value * block.positions[static_cast<size_t>(k)].y;
      }
      series(t, out) = e.row(t).sum();
      series(t, out + 1) = members > 0 ? e.row(t).maxCoeff() : 0.0;
      series(t, out + 2) =
          members > 0 ? static_cast<double>(active) / static_cast<double>(members) : 0.0;
      if (weight > 0.0) {
        cx[t] = wx / weight;
        cy[t] = wy / weight;
        valid[static_cast<size_t>(t)] = true;
        mean_x += cx[t];
        mean_y += cy[t];
        ++valid_count;
      }
    }
    if (valid_count > 0) {
      mean_x /= valid_count;
      mean_y /= valid_count;
      for (Eigen::Index t = 0; t < samples; ++t)
        if (valid[static_cast<size_t>(t)]) {
          // On a grid of 1e-6 map units: a still contact reads exactly 0 wherever it lies,
          // not rounding noise that rocket's biases (often exactly 0) would count.
          series(t, out + 3) = std::round((cx[t] - mean_x) * 1e6) / 1e6;
          series(t, out + 4) = std::round((cy[t] - mean_y) * 1e6) / 1e6;
        }
    }
    out += 5;
    for (const RawSummaryPlan::Kind& kind : block.kinds) {
      Eigen::MatrixXd sums =
          Eigen::MatrixXd::Zero(samples, static_cast<Eigen::Index>(kind.groups.size()));
      std::vector<double> totals(kind.groups.size());
      for (size_t g = 0; g < kind.groups.size(); ++g) {
        for (int member : kind.groups[g]) sums.col(static_cast<Eigen::Index>(g)) += e.col(member);
        totals[g] = sums.col(static_cast<Eigen::Index>(g)).sum();
      }
      for (int g : ranked(totals, kind.ranked)) series.col(out++) = sums.col(g);
      if (kind.placed)
        for (Eigen::Index g = 0; g < sums.cols(); ++g) series.col(out++) = sums.col(g);
    }
    std::vector<double> energy(static_cast<size_t>(members));
    for (Eigen::Index k = 0; k < members; ++k)
      energy[static_cast<size_t>(k)] = x.col(k).squaredNorm();
    for (int k : ranked(energy, block.top_channels)) series.col(out++) = x.col(k);
  }
  return series;
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
    const std::vector<int> channels = raw_channels(layout, reading_, where_);
    std::vector<std::string> names, whats;
    if (raw_reads_summary(layout, reading_, channels)) {
      const RawSummaryPlan plan = plan_raw_summary(layout, channels);
      names = plan.names;
      for (const std::string& description : plan.descriptions)
        whats.push_back(description + " (channels" + referenced + scaled + ")");
    } else {
      for (int channel : channels) {
        names.push_back(layout.channels[static_cast<size_t>(channel)].name);
        whats.push_back(names.back() + referenced + scaled);
      }
    }
    for (size_t series = 0; series < names.size(); ++series)
      for (int64_t k = 0; k < reading_.samples; ++k)
        columns.push_back({names[series] + ".s" + std::to_string(k),
                           whats[series] + ", point " + std::to_string(k) + " of " +
                               std::to_string(reading_.samples) +
                               " spread linearly over the segment"});
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return add_raw_levels(recording, layout, reading_, where_);
  }

  FeatureResult extract(const SegmentInput& input) const override {
    std::string skip_reason;
    const std::vector<int> channels = raw_channels(input.layout, reading_, where_);
    Eigen::MatrixXd points = raw_segment(input, reading_, channels, skip_reason);
    if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
    if (raw_reads_summary(input.layout, reading_, channels))
      points = raw_summary(plan_raw_summary(input.layout, channels), points);
    // Column-major: channel by channel, as columns() names them.
    return {std::vector<double>(points.data(), points.data() + points.size()), {}};
  }

 private:
  RawReading reading_;
  std::string where_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_raw_extractor(const Parameters& parameters) {
  parameters.expect_only({"modality", "stream", "samples", "baseline", "scale", "series"});
  return std::make_unique<RawExtractor>(read_raw_parameters(parameters, 32, 2), parameters.where());
}

}  // namespace tactile

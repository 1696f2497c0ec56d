#include "tactile/features/robovie_xcorr.h"

#include <cmath>
#include <cstdio>
#include <span>
#include <unordered_map>

#include "tactile/dsp/sigma_suppression.h"
#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

int64_t robovie_pair_count(int64_t sensors) { return sensors * (sensors - 1) / 2; }

int64_t robovie_pair_index(int64_t i, int64_t j, int64_t sensors) {
  return i * sensors - i * (i + 1) / 2 + (j - i) - 1;
}

Eigen::MatrixXd robovie_correlation_matrix(const Eigen::MatrixXd& samples) {
  const Eigen::Index count = samples.rows();
  // Standardise each column once (centre, unit norm) so that one GEMM gives every R_ij,
  // instead of N^2 / 2 separate passes over the samples.
  Eigen::MatrixXd standardised(count, samples.cols());
  for (Eigen::Index sensor = 0; sensor < samples.cols(); ++sensor) {
    const auto column = samples.col(sensor);
    const double average = count > 0 ? column.mean() : 0.0;
    auto centred = standardised.col(sensor);
    centred = column.array() - average;
    const double energy = centred.squaredNorm();  // C_ii of eq. (1)
    const std::span<const double> values(column.data(), static_cast<size_t>(count));
    if (count < 2 || stats::is_zero_variance(energy / static_cast<double>(count), values))
      centred.setZero();  // R with a constant sensor is 0 (spec §4.3)
    else
      centred /= std::sqrt(energy);
  }
  // Robovie eq. (2): R = Z^T Z with Z the standardised samples.
  Eigen::MatrixXd correlation = standardised.transpose() * standardised;
  // Rounding can carry |R| a hair past 1.
  return correlation.cwiseMax(-1.0).cwiseMin(1.0);
}

Eigen::VectorXd robovie_xcorr_vector(Eigen::MatrixXd samples, bool sigma_suppression) {
  if (sigma_suppression) dsp::suppress_within_sigma(samples);
  const Eigen::MatrixXd correlation = robovie_correlation_matrix(samples);
  const int64_t sensors = correlation.cols();
  Eigen::VectorXd features(robovie_pair_count(sensors));
  // Row i of the upper triangle is column i below the diagonal (R is symmetric), which is
  // contiguous in column-major storage.
  for (int64_t i = 0; i + 1 < sensors; ++i)
    features.segment(robovie_pair_index(i, i + 1, sensors), sensors - 1 - i) =
        correlation.col(i).tail(sensors - 1 - i);
  return features;
}

namespace {

// Column of `stream` holding each layout channel; throws naming the first one missing.
std::vector<Eigen::Index> layout_columns(const Stream& stream, const SkinLayout& layout,
                                         const std::string& recording_id) {
  std::unordered_map<std::string, Eigen::Index> column_of;
  for (size_t column = 0; column < stream.channels.size(); ++column)
    column_of.emplace(stream.channels[column], static_cast<Eigen::Index>(column));
  std::vector<Eigen::Index> columns;
  for (const Channel& channel : layout.channels) {
    const auto found = column_of.find(channel.name);
    if (found == column_of.end())
      throw Error(recording_id + " stream " + stream.name,
                  "no channel " + channel.name + " of layout " + layout.id);
    columns.push_back(found->second);
  }
  return columns;
}

// The stream recording the layout's films: "skin" when present, else the first stream
// that has the layout's first channel.
const Stream& film_stream(const Recording& recording, const SkinLayout& layout) {
  if (const Stream* skin = recording.find_stream("skin")) return *skin;
  for (const Stream& stream : recording.streams)
    for (const std::string& name : stream.channels)
      if (!layout.channels.empty() && name == layout.channels.front().name) return stream;
  throw Error(recording.id, "no stream with the channels of layout " + layout.id);
}

class RobovieXcorrExtractor : public FeatureExtractor {
 public:
  explicit RobovieXcorrExtractor(bool sigma_suppression) : sigma_suppression_(sigma_suppression) {}

  std::string name() const override { return "robovie_xcorr"; }
  std::string description() const override {
    return "Robovie-IIF (paper 003): Pearson cross-correlation of every pair of films over the "
           "segment (eqs. 1-3)" +
           std::string(sigma_suppression_ ? ", after eq. (13) sigma suppression" : ", raw");
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    const int64_t sensors = static_cast<int64_t>(layout.channels.size());
    std::vector<FeatureColumn> columns;
    columns.reserve(static_cast<size_t>(robovie_pair_count(sensors)));
    for (int64_t i = 0; i < sensors; ++i)
      for (int64_t j = i + 1; j < sensors; ++j) {
        const std::string& first = layout.channels[size_t(i)].name;
        const std::string& second = layout.channels[size_t(j)].name;
        columns.push_back({"xcorr." + first + "." + second,
                           "Pearson correlation of " + first + " and " + second +
                               " over the segment, in [-1, 1] (Robovie eqs. 1-3" +
                               (sigma_suppression_ ? ", after eq. 13)" : ")")});
      }
    return columns;
  }

  // The films' samples inside the segment, nothing else (no preprocessing).
  bool reads_segment_only() const override { return true; }

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = film_stream(input.recording, input.layout);
    const std::vector<Eigen::Index> columns =
        layout_columns(stream, input.layout, input.recording.id);
    const auto [first, last] = sample_range(stream, input.segment.t0, input.segment.t1);
    const Eigen::Index count = last - first;
    if (count < 2)
      return FeatureResult::skip("segment has " + std::to_string(count) +
                                 " sample(s); a correlation needs at least 2");
    Eigen::MatrixXd samples(count, static_cast<Eigen::Index>(columns.size()));
    for (size_t sensor = 0; sensor < columns.size(); ++sensor) {
      samples.col(Eigen::Index(sensor)) =
          stream.samples.col(columns[sensor]).segment(first, count).cast<double>();
      if (!samples.col(Eigen::Index(sensor)).allFinite()) {
        Eigen::Index row = 0;
        while (std::isfinite(samples(row, Eigen::Index(sensor)))) ++row;
        char time[32];
        std::snprintf(time, sizeof(time), "%.6g", stream.time_of(first + row));
        return FeatureResult::skip("film " + input.layout.channels[sensor].name +
                                   " has a non-finite sample at t=" + time + " s");
      }
    }
    const Eigen::VectorXd features = robovie_xcorr_vector(std::move(samples), sigma_suppression_);
    return {std::vector<double>(features.data(), features.data() + features.size()), {}};
  }

 private:
  bool sigma_suppression_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_robovie_xcorr_extractor(const Parameters& parameters) {
  parameters.expect_only({"sigma_suppression"});
  return std::make_unique<RobovieXcorrExtractor>(parameters.flag("sigma_suppression", true));
}

}  // namespace tactile

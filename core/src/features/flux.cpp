#include "tactile/features/flux.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tactile/dsp/flux.h"
#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

std::array<double, kFluxFeaturesPerChannel> flux_channel_features(std::span<const double> window,
                                                                  double rate_hz,
                                                                  int64_t steady_samples) {
  std::array<double, kFluxFeaturesPerChannel> features{};
  const int64_t length = static_cast<int64_t>(window.size());
  if (length == 0) return features;
  const Eigen::Map<const Eigen::ArrayXd> w(window.data(), length);
  // Flux §5.6 (1): max value.
  features[0] = w.maxCoeff();
  if (length > 1) {
    // Flux §5.6 (2), (3): extremes of (w[k] - w[k-1]) · fs.
    const Eigen::ArrayXd derivative = (w.tail(length - 1) - w.head(length - 1)) * rate_hz;
    features[1] = derivative.maxCoeff();
    features[2] = derivative.minCoeff();
  }
  // Flux §5.6 (4): rectangle-rule integral (1/fs) Σ w.
  features[3] = w.sum() / rate_hz;
  // Flux §5.6 (5): the level the signal has settled to at the end of the window.
  features[4] = w.tail(std::clamp<int64_t>(steady_samples, 1, length)).mean();
  // Flux §5.6 (6): time of the first maximum after the onset.
  features[5] = static_cast<double>(stats::argmax(window)) / rate_hz;
  return features;
}

namespace {

const char* const kFeatureNames[kFluxFeaturesPerChannel] = {
    "max_value", "max_derivative", "min_derivative", "integral", "steady_value", "time_of_max"};

std::string feature_description(int feature, const std::string& channel) {
  static const char* const kDescriptions[kFluxFeaturesPerChannel] = {
      "max of e over the 5 s window after onset (relative change, 1); flux §5.6 (1)",
      "max of (e[k] - e[k-1]) * fs over the window (1/s); flux §5.6 (2)",
      "min of (e[k] - e[k-1]) * fs over the window (1/s); flux §5.6 (3)",
      "(1/fs) * sum of e over the window (s); flux §5.6 (4)",
      "mean of e over the last 0.5 s of the window (1); flux §5.6 (5)",
      "time of the first maximum of e after onset (s); flux §5.6 (6)"};
  return std::string(kDescriptions[feature]) + ", channel " + channel;
}

std::string time_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", seconds);
  return text;
}

class FluxExtractor : public FeatureExtractor {
 public:
  explicit FluxExtractor(const dsp::FluxOptions& options) : options_(options) {}

  std::string name() const override { return "flux"; }
  std::string description() const override {
    return "Silicone flux sensor (paper 004): max, max/min derivative, integral, steady value "
           "and time of max of the top channels and their sum over 5 s after onset (spec "
           "§5.2-5.7)";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    std::vector<FeatureColumn> columns;
    for (const std::string& channel : described_channels(dsp::flux_channels(layout)))
      for (int feature = 0; feature < kFluxFeaturesPerChannel; ++feature)
        columns.push_back(
            {channel + "." + kFeatureNames[feature], feature_description(feature, channel)});
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    if (dsp::is_flux_preprocessed(recording)) return recording;
    return dsp::preprocess_flux(recording, layout, options_);
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const Recording& recording = input.recording;
    if (!dsp::is_flux_preprocessed(recording))
      throw Error(recording.id, "the flux features need the flux preprocessing first");
    const std::vector<std::string> names = described_channels(dsp::flux_channels(input.layout));
    const Stream* stream = nullptr;
    for (const Stream& candidate : recording.streams)
      if (std::find(candidate.channels.begin(), candidate.channels.end(), names.back()) !=
          candidate.channels.end())
        stream = &candidate;
    if (stream == nullptr)
      throw Error(recording.id, "no preprocessed flux stream (channel " + names.back() + ")");
    std::vector<Eigen::Index> columns;
    for (const std::string& name : names) {
      const auto found = std::find(stream->channels.begin(), stream->channels.end(), name);
      if (found == stream->channels.end())
        throw Error(recording.id + " stream " + stream->name, "no channel " + name);
      columns.push_back(found - stream->channels.begin());
    }
    const double rate = stream->rate_hz;

    // The onset: first sample of the segment where a top channel's |e| exceeds θ_on.
    const auto [first, last] = sample_range(*stream, input.segment.t0, input.segment.t1);
    int64_t onset = -1;
    for (int64_t n = first; n < last && onset < 0; ++n)
      for (size_t channel = 0; channel < 4; ++channel)
        if (std::abs(stream->samples(n, columns[channel])) > options_.onset_threshold) {
          onset = n;
          break;
        }
    if (onset < 0)
      return FeatureResult::skip("no excitation: no top channel's |e| exceeds " +
                                 time_text(options_.onset_threshold) + " in the segment");

    const int64_t length =
        std::min(dsp::samples_of(options_.window_s, rate, 1), stream->sample_count() - onset);
    const int64_t steady = dsp::samples_of(options_.steady_s, rate, 1);
    FeatureResult result;
    Eigen::VectorXd window(length);
    for (size_t channel = 0; channel < names.size(); ++channel) {
      window = stream->samples.col(columns[channel]).segment(onset, length).cast<double>();
      if (!window.allFinite()) {
        int64_t row = 0;
        while (std::isfinite(window[row])) ++row;
        return FeatureResult::skip("channel " + names[channel] + " has a non-finite sample at t=" +
                                   time_text(stream->time_of(onset + row)) + " s");
      }
      const auto features =
          flux_channel_features({window.data(), static_cast<size_t>(length)}, rate, steady);
      result.values.insert(result.values.end(), features.begin(), features.end());
    }
    return result;
  }

 private:
  // Flux §5.7: the classifier's five channels, top 1-4 then their sum.
  static std::vector<std::string> described_channels(const dsp::FluxChannels& channels) {
    std::vector<std::string> names = channels.top;
    names.push_back(channels.top_sum);
    return names;
  }

  dsp::FluxOptions options_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_flux_extractor(const Parameters& parameters) {
  parameters.expect_only(dsp::flux_option_keys());
  return std::make_unique<FluxExtractor>(dsp::flux_options(parameters));
}

}  // namespace tactile

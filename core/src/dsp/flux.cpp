#include "tactile/dsp/flux.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "tactile/error.h"

namespace tactile::dsp {

//---- Options

std::vector<std::string> flux_option_keys() {
  return {"average_window",    "onset_threshold",  "window_s",        "refractory_quiet_s",
          "baseline_period_s", "baseline_quiet_s", "baseline_settle", "steady_s"};
}

FluxOptions flux_options(const Parameters& parameters) {
  FluxOptions options;
  const auto bad = [&](const std::string& key, const std::string& rule) {
    return Error(parameters.where(), key + "=" + parameters.text(key, "") + ": " + rule);
  };
  options.average_window = parameters.integer("average_window", options.average_window);
  if (options.average_window < 1) throw bad("average_window", "must be at least 1");
  const auto positive = [&](const std::string& key, double fallback) {
    const double value = parameters.number(key, fallback);
    if (!(value > 0.0)) throw bad(key, "must be greater than 0");
    return value;
  };
  const auto not_negative = [&](const std::string& key, double fallback) {
    const double value = parameters.number(key, fallback);
    if (value < 0.0) throw bad(key, "must not be negative");
    return value;
  };
  options.onset_threshold = positive("onset_threshold", options.onset_threshold);
  options.window_s = positive("window_s", options.window_s);
  options.refractory_quiet_s = not_negative("refractory_quiet_s", options.refractory_quiet_s);
  options.baseline_period_s = positive("baseline_period_s", options.baseline_period_s);
  options.baseline_quiet_s = not_negative("baseline_quiet_s", options.baseline_quiet_s);
  options.baseline_settle = positive("baseline_settle", options.baseline_settle);
  options.steady_s = positive("steady_s", options.steady_s);
  return options;
}

int64_t samples_of(double seconds, double rate_hz, int64_t minimum) {
  return std::max<int64_t>(minimum, std::llround(seconds * rate_hz));
}

//---- Moving average

Eigen::VectorXd causal_moving_average(const Eigen::Ref<const Eigen::VectorXd>& x, int64_t window) {
  const Eigen::Index count = x.size();
  Eigen::VectorXd averaged(count);
  // Summed afresh for every output (N adds): a running sum would carry a NaN forever and
  // drift over hours of samples.
  for (Eigen::Index n = 0; n < count; ++n) {
    const Eigen::Index first = std::max<Eigen::Index>(0, n - window + 1);
    averaged[n] = x.segment(first, n - first + 1).mean();
  }
  return averaged;
}

//---- Excitation state

ExcitationDetector::ExcitationDetector(int64_t window_samples, int64_t quiet_samples,
                                       double threshold)
    : window_samples_(window_samples), quiet_samples_(quiet_samples), threshold_(threshold) {}

bool ExcitationDetector::step(double largest_magnitude) {
  const int64_t n = index_++;
  quiet_run_ = largest_magnitude < threshold_ ? quiet_run_ + 1 : 0;
  if (!armed_ && n >= window_end_ && quiet_run_ >= quiet_samples_) armed_ = true;
  if (armed_ && largest_magnitude > threshold_) {
    armed_ = false;
    window_end_ = n + window_samples_;
    return true;
  }
  return false;
}

//---- Ratiometric normalisation

namespace {

// max_c |row_c| over the first `columns` entries; NaN if any of them is NaN.
double largest_magnitude(const Eigen::MatrixXd& values, Eigen::Index row, int64_t columns) {
  double largest = 0.0;
  for (Eigen::Index column = 0; column < columns; ++column) {
    const double magnitude = std::abs(values(row, column));
    if (std::isnan(magnitude)) return magnitude;
    largest = std::max(largest, magnitude);
  }
  return largest;
}

// Whether the averaged signals have settled: sliding sums over the two halves of the last
// 2h samples, updated in O(columns) per sample. Non-finite samples count as 0 in the sums
// and are counted apart (a NaN would otherwise spoil every later sum).
class SettleWindow {
 public:
  SettleWindow(const Eigen::MatrixXd& values, Eigen::Index half)
      : values_(values),
        half_(half),
        early_(Eigen::VectorXd::Zero(values.cols())),
        late_(Eigen::VectorXd::Zero(values.cols())) {}
  // Moves the window to end at sample n (called for n = 0, 1, 2, ...).
  void advance(Eigen::Index n) {
    if (half_ < 1) return;
    add(late_, n, +1.0);
    non_finite_ += non_finite(n);
    if (n - half_ >= 0) {
      add(late_, n - half_, -1.0);
      add(early_, n - half_, +1.0);
    }
    if (n - 2 * half_ >= 0) {
      add(early_, n - 2 * half_, -1.0);
      non_finite_ -= non_finite(n - 2 * half_);
    }
    filled_ = n + 1;
  }
  // Mean of each column over the early half (valid once settled() holds).
  Eigen::VectorXd early_mean() const { return early_ / static_cast<double>(half_); }
  bool has_halves() const { return half_ >= 1; }
  // True when every column's mean over the late half differs from the one over the early
  // half by less than tolerance · |baseline|, with no non-finite sample in either.
  bool settled(const Eigen::VectorXd& baseline, double tolerance) const {
    if (half_ < 1) return true;
    if (filled_ < 2 * half_ || non_finite_ > 0) return false;
    const Eigen::ArrayXd change = (late_ - early_).array().abs() / static_cast<double>(half_);
    return (change < tolerance * baseline.array().abs()).all();
  }

 private:
  void add(Eigen::VectorXd& sums, Eigen::Index n, double sign) {
    for (Eigen::Index column = 0; column < values_.cols(); ++column)
      if (std::isfinite(values_(n, column))) sums[column] += sign * values_(n, column);
  }
  int64_t non_finite(Eigen::Index n) const {
    return static_cast<int64_t>((!values_.row(n).array().isFinite()).count());
  }

  const Eigen::MatrixXd& values_;
  Eigen::Index half_;
  Eigen::VectorXd early_, late_;
  int64_t non_finite_ = 0;
  Eigen::Index filled_ = 0;
};

}  // namespace

RatiometricResult ratiometric_deviation(const Eigen::MatrixXd& averaged, double rate_hz,
                                        int64_t onset_columns, const FluxOptions& options) {
  const Eigen::Index count = averaged.rows();
  const Eigen::Index columns = averaged.cols();
  RatiometricResult result;
  result.deviation.resize(count, columns);
  result.invalid.assign(static_cast<size_t>(columns), false);
  if (count == 0) return result;

  const Eigen::Index startup = std::min<Eigen::Index>(options.average_window - 1, count - 1);
  Eigen::VectorXd baseline = averaged.row(startup).transpose();
  for (Eigen::Index column = 0; column < columns; ++column)
    for (Eigen::Index n = startup + 1; n < count && !std::isfinite(baseline[column]); ++n)
      baseline[column] = averaged(n, column);
  result.baseline_samples.push_back(startup);

  const double threshold = options.onset_threshold;
  const int64_t period = samples_of(options.baseline_period_s, rate_hz, 1);
  const int64_t quiet_needed = samples_of(options.baseline_quiet_s, rate_hz, 0);
  ExcitationDetector detector(samples_of(options.window_s, rate_hz, 1),
                              samples_of(options.refractory_quiet_s, rate_hz, 0), threshold);
  // Flux §5.3: r = y / V0, e = r - 1; a channel without a positive V0 is invalid.
  const auto normalise = [&](Eigen::Index n) {
    for (Eigen::Index column = 0; column < columns; ++column) {
      const double reference = baseline[column];
      if (reference <= 0.0) {
        result.invalid[size_t(column)] = true;
        result.deviation(n, column) = 0.0;
      } else {
        result.deviation(n, column) = averaged(n, column) / reference - 1.0;
      }
    }
  };
  SettleWindow settle(averaged, quiet_needed / 2);
  int64_t next_due = startup + period;
  int64_t quiet_run = 0;
  for (Eigen::Index n = 0; n < count; ++n) {
    normalise(n);
    settle.advance(n);
    quiet_run = largest_magnitude(result.deviation, n, columns) < threshold ? quiet_run + 1 : 0;
    if (n >= next_due && quiet_run >= quiet_needed && !detector.in_progress() &&
        averaged.row(n).allFinite() && settle.settled(baseline, options.baseline_settle)) {
      // The early half of the settled quiet time, not y[n]: the last samples may already
      // carry the start of the next touch, still under θ_on.
      baseline = settle.has_halves() ? settle.early_mean() : averaged.row(n).transpose();
      normalise(n);
      result.baseline_samples.push_back(n);
      next_due = n + period;
    }
    detector.step(largest_magnitude(result.deviation, n, onset_columns));
  }
  return result;
}

//---- Channels and the whole chain

FluxChannels flux_channels(const SkinLayout& layout) {
  std::unordered_set<int> owned;
  for (const Taxel& taxel : layout.taxels)
    for (int channel : taxel.channels)
      if (channel >= 0) owned.insert(channel);
  bool laid_out = layout.channels.size() == 10;
  for (int channel = 0; laid_out && channel < 10; ++channel)
    laid_out = (owned.count(channel) == 0) == (channel == 4 || channel == 9);
  if (!laid_out)
    throw Error("layout " + layout.id,
                "the flux chain needs 10 channels in spec §5.4 order: top 1-4 (taxels), top "
                "sum (virtual), bottom 1-4 (taxels), bottom sum (virtual)");
  FluxChannels channels;
  for (int channel = 0; channel < 4; ++channel) {
    channels.top.push_back(layout.channels[size_t(channel)].name);
    channels.bottom.push_back(layout.channels[size_t(channel + 5)].name);
  }
  channels.top_sum = layout.channels[4].name;
  channels.bottom_sum = layout.channels[9].name;
  return channels;
}

bool is_flux_preprocessed(const Recording& recording) {
  const auto found = recording.metadata.find(kPreprocessedKey);
  return found != recording.metadata.end() && found->second == kFluxPreprocessed;
}

namespace {

Eigen::Index column_of(const Stream& stream, const std::string& channel) {
  const auto found = std::find(stream.channels.begin(), stream.channels.end(), channel);
  return found == stream.channels.end() ? -1 : found - stream.channels.begin();
}

}  // namespace

Recording preprocess_flux(const Recording& recording, const SkinLayout& layout,
                          const FluxOptions& options) {
  const FluxChannels channels = flux_channels(layout);
  size_t stream_index = recording.streams.size();
  for (size_t index = 0; index < recording.streams.size(); ++index) {
    const Stream& stream = recording.streams[index];
    if (column_of(stream, channels.top.front()) < 0) continue;
    if (stream_index == recording.streams.size() || stream.name == "skin") stream_index = index;
  }
  if (stream_index == recording.streams.size())
    throw Error(recording.id, "no stream with flux channel " + channels.top.front());
  const Stream& raw = recording.streams[stream_index];
  const std::string where = recording.id + " stream " + raw.name;
  if (!(raw.rate_hz > 0.0)) throw Error(where, "the flux chain needs a regular sample rate");

  // Real channels, top layer first: the detector watches the first four.
  std::vector<std::string> real = channels.top;
  real.insert(real.end(), channels.bottom.begin(), channels.bottom.end());
  const Eigen::Index count = raw.sample_count();
  Eigen::MatrixXd averaged(count, static_cast<Eigen::Index>(real.size()));
  for (size_t channel = 0; channel < real.size(); ++channel) {
    const Eigen::Index column = column_of(raw, real[channel]);
    if (column < 0) throw Error(where, "no flux channel " + real[channel]);
    averaged.col(Eigen::Index(channel)) =
        causal_moving_average(raw.samples.col(column).cast<double>(), options.average_window);
  }
  const RatiometricResult normalised = ratiometric_deviation(averaged, raw.rate_hz, 4, options);
  const Eigen::MatrixXd& deviation = normalised.deviation;

  Stream processed;
  processed.name = raw.name;
  processed.rate_hz = raw.rate_hz;
  processed.start_time = raw.start_time;
  processed.timestamps = raw.timestamps;
  for (const Channel& channel : layout.channels) {
    processed.channels.push_back(channel.name);
    processed.units.push_back("1");  // relative change, dimensionless
  }
  processed.samples.resize(count, 10);
  processed.samples.leftCols(4) = deviation.leftCols(4).cast<float>();
  // Flux §5.4: virtual channel = sum of the normalised deviations of a layer.
  processed.samples.col(4) = deviation.leftCols(4).rowwise().sum().cast<float>();
  processed.samples.middleCols(5, 4) = deviation.rightCols(4).cast<float>();
  processed.samples.col(9) = deviation.rightCols(4).rowwise().sum().cast<float>();

  Recording result = recording;
  result.streams[stream_index] = std::move(processed);
  result.metadata[kPreprocessedKey] = kFluxPreprocessed;
  result.metadata["flux.baseline_samples"] = std::to_string(normalised.baseline_samples.size());
  std::string invalid;
  for (size_t channel = 0; channel < real.size(); ++channel)
    if (normalised.invalid[channel]) invalid += (invalid.empty() ? "" : " ") + real[channel];
  if (!invalid.empty()) result.metadata["flux.invalid_channels"] = invalid;
  return result;
}

}  // namespace tactile::dsp

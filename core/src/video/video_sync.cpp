// The skin's activity and the proposal of a video's offset from its correlation with the
// video's motion energy (motion_energy.cpp reads the video).
#include "tactile/video/video_sync.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "tactile/error.h"
#include "tactile/jobs/job.h"
#include "tactile/signal/display_scale.h"
#include "tactile/signal/sample_source.h"
#include "tactile/stats/statistics.h"
#include "tactile/text.h"

namespace tactile {
namespace {

// "12.34 s": the proposal's words.
std::string lag_text(double seconds) { return fixed_text(seconds, 2) + " s"; }

// `series` on a grid of `rate`, starting where it starts: each new step the mean of the old
// steps whose time falls in it (a step without any takes the previous step's value).
ActivitySeries resample(const ActivitySeries& series, double rate) {
  if (series.rate == rate || series.values.empty()) return series;
  ActivitySeries out{series.start, rate, {}};
  const double length = static_cast<double>(series.values.size()) / series.rate;
  const auto steps = static_cast<size_t>(std::max(1.0, std::floor(length * rate)));
  std::vector<double> sum(steps, 0.0);
  std::vector<int> count(steps, 0);
  for (size_t k = 0; k < series.values.size(); ++k) {
    const auto step = static_cast<size_t>(static_cast<double>(k) / series.rate * rate);
    if (step >= steps) break;
    sum[step] += series.values[k];
    ++count[step];
  }
  out.values.resize(steps);
  double previous = 0.0;
  for (size_t step = 0; step < steps; ++step) {
    if (count[step] > 0) previous = sum[step] / count[step];
    out.values[step] = previous;
  }
  return out;
}

struct Moments {
  double mean = 0.0;
  double spread = 0.0;  // population standard deviation
};

Moments moments(const double* values, size_t count) {
  if (count == 0) return {};
  const Eigen::Map<const Eigen::ArrayXd> x(values, static_cast<Eigen::Index>(count));
  const double mean = x.mean();
  return {mean, std::sqrt(std::max(0.0, (x - mean).square().mean()))};
}

// Nothing in `skin` stands out of its noise floor: no step reaches kTouchOverMedian times the
// median step (the noise of a quiet skin, summed over its channels).
bool shows_no_touches(const double* values, size_t count) {
  if (count == 0) return true;
  std::vector<double> copy(values, values + count);
  const double peak = *std::max_element(copy.begin(), copy.end());
  return peak <= kTouchOverMedian * stats::median(std::move(copy));
}

}  // namespace

//---- Skin activity

ActivitySeries skin_activity(const SampleSource& source, double rate,
                             const std::function<void(double)>& progress) {
  if (!(rate > 0)) throw Error("skin activity", "the rate must be positive");
  ActivitySeries series{source.start_time(), rate, {}};
  const int64_t count = source.sample_count();
  const int channels = source.channel_count();
  if (count < 2 || channels == 0) return series;
  // Each channel's noise sigma from the skin view's rest scale (band = 3 sigma, read from the
  // coarse data), floored at a quarter of the median channel's: a channel quiet to the last
  // bit must not turn its first touch into the loudest thing on the skin.
  std::vector<int> columns(static_cast<size_t>(channels));
  std::iota(columns.begin(), columns.end(), 0);
  const RestScale scale = rest_scale(source, columns);
  std::vector<double> sigmas;
  for (int c = 0; c < channels; ++c)
    if (std::isfinite(scale.rest[static_cast<size_t>(c)]) && scale.noise_band[c] > 0)
      sigmas.push_back(scale.noise_band[static_cast<size_t>(c)] / 3.0);
  const double typical = sigmas.empty() ? 1.0 : stats::median(sigmas);
  Eigen::ArrayXf weight(channels);
  for (int c = 0; c < channels; ++c) {
    const auto k = static_cast<size_t>(c);
    weight[c] = std::isfinite(scale.rest[k])
                    ? static_cast<float>(1.0 / std::max<double>(scale.noise_band[k] / 3.0,
                                                                kNoiseFloorOfTypical * typical))
                    : 0.0f;
  }

  const double first_time = source.time_of(0);
  const double last_time = source.time_of(count - 1);
  const auto steps = static_cast<size_t>(std::floor((last_time - first_time) * rate)) + 1;
  series.start = first_time;
  series.values.assign(steps, 0.0);
  // The change of each channel's moving mean over `lag` samples (a quarter of a grid step):
  // |x[i] - x[i - lag]| / lag, summed per step. Lag 1 sums every sample's change, which at a
  // high sample rate is mostly noise (1 kHz, 100 samples a step: the touches of a flux skin did
  // not stand out); the moving mean keeps a touch's change whole and its time to a quarter step,
  // and cuts the noise's share by the lag.
  const double sample_rate = source.info().rate_hz > 0 ? source.info().rate_hz
                                                       : static_cast<double>(count - 1) /
                                                             std::max(1e-9, last_time - first_time);
  const int64_t lag = std::max<int64_t>(1, std::llround(sample_rate / (4.0 * rate)));
  const int64_t block = std::max<int64_t>(256, (int64_t{1} << 20) / channels);
  for (int64_t first = lag; first < count; first += block) {
    if (cancel_requested()) throw Error("skin activity", "cancelled");
    const int64_t n = std::min(block, count - first);
    // Each block read with the `lag` samples before it.
    const SampleMatrix samples = source.read(columns, first - lag, n + lag);
    Eigen::ArrayXXf change = (samples.bottomRows(n) - samples.topRows(n)).array().abs();
    change = change.isFinite().select(change, 0.0f);  // a gap changes nothing
    const Eigen::ArrayXf per_sample =
        (change.rowwise() * weight.transpose()).rowwise().sum() / static_cast<float>(lag);
    for (int64_t i = 0; i < n; ++i) {
      const double t = source.time_of(first + i) - first_time;
      const auto step = std::min(steps - 1, static_cast<size_t>(std::max(0.0, t * rate)));
      series.values[step] += per_sample[i];
    }
    if (progress) progress(static_cast<double>(first + n) / static_cast<double>(count));
  }
  return series;
}

//---- The proposal

SyncProposal propose_offset(const ActivitySeries& skin, const ActivitySeries& motion, double centre,
                            double max_lag) {
  if (!(skin.rate > 0) || !(motion.rate > 0))
    throw Error("video sync", "an activity series without a rate");
  if (!(max_lag >= 0)) throw Error("video sync", "the lag range must not be negative");
  SyncProposal proposal;
  proposal.offset = centre;
  // Correlate at the coarser of the two rates.
  const double rate = std::min(skin.rate, motion.rate);
  const ActivitySeries a = resample(skin, rate);
  const ActivitySeries b = resample(motion, rate);
  const auto skin_steps = static_cast<int64_t>(a.values.size());
  const auto video_steps = static_cast<int64_t>(b.values.size());

  if (moments(b.values.data(), b.values.size()).spread < kMinMotion) {
    proposal.why = "the video shows almost no motion";
    return proposal;
  }
  if (shows_no_touches(a.values.data(), a.values.size())) {
    proposal.why = "the skin shows no touches";
    return proposal;
  }

  // Offsets on the grid o = d + n / rate, where the video's step m falls on the skin's step
  // m + n exactly (recording time = offset + video time).
  const double d = a.start - b.start;
  const auto lag_first = static_cast<int64_t>(std::ceil((centre - max_lag - d) * rate - 1e-9));
  const auto lag_last = static_cast<int64_t>(std::floor((centre + max_lag - d) * rate + 1e-9));
  auto overlap_of = [&](int64_t n) {
    return std::max<int64_t>(0, std::min(skin_steps, video_steps + n) - std::max<int64_t>(0, n));
  };
  // Correlations over less than half the longest overlap in the range are left out: a few
  // seconds of each correlate well by chance.
  int64_t longest = 0;
  for (int64_t n = lag_first; n <= lag_last; ++n) longest = std::max(longest, overlap_of(n));
  const int64_t shortest = std::max<int64_t>(3, (longest + 1) / 2);

  // Pearson's correlation over the overlap of each lag, each series standardised within that
  // overlap: the overlap changes with the lag, and a global mean would favour lags whose
  // overlap holds the busy part of both.
  const auto lags = static_cast<size_t>(std::max<int64_t>(0, lag_last - lag_first + 1));
  std::vector<double> correlation(lags, std::numeric_limits<double>::quiet_NaN());
  for (size_t j = 0; j < lags; ++j) {
    const int64_t n = lag_first + static_cast<int64_t>(j);
    const int64_t overlap = overlap_of(n);
    if (overlap < shortest) continue;
    const int64_t s0 = std::max<int64_t>(0, n);
    const Eigen::Map<const Eigen::ArrayXd> x(a.values.data() + s0, overlap);
    const Eigen::Map<const Eigen::ArrayXd> y(b.values.data() + (s0 - n), overlap);
    const Eigen::ArrayXd dx = x - x.mean();
    const Eigen::ArrayXd dy = y - y.mean();
    const double norm = std::sqrt(dx.square().sum() * dy.square().sum());
    if (norm > 0) correlation[j] = (dx * dy).sum() / norm;
  }
  size_t best = lags;
  for (size_t j = 0; j < lags; ++j)
    if (std::isfinite(correlation[j]) && (best == lags || correlation[j] > correlation[best]))
      best = j;
  if (best == lags) {
    proposal.why = "the video and the recording do not overlap at offsets within " +
                   lag_text(max_lag) + " of " + lag_text(centre);
    return proposal;
  }
  auto offset_of = [&](double j) { return d + (static_cast<double>(lag_first) + j) / rate; };

  // The peak refined between the grid steps by the parabola through it and its neighbours.
  double refined = static_cast<double>(best);
  const double peak = correlation[best];
  if (best > 0 && best + 1 < lags && std::isfinite(correlation[best - 1]) &&
      std::isfinite(correlation[best + 1])) {
    const double left = correlation[best - 1], right = correlation[best + 1];
    const double curvature = left - 2.0 * peak + right;
    if (curvature < 0) {
      const double shift = std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
      refined += shift;
    }
  }
  proposal.offset = offset_of(refined);
  proposal.correlation = std::clamp(correlation[best], -1.0, 1.0);

  // The best other peak: the highest local maximum (or end of the range) beyond
  // kSeparateSeconds of the best. A shoulder of the best peak is no rival.
  size_t second = lags;
  for (size_t j = 0; j < lags; ++j) {
    if (!std::isfinite(correlation[j])) continue;
    if (std::abs(offset_of(static_cast<double>(j)) - proposal.offset) <= kSeparateSeconds) continue;
    const bool left_ok =
        j == 0 || !std::isfinite(correlation[j - 1]) || correlation[j] >= correlation[j - 1];
    const bool right_ok =
        j + 1 == lags || !std::isfinite(correlation[j + 1]) || correlation[j] >= correlation[j + 1];
    if (left_ok && right_ok && (second == lags || correlation[j] > correlation[second])) second = j;
  }
  const double rival = second == lags ? 0.0 : std::max(0.0, correlation[second]);
  const double best_value = std::max(0.0, proposal.correlation);
  proposal.confidence =
      rival >= 1.0 ? 0.0 : std::clamp((best_value - rival) / (1.0 - rival), 0.0, 1.0);

  // What the overlap at the best offset holds.
  const auto best_lag = lag_first + static_cast<int64_t>(best);
  const int64_t overlap = overlap_of(best_lag);
  const int64_t s0 = std::max<int64_t>(0, best_lag);
  if (moments(b.values.data() + (s0 - best_lag), static_cast<size_t>(overlap)).spread <
      kMinMotion) {
    proposal.why = "the video shows almost no motion in the overlap";
  } else if (shows_no_touches(a.values.data() + s0, static_cast<size_t>(overlap))) {
    proposal.why = "the skin shows no touches in the overlap";
  } else if (static_cast<double>(overlap) / rate < kMinOverlapSeconds) {
    proposal.why = "the overlap at the best offset is under " + lag_text(kMinOverlapSeconds);
  } else if (proposal.correlation < kMinCorrelation) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the best correlation is weak (%.2f): the video's motion may not follow the "
                  "touches",
                  proposal.correlation);
    proposal.why = text;
  } else if (proposal.confidence < kSureConfidence) {
    proposal.why = "two offsets fit about equally: " + lag_text(proposal.offset) + " and " +
                   lag_text(offset_of(static_cast<double>(second)));
  }
  proposal.sure = proposal.why.empty();
  return proposal;
}

}  // namespace tactile

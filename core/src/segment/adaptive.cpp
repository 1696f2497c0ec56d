#include "tactile/segment/adaptive.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

struct AdaptiveOptions {
  double margin = 2.0;             // times the 3-sigma band: a taxel is off its rest
  int64_t taxels = 2;              // that many taxels on make a touch frame
  double alone = 2.0;              // or one taxel this many times past its band
  double share = 0.2;              // the band's share of the touch amplitude of the taxel's kind
  double footprint = 0.1;          // a touch frame has this share of a touch's channels on
  double join_seconds = -1.0;      // releases this short join contacts; < 0: from the signal
  double baseline_seconds = 20.0;  // the running median the rest follows
  double opening_seconds = 4.0;    // the lower envelope the rest of a one-way channel follows
  double envelope_seconds = 0.03;  // a taxel's excursion is its largest over this span
  double stuck_seconds = 1.0;      // an unchanging run this long is a stuck taxel (noisy ones)
  double max_seconds = 10.0;
  double min_seconds = 0.05;
};

AdaptiveOptions adaptive_options(const Parameters& parameters) {
  parameters.expect_only({"margin", "taxels", "alone", "share", "footprint", "join_seconds",
                          "quiet_seconds", "baseline_seconds", "opening_seconds",
                          "envelope_seconds", "stuck_seconds", "max_seconds", "min_seconds"});
  AdaptiveOptions options;
  options.margin = parameters.number("margin", options.margin);
  options.taxels = parameters.integer("taxels", options.taxels);
  options.alone = parameters.number("alone", options.alone);
  options.share = parameters.number("share", options.share);
  options.footprint = parameters.number("footprint", options.footprint);
  // quiet_seconds: the name join_seconds had before gesture-level touches.
  if (parameters.has("quiet_seconds") && parameters.has("join_seconds"))
    throw Error("parameter quiet_seconds", "is the old name of join_seconds: give one of them");
  options.join_seconds = parameters.has("quiet_seconds")
                             ? parameters.number("quiet_seconds", options.join_seconds)
                             : parameters.number("join_seconds", options.join_seconds);
  options.baseline_seconds = parameters.number("baseline_seconds", options.baseline_seconds);
  options.opening_seconds = parameters.number("opening_seconds", options.opening_seconds);
  options.envelope_seconds = parameters.number("envelope_seconds", options.envelope_seconds);
  options.stuck_seconds = parameters.number("stuck_seconds", options.stuck_seconds);
  options.max_seconds = parameters.number("max_seconds", options.max_seconds);
  options.min_seconds = parameters.number("min_seconds", options.min_seconds);
  if (!(options.margin > 0)) throw Error("parameter margin", "must be positive");
  if (options.taxels < 1) throw Error("parameter taxels", "must be at least 1");
  if (!(options.alone >= 1)) throw Error("parameter alone", "must be at least 1");
  if (!(options.share >= 0 && options.share < 1))
    throw Error("parameter share", "must lie in [0, 1)");
  if (!(options.footprint >= 0 && options.footprint <= 1))
    throw Error("parameter footprint", "must lie in [0, 1]");
  if (std::isnan(options.join_seconds))
    throw Error("parameter join_seconds", "must be a number (negative: chosen from the signal)");
  if (!(options.baseline_seconds > 0))
    throw Error("parameter baseline_seconds", "must be positive");
  if (!(options.opening_seconds >= 0))
    throw Error("parameter opening_seconds", "must not be negative");
  if (!(options.envelope_seconds >= 0))
    throw Error("parameter envelope_seconds", "must not be negative");
  if (!(options.stuck_seconds > 0)) throw Error("parameter stuck_seconds", "must be positive");
  if (!(options.max_seconds > 0)) throw Error("parameter max_seconds", "must be positive");
  if (!(options.min_seconds >= 0)) throw Error("parameter min_seconds", "must not be negative");
  return options;
}

// The rest of one channel at every frame: medians of short blocks, then a running quantile
// of those over `window` blocks, interpolated between block centres. The quantile sits on the
// side away from the channel's touches (0.25 when touches raise it), so a skin touched most of
// the time keeps its rest; a press shorter than the window's share leaves it where it was;
// drift slower than the window moves it.
std::vector<float> adaptive_baseline(const float* column, int64_t samples, int64_t block,
                                     int64_t window, double quantile, int direction,
                                     int64_t opening) {
  const int64_t blocks = (samples + block - 1) / block;
  std::vector<float> block_median(static_cast<size_t>(blocks), 0.0f);
  std::vector<float> values;
  // A block without a value (a stuck stretch) takes the nearest block's median before it, or
  // after it at the start.
  float last = std::numeric_limits<float>::quiet_NaN();
  for (int64_t b = 0; b < blocks; ++b) {
    values.clear();
    for (int64_t t = b * block; t < std::min(samples, (b + 1) * block); ++t)
      if (std::isfinite(column[t])) values.push_back(column[t]);
    if (!values.empty()) last = stats::median(values);
    block_median[static_cast<size_t>(b)] = last;
  }
  for (int64_t b = blocks - 1; b-- > 0;)
    if (std::isnan(block_median[static_cast<size_t>(b)]))
      block_median[static_cast<size_t>(b)] = block_median[static_cast<size_t>(b + 1)];
  std::vector<float> running(static_cast<size_t>(blocks));
  const int64_t half = window / 2;
  if (direction != 0 && opening > 0) {
    // The lower envelope (upper, for channels that touches lower): a morphological opening of
    // the block medians, a running minimum then a running maximum over `opening` blocks,
    // centred and cut short at the ends. It keeps any drift that rises or falls steadily, or
    // bends away from the touches, where it is, at every frame from the first to the last,
    // and removes every press shorter than the window.
    // Past each end the block medians are mirrored through the end (2 x(end) - x(end - k)),
    // so that a drift still rising or falling there keeps its slope to the last frame.
    const float sign = direction > 0 ? 1.0f : -1.0f;
    const int64_t reach = opening / 2;
    const int64_t padded = blocks + 4 * reach;
    std::vector<float> extended(static_cast<size_t>(padded)), eroded(static_cast<size_t>(padded));
    for (int64_t b = 0; b < padded; ++b) {
      const int64_t at = b - 2 * reach;
      const float value =
          at < 0 ? 2.0f * block_median.front() -
                       block_median[static_cast<size_t>(std::min(blocks - 1, -at))]
          : at >= blocks
              ? 2.0f * block_median.back() -
                    block_median[static_cast<size_t>(std::max<int64_t>(0, 2 * (blocks - 1) - at))]
              : block_median[static_cast<size_t>(at)];
      extended[static_cast<size_t>(b)] = sign * value;
    }
    for (int64_t b = 0; b < padded; ++b) {
      float least = std::numeric_limits<float>::infinity();
      for (int64_t u = std::max<int64_t>(0, b - reach); u <= std::min(padded - 1, b + reach); ++u)
        least = std::min(least, extended[static_cast<size_t>(u)]);
      eroded[static_cast<size_t>(b)] = least;
    }
    for (int64_t b = 0; b < blocks; ++b) {
      float most = -std::numeric_limits<float>::infinity();
      for (int64_t u = b + reach; u <= b + 3 * reach; ++u)
        most = std::max(most, eroded[static_cast<size_t>(u)]);
      running[static_cast<size_t>(b)] = sign * most;
    }
  }
  for (int64_t b = 0; b < blocks && !(direction != 0 && opening > 0); ++b) {
    // The window keeps its length at the ends of the recording.
    int64_t from = std::max<int64_t>(0, b - half);
    const int64_t to = std::min(blocks, from + window);
    from = std::max<int64_t>(0, to - window);
    values.assign(block_median.begin() + from, block_median.begin() + to);
    running[static_cast<size_t>(b)] = stats::nth_smallest(
        values,
        static_cast<size_t>(std::llround(quantile * static_cast<double>(values.size() - 1))));
  }
  std::vector<float> rest(static_cast<size_t>(samples));
  for (int64_t t = 0; t < samples; ++t) {
    const double position = (static_cast<double>(t) + 0.5) / static_cast<double>(block) - 0.5;
    const auto below =
        std::clamp<int64_t>(static_cast<int64_t>(std::floor(position)), 0, blocks - 1);
    const int64_t above = std::min(blocks - 1, below + 1);
    const double share = std::clamp(position - static_cast<double>(below), 0.0, 1.0);
    rest[static_cast<size_t>(t)] =
        static_cast<float>((1.0 - share) * running[static_cast<size_t>(below)] +
                           share * running[static_cast<size_t>(above)]);
  }
  return rest;
}

}  // namespace

// A channel's excursion where it can count: the runs of frames where it is past its noise
// band (the lowest band decide() can give it; margin x 3 sigma, 0 for a noiseless sensor),
// every other frame being at or below that. Kept this way a touched skin's excursions take a
// few MB where every frame of every channel took the recording's size again (207 MB for 30
// minutes of Robovie's 274 films).
struct SparseExcursion {
  bool counts = false;         // false: the channel is never on (unusable, stuck or dead)
  std::vector<int64_t> first;  // each run's first frame
  std::vector<size_t> begin;   // where each run's values start in `values`, then the end
  std::vector<float> values;

  // f(frame, value) for every kept value in frames [from, to].
  template <typename F>
  void each(int64_t from, int64_t to, F f) const {
    for (size_t run = 0; run < first.size(); ++run) {
      const int64_t start = first[run];
      const auto length = static_cast<int64_t>(begin[run + 1] - begin[run]);
      if (start + length <= from) continue;
      if (start > to) break;
      for (int64_t t = std::max(from, start); t <= std::min(to, start + length - 1); ++t)
        f(t, values[begin[run] + static_cast<size_t>(t - start)]);
    }
  }
};

struct AdaptiveScan {
  std::string recording;
  double rate = 0.0;
  int64_t samples = 0;
  std::vector<double> times;               // of each frame
  std::vector<SparseExcursion> moved;      // each channel's excursion past its noise band
  std::vector<float> sigmas;               // each channel's noise sigma
  std::vector<std::string> kinds;          // each channel's kind (modality|unit)
  std::map<std::string, float> amplitude;  // each kind's touch amplitude
  float noise_bands = 6.0f;                // margin x 3
  std::vector<std::vector<int>> group_channels;
  std::vector<std::string> group_ids;
};

namespace {

// What the scan reads: one stream, a whole channel at a time, from memory or from a file, so
// that it never holds more than a few channels.
struct ScanInput {
  std::string recording;
  std::string where;  // the stream, for errors
  double rate = 0.0;
  int64_t samples = 0;
  std::vector<std::string> channels;
  std::function<double(int64_t)> time_of;
  std::function<void(int, std::vector<float>&)> column;  // channel c's every sample into out
  std::function<void(double)> step;                      // the share read so far (may throw)
};

ScanInput scan_input(const Recording& recording) {
  if (recording.streams.empty()) throw Error(recording.id, "no stream to segment");
  const Stream& stream = recording.streams.front();
  ScanInput input;
  input.recording = recording.id;
  input.where = recording.id + ":/streams/" + stream.name;
  input.rate = stream.rate_hz;
  input.samples = stream.sample_count();
  input.channels = stream.channels;
  input.time_of = [&stream](int64_t t) { return stream.time_of(t); };
  input.column = [&stream](int c, std::vector<float>& out) {
    const float* values = stream.samples.col(c).data();
    out.assign(values, values + stream.sample_count());
  };
  return input;
}

ScanInput scan_input(const SampleSource& source, const std::function<void(double)>& step) {
  ScanInput input;
  input.recording = source.info().recording_id;
  input.where = input.recording + ":/streams/" + source.info().stream;
  input.rate = source.rate_hz();
  input.samples = source.sample_count();
  input.channels = source.info().channels;
  input.time_of = [&source](int64_t t) { return source.time_of(t); };
  input.column = [&source, samples = input.samples](int c, std::vector<float>& out) {
    const int channel[1] = {c};
    const SampleMatrix values = source.read(channel, 0, samples);
    out.assign(values.data(), values.data() + values.size());
  };
  input.step = step;
  return input;
}

// A noisy channel's runs of one unchanging value for `stuck` frames or more become missing
// (NaN), as do long runs of NaN; returns how often the value changes from one frame to the
// next outside the long runs (noise changes it nearly every frame, a noiseless sensor only at
// its edges).
double mask_stuck_runs(std::vector<float>& column, int64_t stuck) {
  const auto samples = static_cast<int64_t>(column.size());
  int64_t changes = 0, outside = 0;
  std::vector<std::pair<int64_t, int64_t>> long_runs;
  for (int64_t t = 0; t < samples;) {
    const float value = column[static_cast<size_t>(t)];
    int64_t end = t + 1;
    while (end < samples && (column[static_cast<size_t>(end)] == value ||
                             (std::isnan(column[static_cast<size_t>(end)]) && std::isnan(value))))
      ++end;
    if (end - t >= stuck) {
      long_runs.emplace_back(t, end);
    } else {
      outside += end - t;
      changes += 1;
    }
    t = end;
  }
  const double share =
      outside > 1 ? static_cast<double>(changes) / static_cast<double>(outside) : 0.0;
  const bool noisy = share >= 0.5;
  for (const auto& [from, to] : long_runs)
    if (noisy || std::isnan(column[static_cast<size_t>(from)]))
      std::fill(column.begin() + from, column.begin() + to,
                std::numeric_limits<float>::quiet_NaN());
  return share;
}

// The slow half: each channel's rest, noise, excursion and peak, and each kind's amplitude.
// Two passes over the channels, each reading one at a time: the first finds each channel's
// direction (which the skin's lends to channels without one), the second its excursion.
std::shared_ptr<AdaptiveScan> adaptive_scan(const ScanInput& input, const SkinLayout& layout,
                                            const AdaptiveOptions& options) {
  auto scan = std::make_shared<AdaptiveScan>();
  scan->recording = input.recording;
  if (!(input.rate > 0)) throw Error(input.where, "needs a sample rate");
  const double rate = input.rate;
  const int channels = static_cast<int>(input.channels.size());
  const int64_t samples = input.samples;
  scan->rate = rate;
  scan->samples = samples;
  scan->times.reserve(static_cast<size_t>(samples));
  for (int64_t t = 0; t < samples; ++t) scan->times.push_back(input.time_of(t));
  if (samples == 0) return scan;
  const auto report = [&](int pass, int c) {
    if (input.step) input.step((pass + static_cast<double>(c + 1) / channels) / 2.0);
  };
  const auto frames_of = [&](double seconds) {
    return std::max<int64_t>(1, std::llround(seconds * rate));
  };
  const int64_t block = frames_of(0.25);
  const int64_t window = std::max<int64_t>(3, std::llround(options.baseline_seconds / 0.25));
  const int64_t envelope = std::llround(options.envelope_seconds * rate / 2.0);
  const int64_t stuck = frames_of(options.stuck_seconds);
  const int64_t opening = std::llround(options.opening_seconds / 0.25);
  const int64_t peak_frames = std::llround(options.min_seconds * rate);

  // Each channel's excursion from its running rest, in its own units (its band is the fast
  // half's). A run of one unchanging value for stuck_seconds or more on a noisy channel is a stuck
  // taxel: missing everywhere below. A channel with no noise at all (binary, integer-step,
  // clipped at zero) holds its rest for long stretches by nature, so the rule skips it.
  std::vector<SparseExcursion>& score = scan->moved;
  score.resize(static_cast<size_t>(channels));
  std::vector<float> residual(static_cast<size_t>(samples));
  std::vector<float> deviations;
  std::vector<float> kept;
  std::vector<int> directions(static_cast<size_t>(channels), 0);
  std::vector<uint8_t> usable_channel(static_cast<size_t>(channels), 0);
  std::vector<double> change_share(static_cast<size_t>(channels), 0.0);
  for (int c = 0; c < channels; ++c) {
    input.column(c, kept);
    report(0, c);
    change_share[static_cast<size_t>(c)] = mask_stuck_runs(kept, stuck);
    const float* column = kept.data();
    // Which way touches move the channel: the side of its median with the longer tail, once
    // a running median over baseline_seconds is taken off (drift has no tail of its own; a
    // touch of several seconds, shorter than the window, keeps its tail).
    const std::vector<float> centred = adaptive_baseline(column, samples, block, window, 0.5, 0, 0);
    deviations.clear();
    for (int64_t t = 0; t < samples; ++t)
      if (std::isfinite(column[t]))
        deviations.push_back(column[t] - centred[static_cast<size_t>(t)]);
    if (deviations.size() < 3) continue;
    const float middle = stats::median(deviations);
    const size_t tail = (deviations.size() - 1) / 200;
    const float lowest = stats::nth_smallest(deviations, tail);
    const float highest = stats::nth_smallest(deviations, deviations.size() - 1 - tail);
    const float up = highest - middle, down = middle - lowest;
    directions[static_cast<size_t>(c)] = up > 2.0f * down ? 1 : down > 2.0f * up ? -1 : 0;
    usable_channel[static_cast<size_t>(c)] = 1;
  }
  // A channel that no touch reached clearly (no tail either way, as most taxels of a large
  // grid) takes the direction of the skin: the one at least nine in ten of the channels with
  // a direction share. Oscillating films have none, and keep both ways.
  {
    int64_t rising = 0, falling = 0;
    for (int direction : directions) rising += direction > 0, falling += direction < 0;
    const int skin_direction = 10 * rising >= 9 * (rising + falling) && rising > 0     ? 1
                               : 10 * falling >= 9 * (rising + falling) && falling > 0 ? -1
                                                                                       : 0;
    for (int& direction : directions)
      if (direction == 0) direction = skin_direction;
  }
  // Each channel's excursion in its own units (one-sided where touches move it one way),
  // closed over envelope_seconds, its noise sigma (0 for a noiseless sensor), and its peak:
  // the highest excursion it holds for min_seconds.
  std::vector<float>& sigmas = scan->sigmas;
  sigmas.assign(static_cast<size_t>(channels), 0.0f);
  const float noise_bands = static_cast<float>(options.margin * 3.0);
  scan->noise_bands = noise_bands;
  std::vector<float> peaks(static_cast<size_t>(channels), 0.0f);
  std::vector<float> moved, copy;
  for (int c = 0; c < channels; ++c) {
    if (!usable_channel[static_cast<size_t>(c)]) continue;
    input.column(c, kept);
    report(1, c);
    mask_stuck_runs(kept, stuck);
    const float* column = kept.data();
    const int direction = directions[static_cast<size_t>(c)];
    const std::vector<float> rest = adaptive_baseline(column, samples, block, window,
                                                      direction > 0   ? 0.25
                                                      : direction < 0 ? 0.75
                                                                      : 0.5,
                                                      direction, opening);
    for (int64_t t = 0; t < samples; ++t) {
      residual[static_cast<size_t>(t)] =
          std::isfinite(column[t]) ? column[t] - rest[static_cast<size_t>(t)] : 0.0f;
    }
    // Noise from one frame to the next (1.4826 x the MAD of the differences, over sqrt 2):
    // white noise gives its sigma, while touches, however much of the recording they fill,
    // and drift move too slowly to count.
    deviations.clear();
    for (int64_t t = 1; t < samples; ++t)
      if (std::isfinite(column[t]) && std::isfinite(column[t - 1]))
        deviations.push_back(column[t] - column[t - 1]);
    if (deviations.size() >= 3) {
      const float centre = stats::median(deviations);
      for (float& value : deviations) value = std::fabs(value - centre);
      sigmas[static_cast<size_t>(c)] = 1.4826f / std::sqrt(2.0f) * stats::median(deviations);
    }
    moved.assign(static_cast<size_t>(samples), 0.0f);
    for (int64_t t = 0; t < samples; ++t) {
      const float value = residual[static_cast<size_t>(t)];
      moved[static_cast<size_t>(t)] = direction > 0   ? std::max(0.0f, value)
                                      : direction < 0 ? std::max(0.0f, -value)
                                                      : std::fabs(value);
    }
    // A closing (running maximum, then running minimum, over envelope_seconds): oscillating
    // signals (piezo films) keep their level through zero crossings, and the edges stay put.
    if (envelope > 0) {
      std::vector<float> widest(moved.size()), closed(moved.size());
      for (int64_t t = 0; t < samples; ++t) {
        float most = 0.0f;
        for (int64_t u = std::max<int64_t>(0, t - envelope);
             u <= std::min(samples - 1, t + envelope); ++u)
          most = std::max(most, moved[static_cast<size_t>(u)]);
        widest[static_cast<size_t>(t)] = most;
      }
      for (int64_t t = 0; t < samples; ++t) {
        float least = widest[static_cast<size_t>(t)];
        for (int64_t u = std::max<int64_t>(0, t - envelope);
             u <= std::min(samples - 1, t + envelope); ++u)
          least = std::min(least, widest[static_cast<size_t>(u)]);
        closed[static_cast<size_t>(t)] = least;
      }
      moved = std::move(closed);
    }
    copy = moved;
    const auto index =
        static_cast<size_t>(std::max<int64_t>(0, samples - std::max<int64_t>(1, peak_frames)));
    peaks[static_cast<size_t>(c)] = stats::nth_smallest(copy, index);
    // Kept where past the noise band: every band decide() gives is at least that.
    SparseExcursion& sparse = score[static_cast<size_t>(c)];
    sparse.counts = true;
    const float floor = noise_bands * sigmas[static_cast<size_t>(c)];
    for (int64_t t = 0; t < samples; ++t) {
      if (!(moved[static_cast<size_t>(t)] > floor)) continue;
      if (sparse.first.empty() ||
          sparse.first.back() + static_cast<int64_t>(sparse.values.size() - sparse.begin.back()) !=
              t) {
        sparse.first.push_back(t);
        sparse.begin.push_back(sparse.values.size());
      }
      sparse.values.push_back(moved[static_cast<size_t>(t)]);
    }
    sparse.begin.push_back(sparse.values.size());
  }
  // A noisy channel with a tenth of the median noisy channel's sigma or less, changing
  // smoothly, is stuck under a drifting offset, or dead: it never counts.
  {
    std::vector<float> noises;
    for (int c = 0; c < channels; ++c)
      if (score[static_cast<size_t>(c)].counts && sigmas[static_cast<size_t>(c)] > 0)
        noises.push_back(sigmas[static_cast<size_t>(c)]);
    if (noises.size() >= 3) {
      const float typical_noise = stats::median(noises);
      for (int c = 0; c < channels; ++c)
        if (sigmas[static_cast<size_t>(c)] < 0.1f * typical_noise &&
            change_share[static_cast<size_t>(c)] >= 0.5)
          score[static_cast<size_t>(c)] = SparseExcursion();
    }
  }

  // The band of each channel: its noise band (margin x 3 sigma) or `share` of the touch
  // amplitude of its kind, whichever is higher. A channel's peak is the highest excursion it
  // holds for min_seconds; the touch amplitude of a kind (the layout's modality and unit: one
  // scale) is the 95th percentile of the peaks of its channels that left their noise band.
  // So a noiseless sensor (binary, integer steps) is on past a fifth of its kind's press, an
  // 8-bit grid past a fifth of its full presses (crosstalk and a resting hand stay below),
  // and a noisy analog skin past its noise.
  std::map<std::string, std::string> kind_of_name;
  for (const Channel& channel : layout.channels)
    kind_of_name[channel.name] = channel.modality + "|" + channel.unit;
  std::vector<std::string>& kinds = scan->kinds;
  kinds.resize(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) {
    const auto found = kind_of_name.find(input.channels[static_cast<size_t>(c)]);
    if (found != kind_of_name.end()) kinds[static_cast<size_t>(c)] = found->second;
  }
  std::map<std::string, std::vector<float>> kind_peaks;
  for (int c = 0; c < channels; ++c) {
    if (!score[static_cast<size_t>(c)].counts) continue;
    if (peaks[static_cast<size_t>(c)] > noise_bands * sigmas[static_cast<size_t>(c)])
      kind_peaks[kinds[static_cast<size_t>(c)]].push_back(peaks[static_cast<size_t>(c)]);
  }
  std::map<std::string, float>& amplitude = scan->amplitude;
  for (auto& [kind, values] : kind_peaks)
    amplitude[kind] = stats::nth_smallest(
        values, static_cast<size_t>(std::llround(0.95 * static_cast<double>(values.size() - 1))));
  // Which group a channel's taxel belongs to, for the region.
  std::map<std::string, int> channel_of_name;
  for (int c = 0; c < channels; ++c) channel_of_name[input.channels[static_cast<size_t>(c)]] = c;
  std::vector<std::vector<int>>& group_channels = scan->group_channels;
  group_channels.resize(layout.groups.size());
  for (const auto& group : layout.groups) scan->group_ids.push_back(group.id);
  for (size_t g = 0; g < layout.groups.size(); ++g)
    for (int64_t taxel_id : layout.groups[g].taxels)
      if (const Taxel* taxel = layout.find_taxel(taxel_id))
        for (int channel : taxel->channels)
          if (channel >= 0 && channel < static_cast<int>(layout.channels.size())) {
            const auto found =
                channel_of_name.find(layout.channels[static_cast<size_t>(channel)].name);
            if (found != channel_of_name.end()) group_channels[g].push_back(found->second);
          }
  return scan;
}

// The fast half: bands from the touch amplitude, touch frames, contacts joined into touches.
std::vector<Label> adaptive_decide(const AdaptiveScan& scan, const AdaptiveOptions& options) {
  const int64_t samples = scan.samples;
  if (samples == 0) return {};
  const double rate = scan.rate;
  const int channels = static_cast<int>(scan.moved.size());
  const auto frames_of = [&](double seconds) {
    return std::max<int64_t>(1, std::llround(seconds * rate));
  };
  // Each channel's band (0: never on); its excursion over the band is > 1 where it is on.
  const std::vector<SparseExcursion>& moved = scan.moved;
  std::vector<float> bands(static_cast<size_t>(channels), 0.0f);
  const std::vector<float>& sigmas = scan.sigmas;
  const std::vector<std::string>& kinds = scan.kinds;
  const float noise_bands = scan.noise_bands;
  const auto& amplitude = scan.amplitude;
  const auto& group_channels = scan.group_channels;
  int usable = 0;
  for (int c = 0; c < channels; ++c) {
    if (!moved[static_cast<size_t>(c)].counts) continue;
    const auto found = amplitude.find(kinds[static_cast<size_t>(c)]);
    const float band = std::max(
        noise_bands * sigmas[static_cast<size_t>(c)],
        static_cast<float>(options.share) * (found == amplitude.end() ? 0.0f : found->second));
    if (!(band > 0)) continue;  // a channel of a kind no touch moved: never on
    bands[static_cast<size_t>(c)] = band;
    ++usable;
  }

  // Touch frames: as many channels on as a tenth (`footprint`) of a touch's footprint on this
  // skin, `taxels` (2) at least, where one channel `alone` times past its band stands for
  // `taxels`. The footprint is the median number of channels on, over the frames with any on:
  // where hands cover a hundred taxels of a 19 x 27 grid, a few lingering ones between two
  // touches are no touch; where fingertips and palms mix, the typical touch is small and a
  // fingertip still counts; on a strip of eight sensors a touch is one or two.
  // A contact is a run of touch frames, its edges moved out while half as many channels stay
  // on (one, on a skin whose touches need two).
  const float alone = static_cast<float>(options.alone);
  std::vector<int64_t> on_count(static_cast<size_t>(samples), 0),
      strong(static_cast<size_t>(samples), 0);
  for (int c = 0; c < channels; ++c) {
    const float band = bands[static_cast<size_t>(c)];
    if (!(band > 0)) continue;
    moved[static_cast<size_t>(c)].each(0, samples - 1, [&](int64_t t, float value) {
      on_count[static_cast<size_t>(t)] += value > band;
      strong[static_cast<size_t>(t)] += value > alone * band;
    });
  }
  int64_t needed = std::min<int64_t>(options.taxels, std::max(1, usable));
  {
    std::vector<float> counts;
    for (int64_t count : on_count)
      if (count > 0) counts.push_back(static_cast<float>(count));
    if (!counts.empty()) {
      const float footprint = stats::nth_smallest(counts, (counts.size() - 1) / 2);
      needed = std::max<int64_t>(
          needed, static_cast<int64_t>(std::ceil(options.footprint * footprint - 1e-9)));
    }
  }
  const int64_t stands_for = std::min<int64_t>(options.taxels, needed);
  std::vector<uint8_t> touching(static_cast<size_t>(samples), 0),
      any_on(static_cast<size_t>(samples), 0);
  for (int64_t t = 0; t < samples; ++t) {
    const auto at = static_cast<size_t>(t);
    touching[at] = on_count[at] + strong[at] * (stands_for - 1) >= needed;
    any_on[at] = on_count[at] + strong[at] * (stands_for - 1) >= std::max<int64_t>(1, needed / 2);
  }
  std::vector<std::pair<int64_t, int64_t>> contacts;
  for (int64_t t = 0; t < samples; ++t) {
    if (!touching[static_cast<size_t>(t)]) continue;
    int64_t first = t, last = t;
    while (last + 1 < samples && touching[static_cast<size_t>(last + 1)]) ++last;
    t = last;
    while (first > 0 && any_on[static_cast<size_t>(first - 1)]) --first;
    while (last + 1 < samples && any_on[static_cast<size_t>(last + 1)]) ++last;
    if (!contacts.empty() && first <= contacts.back().second + 1)
      contacts.back().second = std::max(contacts.back().second, last);
    else
      contacts.emplace_back(first, last);
    t = std::max(t, last);
  }
  // A touch is a gesture instance: contacts whose release is at most `join` frames are one.
  // From the signal, join is a quarter of the median contact's length (at least one frame, at
  // most half a second: a lift inside one gesture is brief, however long its contacts):
  // the fingers of a tickle, a stroke that lifts and lands again, a squeeze that eases. A
  // release as long as a contact itself (repeated pulses, taps) still separates touches.
  int64_t join = 0;
  if (options.join_seconds >= 0) {
    join = std::llround(options.join_seconds * rate);
  } else if (!contacts.empty()) {
    std::vector<float> lengths;
    for (const auto& [first, last] : contacts)
      lengths.push_back(static_cast<float>(last - first + 1));
    join = std::max<int64_t>(1, std::min(static_cast<int64_t>(0.25 * stats::median(lengths)),
                                         static_cast<int64_t>(0.5 * rate)));
  }
  std::vector<std::pair<int64_t, int64_t>> parts;
  for (const auto& contact : contacts) {
    if (!parts.empty() && contact.first - parts.back().second - 1 <= join)
      parts.back().second = contact.second;
    else
      parts.push_back(contact);
  }

  const int64_t longest = frames_of(options.max_seconds);
  std::vector<Label> labels;
  for (const auto& [part_first, part_last] : parts) {
    for (int64_t first = part_first; first <= part_last; first += longest) {
      const int64_t last = std::min(part_last, first + longest - 1);
      const double t0 = scan.times[static_cast<size_t>(first)];
      const double t1 = scan.times[static_cast<size_t>(last)] + 1.0 / rate;
      if (t1 - t0 < options.min_seconds - 1e-9) continue;
      Label label;
      label.recording = scan.recording;
      label.t0 = t0;
      label.t1 = t1;
      label.class_name = kUnknownClass;
      label.note = last < part_last ? "forced" : last + 1 >= samples ? "open" : "quiet";
      // The group whose channels left their band the most, summed over the segment.
      double best = 0.0;
      for (size_t g = 0; g < group_channels.size(); ++g) {
        double past = 0.0;
        for (int c : group_channels[g]) {
          const float band = bands[static_cast<size_t>(c)];
          if (!(band > 0)) continue;
          moved[static_cast<size_t>(c)].each(first, last, [&](int64_t, float value) {
            past += std::max(0.0f, value / band - 1.0f);
          });
        }
        if (past > best) best = past, label.region = scan.group_ids[g];
      }
      labels.push_back(std::move(label));
    }
  }
  return labels;
}

}  // namespace

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters) {
  const AdaptiveOptions options = adaptive_options(parameters);
  return adaptive_decide(*adaptive_scan(scan_input(recording), layout, options), options);
}

std::vector<Label> segment_adaptive(const SampleSource& source, const SkinLayout& layout,
                                    const Parameters& parameters,
                                    const std::function<void(double)>& step) {
  const AdaptiveOptions options = adaptive_options(parameters);
  return adaptive_decide(*adaptive_scan(scan_input(source, step), layout, options), options);
}

AdaptiveSegmenter::AdaptiveSegmenter(const Recording& recording, const SkinLayout& layout,
                                     const Parameters& slow)
    : scan_(adaptive_scan(scan_input(recording), layout, adaptive_options(slow))), slow_(slow) {
  for (const std::string& key : adaptive_fast_parameters())
    if (slow.has(key))
      throw Error("parameter " + key, "is chosen per run, not when the recording is scanned");
}

std::vector<Label> AdaptiveSegmenter::segments(const Parameters& fast) const {
  for (const auto& [key, value] : fast.values())
    if (std::find(adaptive_fast_parameters().begin(), adaptive_fast_parameters().end(), key) ==
        adaptive_fast_parameters().end())
      throw Error("parameter " + key, "needs a new scan of the recording (AdaptiveSegmenter)");
  Parameters all = slow_;
  for (const auto& [key, value] : fast.values()) all.set(key, value);
  return adaptive_decide(*scan_, adaptive_options(all));
}

const std::vector<std::string>& adaptive_fast_parameters() {
  static const std::vector<std::string> keys = {
      "taxels", "alone", "share", "footprint", "join_seconds", "quiet_seconds", "max_seconds"};
  return keys;
}

}  // namespace tactile

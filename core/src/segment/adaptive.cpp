#include "tactile/segment/adaptive.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "tactile/error.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace {

struct AdaptiveOptions {
  double margin = 2.0;             // times the 3-sigma band: a taxel is off its rest
  int64_t taxels = 2;              // that many taxels off their rest make a touch frame
  double alone = 2.0;              // or one taxel this many times further
  double level = 0.3;              // share of the touch level a touch needs somewhere
  double dip = 0.2;                // a release: the excursion below this share of both peaks
  double baseline_seconds = 20.0;  // the running median the rest follows
  double opening_seconds = 4.0;    // the lower envelope the rest of a one-way channel follows
  double envelope_seconds = 0.03;  // a taxel's excursion is its largest over this span
  double stuck_seconds = 1.0;      // an unchanging run this long is a stuck taxel
  double quiet_seconds = 0.02;     // gaps this short inside a touch are bridged
  double max_seconds = 10.0;
  double min_seconds = 0.05;
};

AdaptiveOptions adaptive_options(const Parameters& parameters) {
  parameters.expect_only({"margin", "taxels", "alone", "level", "dip", "baseline_seconds",
                          "opening_seconds", "envelope_seconds", "stuck_seconds", "quiet_seconds",
                          "max_seconds", "min_seconds"});
  AdaptiveOptions options;
  options.margin = parameters.number("margin", options.margin);
  options.taxels = parameters.integer("taxels", options.taxels);
  options.alone = parameters.number("alone", options.alone);
  options.level = parameters.number("level", options.level);
  options.dip = parameters.number("dip", options.dip);
  options.baseline_seconds = parameters.number("baseline_seconds", options.baseline_seconds);
  options.opening_seconds = parameters.number("opening_seconds", options.opening_seconds);
  options.envelope_seconds = parameters.number("envelope_seconds", options.envelope_seconds);
  options.stuck_seconds = parameters.number("stuck_seconds", options.stuck_seconds);
  options.quiet_seconds = parameters.number("quiet_seconds", options.quiet_seconds);
  options.max_seconds = parameters.number("max_seconds", options.max_seconds);
  options.min_seconds = parameters.number("min_seconds", options.min_seconds);
  if (!(options.margin > 0)) throw Error("parameter margin", "must be positive");
  if (options.taxels < 1) throw Error("parameter taxels", "must be at least 1");
  if (!(options.alone >= 1)) throw Error("parameter alone", "must be at least 1");
  if (!(options.level >= 0 && options.level < 1))
    throw Error("parameter level", "must lie in [0, 1)");
  if (!(options.dip >= 0 && options.dip < 1)) throw Error("parameter dip", "must lie in [0, 1)");
  if (!(options.baseline_seconds > 0))
    throw Error("parameter baseline_seconds", "must be positive");
  if (!(options.opening_seconds >= 0))
    throw Error("parameter opening_seconds", "must not be negative");
  if (!(options.envelope_seconds >= 0))
    throw Error("parameter envelope_seconds", "must not be negative");
  if (!(options.stuck_seconds > 0)) throw Error("parameter stuck_seconds", "must be positive");
  if (!(options.quiet_seconds >= 0)) throw Error("parameter quiet_seconds", "must not be negative");
  if (!(options.max_seconds > 0)) throw Error("parameter max_seconds", "must be positive");
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

// Splits [first, last] at its deepest release, recursively: a frame whose excursion is below
// `dip` times the smaller of the highest excursions on either side.
void adaptive_split(const std::vector<float>& excursion, int64_t first, int64_t last, double dip,
                    int64_t shortest, std::vector<std::pair<int64_t, int64_t>>& parts) {
  if (last - first + 1 < 2 * shortest + 1) {
    parts.emplace_back(first, last);
    return;
  }
  const auto count = static_cast<size_t>(last - first + 1);
  std::vector<float> left(count), right(count);
  for (size_t k = 0; k < count; ++k)
    left[k] = std::max(k ? left[k - 1] : 0.0f, excursion[static_cast<size_t>(first) + k]);
  for (size_t k = count; k-- > 0;)
    right[k] =
        std::max(k + 1 < count ? right[k + 1] : 0.0f, excursion[static_cast<size_t>(first) + k]);
  double deepest = dip;
  int64_t at = -1;
  for (int64_t t = first + shortest; t <= last - shortest; ++t) {
    const auto k = static_cast<size_t>(t - first);
    const float peak = std::min(left[k], right[k]);
    if (!(peak > 0)) continue;
    const double ratio = excursion[static_cast<size_t>(t)] / peak;
    if (ratio < deepest) deepest = ratio, at = t;
  }
  if (at < 0) {
    parts.emplace_back(first, last);
    return;
  }
  // The release frames around the deepest one go to neither touch.
  int64_t end_left = at - 1, start_right = at + 1;
  const float release = excursion[static_cast<size_t>(at)];
  const auto near_release = [&](int64_t t) {
    return excursion[static_cast<size_t>(t)] <= release * 1.0001f + 1e-6f;
  };
  while (end_left > first && near_release(end_left)) --end_left;
  while (start_right < last && near_release(start_right)) ++start_right;
  adaptive_split(excursion, first, end_left, dip, shortest, parts);
  adaptive_split(excursion, start_right, last, dip, shortest, parts);
}

}  // namespace

std::vector<Label> segment_adaptive(const Recording& recording, const SkinLayout& layout,
                                    const Parameters& parameters) {
  const AdaptiveOptions options = adaptive_options(parameters);
  if (recording.streams.empty()) throw Error(recording.id, "no stream to segment");
  const Stream& stream = recording.streams.front();
  if (!(stream.rate_hz > 0)) throw Error(recording.id + ":/streams/" + stream.name, "needs a sample rate");
  const double rate = stream.rate_hz;
  const int channels = static_cast<int>(stream.channel_count());
  const int64_t samples = stream.sample_count();
  if (samples == 0) return {};
  const auto frames_of = [&](double seconds) {
    return std::max<int64_t>(1, std::llround(seconds * rate));
  };
  const int64_t block = frames_of(0.25);
  const int64_t window = std::max<int64_t>(3, std::llround(options.baseline_seconds / 0.25));
  const int64_t envelope = std::llround(options.envelope_seconds * rate / 2.0);
  const int64_t stuck = frames_of(options.stuck_seconds);
  const int64_t opening = std::llround(options.opening_seconds / 0.25);
  const int64_t peak_frames = std::llround(options.min_seconds * rate);
  const float on = static_cast<float>(options.margin * 3.0);  // in noise sigmas

  // Each channel's excursion from its running rest, in its own noise sigmas (1.4826 MAD of
  // the residual); 0 where the channel holds one value for stuck_seconds or more (a stuck or
  // dead taxel), and everywhere for a channel without noise (it never moves).
  std::vector<std::vector<float>> score(static_cast<size_t>(channels));
  std::vector<float> residual(static_cast<size_t>(samples));
  std::vector<float> deviations;
  std::vector<std::vector<float>> kept_columns(static_cast<size_t>(channels));
  std::vector<int> directions(static_cast<size_t>(channels), 0);
  std::vector<uint8_t> usable_channel(static_cast<size_t>(channels), 0);
  for (int c = 0; c < channels; ++c) {
    // Runs of one unchanging value for stuck_seconds or more: a stuck or dead taxel. They
    // count as missing everywhere below (rest, direction, noise) and never as a touch.
    const float* raw = stream.samples.col(c).data();
    std::vector<float>& kept = kept_columns[static_cast<size_t>(c)];
    kept.assign(raw, raw + samples);
    for (int64_t t = 0; t < samples;) {
      int64_t end = t + 1;
      while (end < samples && raw[end] == raw[t]) ++end;
      if (end - t >= stuck)
        std::fill(kept.begin() + t, kept.begin() + end, std::numeric_limits<float>::quiet_NaN());
      t = end;
    }
    const float* column = kept.data();
    // Which way touches move the channel: the side of its median with the longer tail, once
    // a running median over the opening window is taken off (drift has no tail of its own).
    const std::vector<float> centred =
        adaptive_baseline(column, samples, block, opening > 0 ? opening : window, 0.5, 0, 0);
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
  std::vector<float> sigmas(static_cast<size_t>(channels), 0.0f);
  for (int c = 0; c < channels; ++c) {
    if (!usable_channel[static_cast<size_t>(c)]) continue;
    const float* column = kept_columns[static_cast<size_t>(c)].data();
    const int direction = directions[static_cast<size_t>(c)];
    const std::vector<float> rest = adaptive_baseline(column, samples, block, window,
                                                      direction > 0   ? 0.25
                                                      : direction < 0 ? 0.75
                                                                      : 0.5,
                                                      direction, opening);

    deviations.clear();
    for (int64_t t = 0; t < samples; ++t) {
      residual[static_cast<size_t>(t)] =
          std::isfinite(column[t]) ? column[t] - rest[static_cast<size_t>(t)] : 0.0f;
      if (std::isfinite(column[t])) deviations.push_back(residual[static_cast<size_t>(t)]);
    }
    const float centre = stats::median(deviations);
    for (float& value : deviations) value = std::fabs(value - centre);
    float sigma = 1.4826f * stats::median(deviations);
    if (!(sigma > 0)) {
      // Quantised quiet channels: the median change between frames tells the step.
      deviations.clear();
      for (int64_t t = 1; t < samples; ++t)
        if (column[t] != column[t - 1] && std::isfinite(column[t]) && std::isfinite(column[t - 1]))
          deviations.push_back(std::fabs(column[t] - column[t - 1]));
      if (deviations.size() < 3) continue;
      sigma = stats::median(deviations);
    }
    sigmas[static_cast<size_t>(c)] = sigma;
    std::vector<float>& z = score[static_cast<size_t>(c)];
    z.assign(static_cast<size_t>(samples), 0.0f);
    // One-sided for a channel that touches move one way: the other way is no touch.
    for (int64_t t = 0; t < samples; ++t) {
      const float moved = residual[static_cast<size_t>(t)];
      z[static_cast<size_t>(t)] = (direction > 0   ? std::max(0.0f, moved)
                                   : direction < 0 ? std::max(0.0f, -moved)
                                                   : std::fabs(moved)) /
                                  sigma;
    }
    // A closing (running maximum, then running minimum, over envelope_seconds): oscillating
    // signals (piezo films) keep their level through zero crossings, and the edges stay put.
    if (envelope > 0) {
      std::vector<float> widest(z.size()), closed(z.size());
      for (int64_t t = 0; t < samples; ++t) {
        float most = 0.0f;
        for (int64_t u = std::max<int64_t>(0, t - envelope);
             u <= std::min(samples - 1, t + envelope); ++u)
          most = std::max(most, z[static_cast<size_t>(u)]);
        widest[static_cast<size_t>(t)] = most;
      }
      for (int64_t t = 0; t < samples; ++t) {
        float least = widest[static_cast<size_t>(t)];
        for (int64_t u = std::max<int64_t>(0, t - envelope);
             u <= std::min(samples - 1, t + envelope); ++u)
          least = std::min(least, widest[static_cast<size_t>(u)]);
        closed[static_cast<size_t>(t)] = least;
      }
      z = std::move(closed);
    }
  }
  // A channel with almost no noise of its own (a tenth of the median channel's, or less) is
  // stuck under a drifting offset, or dead: it never counts.
  {
    std::vector<float> noises;
    for (int c = 0; c < channels; ++c)
      if (!score[static_cast<size_t>(c)].empty()) noises.push_back(sigmas[static_cast<size_t>(c)]);
    if (noises.size() >= 3) {
      const float typical_noise = stats::median(noises);
      for (int c = 0; c < channels; ++c)
        if (sigmas[static_cast<size_t>(c)] < 0.1f * typical_noise)
          score[static_cast<size_t>(c)].clear();
    }
  }

  // The touch level: each moving channel's peak, the highest z it holds for min_seconds (a
  // channel touched once, briefly, keeps its press's level); the median of those stands in
  // for channels that only a resting hand reached. A touch needs, somewhere, `taxels` channels
  // past `level` times that; a low broad press between touches never gets there.
  std::vector<float> high(static_cast<size_t>(channels), 0.0f);
  std::vector<float> levels;
  int usable = 0;
  for (int c = 0; c < channels; ++c) {
    std::vector<float>& z = score[static_cast<size_t>(c)];
    if (z.empty()) continue;
    ++usable;
    std::vector<float> copy = z;
    const auto index = static_cast<size_t>(std::max<int64_t>(
        0, static_cast<int64_t>(copy.size()) - std::max<int64_t>(1, peak_frames)));
    high[static_cast<size_t>(c)] = stats::nth_smallest(copy, index);
    if (high[static_cast<size_t>(c)] > on) levels.push_back(high[static_cast<size_t>(c)]);
  }
  const float typical = levels.empty() ? on : stats::median(levels);
  const int64_t needed = std::min<int64_t>(options.taxels, std::max(1, usable));
  const float alone = static_cast<float>(options.alone) * on;
  std::vector<uint8_t> low(static_cast<size_t>(samples), 0), core(static_cast<size_t>(samples), 0);
  std::vector<float> excursion(static_cast<size_t>(samples), 0.0f);
  {
    std::vector<int64_t> above(static_cast<size_t>(samples), 0),
        strong(static_cast<size_t>(samples), 0);
    for (int c = 0; c < channels; ++c) {
      const std::vector<float>& z = score[static_cast<size_t>(c)];
      if (z.empty()) continue;
      const float touch_level = std::max(
          on, static_cast<float>(options.level) * std::max(high[static_cast<size_t>(c)], typical));
      for (int64_t t = 0; t < samples; ++t) {
        const float value = z[static_cast<size_t>(t)];
        // One channel far past its band counts as many (a touch on one large taxel).
        above[static_cast<size_t>(t)] += value > alone ? needed : value > on;
        strong[static_cast<size_t>(t)] +=
            value > std::max(alone, touch_level) ? needed : value > touch_level;
        // The excursion beyond the noise band, capped at a channel's touch level so that one
        // wild channel cannot hide a release.
        excursion[static_cast<size_t>(t)] +=
            std::clamp(value - on, 0.0f, std::max(high[static_cast<size_t>(c)], on));
      }
    }
    for (int64_t t = 0; t < samples; ++t) {
      low[static_cast<size_t>(t)] = above[static_cast<size_t>(t)] >= needed;
      core[static_cast<size_t>(t)] = strong[static_cast<size_t>(t)] >= needed;
    }
  }

  // Runs of frames with `taxels` channels off rest, bridged over gaps up to quiet_seconds, kept
  // when they reach the touch level somewhere; then split at releases.
  const int64_t bridge = std::llround(options.quiet_seconds * rate);
  std::vector<std::pair<int64_t, int64_t>> runs;
  for (int64_t t = 0; t < samples;) {
    if (!low[static_cast<size_t>(t)]) {
      ++t;
      continue;
    }
    int64_t end = t;
    for (;;) {
      while (end + 1 < samples && low[static_cast<size_t>(end + 1)]) ++end;
      int64_t next = end + 1;
      while (next < samples && next - end - 1 < bridge && !low[static_cast<size_t>(next)]) ++next;
      if (next < samples && next - end - 1 <= bridge && low[static_cast<size_t>(next)] &&
          next > end + 1) {
        end = next;
        continue;
      }
      break;
    }
    if (std::any_of(core.begin() + t, core.begin() + end + 1, [](uint8_t v) { return v != 0; }))
      runs.emplace_back(t, end);
    t = end + 1;
  }
  std::vector<std::pair<int64_t, int64_t>> parts;
  const int64_t shortest = std::max<int64_t>(1, std::llround(options.min_seconds * rate));
  for (const auto& [first, last] : runs) {
    // Touch-level stretches inside the run, bridged over quiet_seconds: each gap between two is
    // a release, cut at its lowest frame.
    std::vector<std::pair<int64_t, int64_t>> pressed;
    for (int64_t t = first; t <= last; ++t) {
      if (!core[static_cast<size_t>(t)]) continue;
      if (!pressed.empty() && t - pressed.back().second - 1 <= bridge)
        pressed.back().second = t;
      else
        pressed.emplace_back(t, t);
    }
    int64_t start = first;
    for (size_t k = 0; k + 1 < pressed.size(); ++k) {
      int64_t lowest = pressed[k].second + 1;
      for (int64_t t = lowest; t < pressed[k + 1].first; ++t)
        if (excursion[static_cast<size_t>(t)] < excursion[static_cast<size_t>(lowest)]) lowest = t;
      if (lowest - 1 >= start)
        adaptive_split(excursion, start, lowest - 1, options.dip, shortest, parts);
      start = lowest + 1;
    }
    if (start <= last) adaptive_split(excursion, start, last, options.dip, shortest, parts);
  }

  // Which group a channel's taxel belongs to, for the region.
  std::map<std::string, int> channel_of_name;
  for (int c = 0; c < channels; ++c) channel_of_name[stream.channels[static_cast<size_t>(c)]] = c;
  std::vector<std::vector<int>> group_channels(layout.groups.size());
  for (size_t g = 0; g < layout.groups.size(); ++g)
    for (int64_t taxel_id : layout.groups[g].taxels)
      if (const Taxel* taxel = layout.find_taxel(taxel_id))
        for (int channel : taxel->channels)
          if (channel >= 0 && channel < static_cast<int>(layout.channels.size())) {
            const auto found = channel_of_name.find(layout.channels[static_cast<size_t>(channel)].name);
            if (found != channel_of_name.end()) group_channels[g].push_back(found->second);
          }
  const int64_t longest = frames_of(options.max_seconds);
  std::vector<Label> labels;
  for (const auto& [part_first, part_last] : parts) {
    for (int64_t first = part_first; first <= part_last; first += longest) {
      const int64_t last = std::min(part_last, first + longest - 1);
      const double t0 = stream.time_of(first);
      const double t1 = stream.time_of(last) + 1.0 / rate;
      if (t1 - t0 < options.min_seconds - 1e-9) continue;
      Label label;
      label.recording = recording.id;
      label.t0 = t0;
      label.t1 = t1;
      label.class_name = kUnknownClass;
      label.note = last < part_last ? "forced" : last + 1 >= samples ? "open" : "quiet";
      // The group whose channels left their band the most, summed over the segment.
      double best = 0.0;
      for (size_t g = 0; g < group_channels.size(); ++g) {
        double moved = 0.0;
        for (int c : group_channels[g]) {
          const std::vector<float>& z = score[static_cast<size_t>(c)];
          if (z.empty()) continue;
          for (int64_t t = first; t <= last; ++t)
            moved += std::max(0.0f, z[static_cast<size_t>(t)] - on);
        }
        if (moved > best) best = moved, label.region = layout.groups[g].id;
      }
      labels.push_back(std::move(label));
    }
  }
  return labels;
}

}  // namespace tactile

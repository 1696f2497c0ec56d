// Multivariate MiniRocket on resampled segments (rocket.h says how the biases are fitted).
#include "tactile/features/rocket.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <random>
#include <string>

#include "tactile/error.h"
#include "tactile/features/raw.h"

namespace tactile {

namespace {

// MiniRocket: at most 32 dilations per kernel.
constexpr int kRocketMaxDilations = 32;
// The recording is cut into this many windows to fit the biases on.
constexpr int64_t kRocketFitWindows = 16;
constexpr const char* kRocketBiasStream = "rocket.biases";
constexpr const char* kRocketLevelsStream = "rocket.levels";

// A uniform double in [0, 1) from the top 53 bits: the same on every standard library.
double rocket_uniform(std::mt19937_64& generator) {
  return static_cast<double>(generator() >> 11) * 0x1.0p-53;
}

// One channel's kernel output added to a pair's: alpha plus the kernel's three gammas. Only
// additions, in the same order on every path (no contraction into FMA), so the clones for
// wider vectors give the same sums to the bit.
__attribute__((target_clones("avx512f", "avx2", "default"))) void rocket_add_kernel(
    float* output, const float* alpha, const float* gamma0, const float* gamma1,
    const float* gamma2, size_t length) {
  for (size_t t = 0; t < length; ++t) output[t] += alpha[t] + gamma0[t] + gamma1[t] + gamma2[t];
}

// Runs `visit(pair, dilation_index, kernel, output)` for every (dilation, kernel) pair with
// the pair's full zero-padded convolution output, summed over its channels. MiniRocket's
// trick: per dilation, each channel's sum of -x over the 9 taps (alpha) and its 9 shifted
// copies of 3x (gamma) are computed once; a kernel's output is alpha plus three gammas.
template <typename Visit>
void rocket_visit_pairs(const RocketPlan& plan, const Eigen::MatrixXf& series, Visit&& visit) {
  const auto length = static_cast<size_t>(plan.length);
  const auto channels = static_cast<size_t>(plan.channels);
  std::vector<float> alpha(channels * length), gamma(channels * kRocketKernelLength * length),
      output(length);
  static const std::vector<std::array<int, 3>> kernels = minirocket_kernels();
  size_t pair = 0;
  for (size_t dilation_index = 0; dilation_index < plan.dilations.size(); ++dilation_index) {
    const int64_t dilation = plan.dilations[dilation_index];
    for (size_t channel = 0; channel < channels; ++channel) {
      const float* x = series.col(static_cast<Eigen::Index>(channel)).data();
      float* a = alpha.data() + channel * length;
      std::fill(a, a + length, 0.0f);
      for (int tap = 0; tap < kRocketKernelLength; ++tap) {
        const int64_t offset = (tap - kRocketKernelLength / 2) * dilation;
        float* g =
            gamma.data() + (channel * kRocketKernelLength + static_cast<size_t>(tap)) * length;
        // Valid t: 0 <= t + offset < length; zero padding elsewhere.
        const auto from = static_cast<size_t>(std::clamp<int64_t>(-offset, 0, plan.length));
        const auto to =
            static_cast<size_t>(std::clamp<int64_t>(plan.length - offset, 0, plan.length));
        std::fill(g, g + length, 0.0f);
        for (size_t t = from; t < to; ++t) {
          const float value = x[static_cast<int64_t>(t) + offset];
          g[t] = 3.0f * value;
          a[t] -= value;
        }
      }
    }
    for (int kernel = 0; kernel < kRocketKernels; ++kernel, ++pair) {
      const std::array<int, 3>& twos = kernels[static_cast<size_t>(kernel)];
      std::fill(output.begin(), output.end(), 0.0f);
      for (int channel : plan.channel_sets[pair]) {
        const auto c = static_cast<size_t>(channel);
        const float* a = alpha.data() + c * length;
        const float* g0 =
            gamma.data() + (c * kRocketKernelLength + static_cast<size_t>(twos[0])) * length;
        const float* g1 =
            gamma.data() + (c * kRocketKernelLength + static_cast<size_t>(twos[1])) * length;
        const float* g2 =
            gamma.data() + (c * kRocketKernelLength + static_cast<size_t>(twos[2])) * length;
        rocket_add_kernel(output.data(), a, g0, g1, g2, length);
      }
      visit(pair, dilation_index, kernel, output);
    }
  }
}

// The PPV counts of one output against its pair's biases: how many of the `used` values
// exceed each bias, 16 (or, for the last 8 or fewer, 8) biases at a time in one vector of
// counts, so that no lanes are summed. `biases` is padded to a multiple of 8 with +infinity,
// which no value exceeds. This compare-and-count is most of a transform's time (on one
// 64-sample channel, 9,996 biases x up to 64 outputs against ~600 outputs to compute); it is
// compiled for AVX-512, AVX2 and plain x86-64, the widest the CPU has picked at load time. The
// counts are integers: the same on every path, to the bit.
constexpr size_t kRocketCountWidth = 8;
// GCC's vector types: 16 floats are one AVX-512 register, two AVX2 or four SSE2 ones.
typedef float RocketFloats16 __attribute__((vector_size(16 * sizeof(float))));
typedef int32_t RocketCounts16 __attribute__((vector_size(16 * sizeof(int32_t))));
typedef float RocketFloats8 __attribute__((vector_size(8 * sizeof(float))));
typedef int32_t RocketCounts8 __attribute__((vector_size(8 * sizeof(int32_t))));

// One group of biases; a true comparison is -1 in every bit of its lane. Two counters, for
// the even and odd values, so that consecutive compares do not wait for each other.
template <typename Floats, typename Counts>
inline void rocket_count_group(const float* values, size_t used, const float* biases,
                               int32_t* positives) {
  Floats group;
  std::memcpy(&group, biases, sizeof group);
  Counts even = {}, odd = {};
  size_t t = 0;
  for (; t + 1 < used; t += 2) {
    even -= (Floats{} + values[t]) > group;
    odd -= (Floats{} + values[t + 1]) > group;
  }
  if (t < used) even -= (Floats{} + values[t]) > group;
  const Counts lanes = even + odd;
  std::memcpy(positives, &lanes, sizeof lanes);
}

__attribute__((target_clones("avx512f", "avx2", "default"))) void rocket_count_above(
    const float* values, size_t used, const float* biases, size_t padded_count,
    int32_t* positives) {
  size_t first = 0;
  for (; first + 8 < padded_count; first += 16)
    rocket_count_group<RocketFloats16, RocketCounts16>(values, used, biases + first,
                                                       positives + first);
  if (first < padded_count)
    rocket_count_group<RocketFloats8, RocketCounts8>(values, used, biases + first,
                                                     positives + first);
}

}  // namespace

std::vector<std::array<int, 3>> minirocket_kernels() {
  std::vector<std::array<int, 3>> kernels;
  for (int first = 0; first < kRocketKernelLength; ++first)
    for (int second = first + 1; second < kRocketKernelLength; ++second)
      for (int third = second + 1; third < kRocketKernelLength; ++third)
        kernels.push_back({first, second, third});
  return kernels;
}

RocketPlan plan_rocket(int64_t length, int64_t channels, int64_t features, uint64_t seed,
                       int64_t fit_examples) {
  if (length < kRocketKernelLength)
    throw Error("rocket", "series of " + std::to_string(length) + " samples: needs at least 9");
  if (features < kRocketKernels)
    throw Error("rocket", "features=" + std::to_string(features) + ": needs at least 84");
  if (channels < 1 || fit_examples < 1) throw Error("rocket", "needs a channel and a fit example");
  RocketPlan plan;
  plan.length = length;
  plan.channels = channels;
  // MiniRocket's fit_dilations: exponents spread evenly up to log2((length - 1) / 8), the
  // distinct dilations kept, each with features in proportion to how often it came up.
  const int64_t per_kernel = features / kRocketKernels;
  const int64_t dilation_count = std::min<int64_t>(per_kernel, kRocketMaxDilations);
  const double multiplier = static_cast<double>(per_kernel) / static_cast<double>(dilation_count);
  const double max_exponent =
      std::log2(static_cast<double>(length - 1) / static_cast<double>(kRocketKernelLength - 1));
  std::map<int, int64_t> counts;
  for (int64_t index = 0; index < dilation_count; ++index) {
    const double exponent = dilation_count == 1 ? 0.0
                                                : max_exponent * static_cast<double>(index) /
                                                      static_cast<double>(dilation_count - 1);
    ++counts[static_cast<int>(std::pow(2.0, exponent))];
  }
  int64_t assigned = 0;
  for (const auto& [dilation, count] : counts) {
    plan.dilations.push_back(dilation);
    plan.features_per_dilation.push_back(static_cast<int>(static_cast<double>(count) * multiplier));
    assigned += plan.features_per_dilation.back();
  }
  for (size_t index = 0; assigned < per_kernel;
       index = (index + 1) % plan.dilations.size(), ++assigned)
    ++plan.features_per_dilation[index];
  // Multivariate MiniRocket: 2^U(0, log2(min(C, 9) + 1)) channels per pair, drawn without
  // replacement; one random fit example per pair.
  std::mt19937_64 generator(seed);
  const double channel_exponent =
      std::log2(static_cast<double>(std::min<int64_t>(channels, 9)) + 1.0);
  const size_t pairs = plan.dilations.size() * kRocketKernels;
  std::vector<int> pool(static_cast<size_t>(channels));
  for (size_t pair = 0; pair < pairs; ++pair) {
    const auto take = std::clamp<int64_t>(
        static_cast<int64_t>(std::pow(2.0, rocket_uniform(generator) * channel_exponent)), 1,
        std::min<int64_t>(channels, 9));
    for (size_t index = 0; index < pool.size(); ++index) pool[index] = static_cast<int>(index);
    for (int64_t index = 0; index < take; ++index) {
      const auto pick = static_cast<size_t>(index) +
                        static_cast<size_t>(generator() % static_cast<uint64_t>(channels - index));
      std::swap(pool[static_cast<size_t>(index)], pool[pick]);
    }
    std::vector<int> chosen(pool.begin(), pool.begin() + take);
    std::sort(chosen.begin(), chosen.end());
    plan.channel_sets.push_back(std::move(chosen));
    plan.fit_example.push_back(static_cast<int>(generator() % static_cast<uint64_t>(fit_examples)));
  }
  // MiniRocket's quantiles: the fractional parts of k times the golden ratio.
  int64_t total = 0;
  for (int count : plan.features_per_dilation) total += count * kRocketKernels;
  for (int64_t k = 1; k <= total; ++k) {
    const double value = static_cast<double>(k) * std::numbers::phi;
    plan.quantiles.push_back(value - std::floor(value));
  }
  return plan;
}

std::vector<float> rocket_biases(const RocketPlan& plan,
                                 const std::vector<Eigen::MatrixXf>& examples) {
  std::vector<float> biases(static_cast<size_t>(plan.feature_count()), 0.0f);
  // Each example is visited once; its pairs' outputs are sorted and read at the quantiles.
  std::vector<size_t> first_feature(plan.channel_sets.size());
  size_t feature = 0;
  for (size_t dilation_index = 0, pair = 0; dilation_index < plan.dilations.size();
       ++dilation_index)
    for (int kernel = 0; kernel < kRocketKernels; ++kernel, ++pair) {
      first_feature[pair] = feature;
      feature += static_cast<size_t>(plan.features_per_dilation[dilation_index]);
    }
  std::vector<float> sorted;
  for (size_t example = 0; example < examples.size(); ++example) {
    rocket_visit_pairs(
        plan, examples[example],
        [&](size_t pair, size_t dilation_index, int, const std::vector<float>& output) {
          if (plan.fit_example[pair] != static_cast<int>(example)) return;
          sorted = output;
          std::sort(sorted.begin(), sorted.end());
          const auto last = static_cast<double>(sorted.size() - 1);
          for (int index = 0; index < plan.features_per_dilation[dilation_index]; ++index) {
            const size_t at = first_feature[pair] + static_cast<size_t>(index);
            // numpy.quantile's default: linear between the order statistics.
            const double position = plan.quantiles[at] * last;
            const auto below = static_cast<size_t>(position);
            const size_t above = std::min(below + 1, sorted.size() - 1);
            const double fraction = position - static_cast<double>(below);
            biases[at] =
                static_cast<float>(sorted[below] + (sorted[above] - sorted[below]) * fraction);
          }
        });
  }
  return biases;
}

void rocket_transform(const RocketPlan& plan, const Eigen::MatrixXf& series,
                      std::span<const float> biases, std::span<double> features) {
  if (series.rows() != plan.length || series.cols() != plan.channels ||
      static_cast<int64_t>(biases.size()) != plan.feature_count() ||
      static_cast<int64_t>(features.size()) != plan.feature_count())
    throw Error("rocket", "series, biases or features do not match the plan");
  size_t feature = 0;
  // One pair's biases padded with +infinity (rocket_count_above), and its counts: 16 more
  // than the most biases of a pair, the room the groups of 16 may take.
  const int most =
      *std::max_element(plan.features_per_dilation.begin(), plan.features_per_dilation.end());
  std::vector<float> pair_biases(static_cast<size_t>(most) + 16);
  std::vector<int32_t> positives(pair_biases.size());
  // PPV = count / outputs compared, for every count: per dilation, the whole output's
  // length and its central part's. The same divisions as one per feature, far fewer of them.
  const auto length = static_cast<size_t>(plan.length);
  std::vector<std::vector<double>> shares(plan.dilations.size() * 2);
  for (size_t dilation_index = 0; dilation_index < plan.dilations.size(); ++dilation_index)
    for (int central = 0; central < 2; ++central) {
      const size_t used =
          length -
          (central ? static_cast<size_t>((kRocketKernelLength - 1) * plan.dilations[dilation_index])
                   : 0);
      std::vector<double>& share = shares[dilation_index * 2 + static_cast<size_t>(central)];
      share.resize(used + 1);
      for (size_t count = 0; count <= used; ++count)
        share[count] = static_cast<double>(static_cast<int32_t>(count)) / static_cast<double>(used);
    }
  rocket_visit_pairs(
      plan, series,
      [&](size_t, size_t dilation_index, int kernel, const std::vector<float>& output) {
        // MiniRocket's padding: alternate pairs read the whole zero-padded output or only its
        // central part, where every tap lies inside the series.
        const bool padded = (static_cast<int>(dilation_index % 2) + kernel) % 2 == 0;
        const int64_t padding = (kRocketKernelLength - 1) / 2 * plan.dilations[dilation_index];
        const size_t from = padded ? 0 : static_cast<size_t>(padding);
        const size_t to = padded ? output.size() : output.size() - static_cast<size_t>(padding);
        const auto count = static_cast<size_t>(plan.features_per_dilation[dilation_index]);
        const size_t padded_count =
            (count + kRocketCountWidth - 1) / kRocketCountWidth * kRocketCountWidth;
        std::copy(biases.begin() + static_cast<std::ptrdiff_t>(feature),
                  biases.begin() + static_cast<std::ptrdiff_t>(feature + count),
                  pair_biases.begin());
        std::fill(pair_biases.begin() + static_cast<std::ptrdiff_t>(count),
                  pair_biases.begin() + static_cast<std::ptrdiff_t>(padded_count),
                  std::numeric_limits<float>::infinity());
        rocket_count_above(output.data() + from, to - from, pair_biases.data(), padded_count,
                           positives.data());
        const std::vector<double>& share = shares[dilation_index * 2 + (padded ? 0 : 1)];
        for (size_t index = 0; index < count; ++index, ++feature)
          features[feature] = share[static_cast<size_t>(positives[index])];
      });
}

std::vector<double> minirocket_convolution(std::span<const double> values, int kernel,
                                           int dilation) {
  const std::array<int, 3> twos = minirocket_kernels().at(static_cast<size_t>(kernel));
  const auto length = static_cast<int64_t>(values.size());
  std::vector<double> output(values.size(), 0.0);
  for (int64_t t = 0; t < length; ++t)
    for (int tap = 0; tap < kRocketKernelLength; ++tap) {
      const int64_t at = t + (tap - kRocketKernelLength / 2) * dilation;
      if (at < 0 || at >= length) continue;
      const bool two = tap == twos[0] || tap == twos[1] || tap == twos[2];
      output[static_cast<size_t>(t)] += (two ? 2.0 : -1.0) * values[static_cast<size_t>(at)];
    }
  return output;
}

//---- The extractor

namespace {

class RocketExtractor : public FeatureExtractor {
 public:
  RocketExtractor(RawReading reading, int64_t features, uint64_t seed, std::string where)
      : reading_(std::move(reading)), features_(features), seed_(seed), where_(std::move(where)) {
    reading_.levels_stream = kRocketLevelsStream;
  }

  std::string name() const override { return "rocket"; }
  std::string description() const override {
    return "Any layout: multivariate MiniRocket (Dempster et al. 2021): 84 kernels of length 9 at "
           "exponential dilations over random channel subsets of the resampled segment, PPV "
           "against biases fitted as quantiles of the recording's own windows";
  }

  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override {
    const std::vector<int> channels = raw_channels(layout, reading_, where_);
    std::vector<std::string> names;
    if (raw_reads_summary(layout, reading_, channels))
      names = plan_raw_summary(layout, channels).names;
    else
      for (int channel : channels)
        names.push_back(layout.channels[static_cast<size_t>(channel)].name);
    const RocketPlan& plan = plan_for(static_cast<int64_t>(names.size()));
    const std::vector<std::array<int, 3>> kernels = minirocket_kernels();
    std::vector<FeatureColumn> columns;
    size_t pair = 0, feature = 0;
    for (size_t dilation_index = 0; dilation_index < plan.dilations.size(); ++dilation_index)
      for (int kernel = 0; kernel < kRocketKernels; ++kernel, ++pair) {
        std::string summed;
        for (int channel : plan.channel_sets[pair])
          summed += (summed.empty() ? "" : "+") + names[static_cast<size_t>(channel)];
        const std::array<int, 3>& twos = kernels[static_cast<size_t>(kernel)];
        const bool padded = (static_cast<int>(dilation_index % 2) + kernel) % 2 == 0;
        for (int index = 0; index < plan.features_per_dilation[dilation_index]; ++index, ++feature)
          columns.push_back(
              {"rocket." + std::to_string(feature),
               "PPV of kernel " + std::to_string(kernel) + " (2 at " + std::to_string(twos[0]) +
                   "," + std::to_string(twos[1]) + "," + std::to_string(twos[2]) + "), dilation " +
                   std::to_string(plan.dilations[dilation_index]) + ", channels " + summed +
                   ", bias at quantile " + std::to_string(plan.quantiles[feature]) +
                   (padded ? ", zero-padded" : ", central part")});
      }
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    Recording prepared = add_raw_levels(recording, layout, reading_, where_);
    const std::vector<int> channels = raw_channels(layout, reading_, where_);
    const std::optional<RawSummaryPlan> summary = summary_for(layout, channels);
    const RocketPlan& plan = plan_for(summary ? static_cast<int64_t>(summary->names.size())
                                              : static_cast<int64_t>(channels.size()));
    const Stream& stream = raw_stream(prepared, layout, reading_);
    const double start = stream.time_of(0);
    const double span = stream.duration() > 0.0 ? stream.duration() : 1.0;
    std::vector<Eigen::MatrixXf> windows;
    for (int64_t window = 0; window < kRocketFitWindows; ++window) {
      Label label;
      label.t0 = start + span * static_cast<double>(window) / kRocketFitWindows;
      label.t1 = start + span * static_cast<double>(window + 1) / kRocketFitWindows;
      std::string skip_reason;
      Eigen::MatrixXd points =
          raw_segment({prepared, layout, label}, reading_, channels, skip_reason);
      if (skip_reason.empty() && summary) points = raw_summary(*summary, points);
      windows.push_back(skip_reason.empty() ? Eigen::MatrixXf(points.cast<float>())
                                            : Eigen::MatrixXf::Zero(plan.length, plan.channels));
    }
    const std::vector<float> biases = rocket_biases(plan, windows);
    Stream bias_stream;
    bias_stream.name = kRocketBiasStream;
    bias_stream.rate_hz = stream.rate_hz;
    bias_stream.samples =
        Eigen::Map<const SampleMatrix>(biases.data(), 1, static_cast<Eigen::Index>(biases.size()));
    for (size_t index = 0; index < biases.size(); ++index)
      bias_stream.channels.push_back("bias." + std::to_string(index));
    bias_stream.units.assign(biases.size(), "");
    prepared.streams.push_back(std::move(bias_stream));
    return prepared;
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const std::vector<int> channels = raw_channels(input.layout, reading_, where_);
    const std::optional<RawSummaryPlan> summary = summary_for(input.layout, channels);
    const RocketPlan& plan = plan_for(summary ? static_cast<int64_t>(summary->names.size())
                                              : static_cast<int64_t>(channels.size()));
    const Stream* bias_stream = input.recording.find_stream(kRocketBiasStream);
    if (bias_stream == nullptr || bias_stream->channel_count() != plan.feature_count())
      return FeatureResult::skip(
          "rocket's biases are fitted on the recording by preprocess(), "
          "which has not run");
    std::string skip_reason;
    Eigen::MatrixXd points = raw_segment(input, reading_, channels, skip_reason);
    if (!skip_reason.empty()) return FeatureResult::skip(skip_reason);
    if (summary) points = raw_summary(*summary, points);
    FeatureResult result;
    result.values.resize(static_cast<size_t>(plan.feature_count()));
    rocket_transform(plan, points.cast<float>(),
                     std::span<const float>(bias_stream->samples.data(),
                                            static_cast<size_t>(bias_stream->channel_count())),
                     result.values);
    return result;
  }

 private:
  // The summary's plan when the reading reads it (series=summary, or auto on a large map).
  std::optional<RawSummaryPlan> summary_for(const SkinLayout& layout,
                                            const std::vector<int>& channels) const {
    if (!raw_reads_summary(layout, reading_, channels)) return std::nullopt;
    return plan_raw_summary(layout, channels);
  }

  // The plan depends on the series count only; drawn once per count (extract() runs per
  // segment, possibly on several threads).
  const RocketPlan& plan_for(int64_t channels) const {
    const std::lock_guard lock(mutex_);
    auto found = plans_.find(channels);
    if (found == plans_.end())
      found = plans_
                  .emplace(channels,
                           std::make_unique<RocketPlan>(plan_rocket(
                               reading_.samples, channels, features_, seed_, kRocketFitWindows)))
                  .first;
    return *found->second;
  }

  RawReading reading_;
  int64_t features_;
  uint64_t seed_;
  std::string where_;
  mutable std::mutex mutex_;
  mutable std::map<int64_t, std::unique_ptr<RocketPlan>> plans_;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_rocket_extractor(const Parameters& parameters) {
  parameters.expect_only(
      {"modality", "stream", "samples", "baseline", "scale", "series", "features", "seed"});
  RawReading reading = read_raw_parameters(parameters, 64, kRocketKernelLength, "auto");
  const int64_t features = parameters.integer("features", 10000);
  if (features < kRocketKernels || features > 1000000)
    throw Error(parameters.where(),
                "features=" + std::to_string(features) + ": must be in [84, 1000000]");
  const int64_t seed = parameters.integer("seed", 1);
  if (seed < 0) throw Error(parameters.where(), "seed=" + std::to_string(seed) + ": must be >= 0");
  return std::make_unique<RocketExtractor>(std::move(reading), features,
                                           static_cast<uint64_t>(seed), parameters.where());
}

}  // namespace tactile

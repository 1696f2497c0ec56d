// The rocket transform's speed (issue 26 target: >= 1 million samples per second per core),
// one thread:
//   RocketTransform/L/C   rocket_transform alone on an L x C resampled series with the
//                         default 10,000 features (9,996); samples/s counts L x C.
//   RocketExtract/skin    the whole pipeline's extract() on every ground-truth segment of
//                         one simulated recording (read, resample, reference, transform);
//                         samples/s counts the segments' recorded samples x channels read.
// Plus the per-recording bias fit (preprocess) for each skin, timed once.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>

#include "tactile/features/raw.h"
#include "tactile/features/rocket.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/simulator.h"

namespace {

void RocketTransform(benchmark::State& state) {
  const int64_t length = state.range(0), channels = state.range(1);
  const tactile::RocketPlan plan = tactile::plan_rocket(length, channels, 10000, 1, 1);
  std::mt19937_64 engine(3);
  std::normal_distribution<float> noise;
  Eigen::MatrixXf series(length, channels);
  for (Eigen::Index k = 0; k < series.size(); ++k) series.data()[k] = noise(engine);
  const std::vector<float> biases = tactile::rocket_biases(plan, {series});
  std::vector<double> features(static_cast<size_t>(plan.feature_count()));
  for (auto _ : state) {
    tactile::rocket_transform(plan, series, biases, features);
    benchmark::DoNotOptimize(features.data());
  }
  state.counters["samples/s"] = benchmark::Counter(static_cast<double>(length * channels),
                                                   benchmark::Counter::kIsIterationInvariantRate);
  state.counters["features"] = static_cast<double>(plan.feature_count());
}
BENCHMARK(RocketTransform)
    ->Args({64, 1})
    ->Args({64, 8})
    ->Args({64, 32})
    ->Unit(benchmark::kMicrosecond);

struct RocketBenchSkin {
  tactile::SkinLayout layout;
  tactile::Recording prepared;
  std::vector<tactile::Label> labels;
  int64_t channels = 0;
};

const RocketBenchSkin& rocket_bench_skin(const std::string& skin) {
  static std::map<std::string, RocketBenchSkin> cache;
  auto found = cache.find(skin);
  if (found != cache.end()) return found->second;
  RocketBenchSkin entry;
  entry.layout = tactile::load_layout(skin);
  tactile::SimulationOptions options;
  tactile::SimulatedTrial trial =
      skin == "nao"       ? tactile::simulate_nao_trial(entry.layout, options, 0, 0)
      : skin == "tsa"     ? tactile::simulate_tsa_trial(entry.layout, options, 0, 0)
      : skin == "fur"     ? tactile::simulate_fur_trial(entry.layout, options, 0, 0)
      : skin == "robovie" ? tactile::simulate_robovie_trial(entry.layout, options, 0, 0)
                          : tactile::simulate_flux_trial(entry.layout, options, 0, 0);
  const auto extractor = tactile::make_rocket_extractor({});
  entry.prepared = extractor->preprocess(trial.recording, entry.layout);
  entry.labels = trial.labels;
  tactile::RawReading reading;
  entry.channels =
      static_cast<int64_t>(tactile::raw_channels(entry.layout, reading, "bench").size());
  return cache.emplace(skin, std::move(entry)).first->second;
}

void RocketExtract(benchmark::State& state, const std::string& skin) {
  const RocketBenchSkin& data = rocket_bench_skin(skin);
  const auto extractor = tactile::make_rocket_extractor({});
  const tactile::Stream& stream = data.prepared.streams.front();
  double samples = 0.0;
  for (const tactile::Label& label : data.labels) {
    const auto [first, last] = tactile::sample_range(stream, label.t0, label.t1);
    samples += static_cast<double>((last - first) * data.channels);
  }
  for (auto _ : state)
    for (const tactile::Label& label : data.labels) {
      tactile::FeatureResult result = extractor->extract({data.prepared, data.layout, label});
      benchmark::DoNotOptimize(result.values.data());
    }
  state.counters["samples/s"] =
      benchmark::Counter(samples, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["segments/s"] = benchmark::Counter(static_cast<double>(data.labels.size()),
                                                    benchmark::Counter::kIsIterationInvariantRate);
  state.counters["channels"] = static_cast<double>(data.channels);
}
BENCHMARK_CAPTURE(RocketExtract, nao, std::string("nao"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(RocketExtract, tsa, std::string("tsa"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(RocketExtract, fur, std::string("fur"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(RocketExtract, robovie, std::string("robovie"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(RocketExtract, flux, std::string("flux"))->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

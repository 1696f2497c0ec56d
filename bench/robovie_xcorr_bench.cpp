// robovie_xcorr on a full Robovie segment (274 films x 12,000 samples = 2 min at 100 Hz)
// against a plain Eigen GEMM of the same shape in the same run. Both count 2 N^2 T
// floating-point operations, so their GFLOP/s say how much of the GEMM's speed the
// feature keeps after sigma suppression, standardisation and the triangle copy.

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>

#include "tactile/features/robovie_xcorr.h"
#include "tactile/layout/skin_layout.h"

namespace {

constexpr Eigen::Index kFilms = 274;
constexpr Eigen::Index kSamples = 12000;
constexpr double kFlops = 2.0 * kFilms * kFilms * kSamples;

// Noise on every film, plus touches shared by neighbouring films, so that eq. (13) keeps
// a realistic fraction of the samples.
const tactile::Recording& segment_recording(const tactile::SkinLayout& layout) {
  static const tactile::Recording recording = [&] {
    std::mt19937_64 engine(7);
    std::normal_distribution<float> noise(0.0f, 30.0f);
    tactile::Stream skin;
    skin.name = "skin";
    skin.rate_hz = 100.0;
    for (const tactile::Channel& channel : layout.channels) {
      skin.channels.push_back(channel.name);
      skin.units.push_back(channel.unit);
    }
    skin.samples.resize(kSamples, kFilms);
    for (Eigen::Index film = 0; film < kFilms; ++film)
      for (Eigen::Index t = 0; t < kSamples; ++t) skin.samples(t, film) = 1000.0f + noise(engine);
    for (Eigen::Index touch = 0; touch < 40; ++touch) {
      const Eigen::Index first_film = (touch * 37) % (kFilms - 8);
      const Eigen::Index start = (touch * 911) % (kSamples - 300);
      skin.samples.block(start, first_film, 300, 8).array() += 2000.0f;
    }
    tactile::Recording result;
    result.id = "bench";
    result.streams.push_back(std::move(skin));
    return result;
  }();
  return recording;
}

void set_rate(benchmark::State& state) {
  state.counters["GFLOP/s"] =
      benchmark::Counter(kFlops / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

void RobovieXcorrExtract(benchmark::State& state) {
  const tactile::SkinLayout layout = tactile::load_layout("robovie");
  const tactile::Recording& recording = segment_recording(layout);
  const auto extractor = tactile::make_robovie_xcorr_extractor({});
  tactile::Label segment;
  segment.t0 = 0.0;
  segment.t1 = static_cast<double>(kSamples) / 100.0;
  for (auto _ : state) {
    tactile::FeatureResult result = extractor->extract({recording, layout, segment});
    benchmark::DoNotOptimize(result.values.data());
  }
  set_rate(state);
}

void PlainGemmSameShape(benchmark::State& state) {
  const Eigen::MatrixXd left = Eigen::MatrixXd::Random(kFilms, kSamples);
  const Eigen::MatrixXd right = Eigen::MatrixXd::Random(kSamples, kFilms);
  Eigen::MatrixXd product(kFilms, kFilms);
  for (auto _ : state) {
    product.noalias() = left * right;
    benchmark::DoNotOptimize(product.data());
  }
  set_rate(state);
}

}  // namespace

// Rates per CPU second: Eigen runs single-threaded here (no OpenMP), and on a shared
// machine wall time measures the neighbours as much as the code.
BENCHMARK(RobovieXcorrExtract)->Unit(benchmark::kMillisecond);
BENCHMARK(PlainGemmSameShape)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

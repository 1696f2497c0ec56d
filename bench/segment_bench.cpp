// Segmentation against ground truth on every simulated skin, clean and with realistic sensor
// faults (sim/sensor_faults.h): frame precision, recall, F1 and one-to-one event F1
// (segment/scoring.h) of the skin's own segmenter, of `adaptive` as it was before issue 26
// (kept below, verbatim in behaviour) and of `adaptive` now. bench/SEGMENT.md has the table.
//
//   build/bench/segment_bench [--subjects N] [--seed S] [--params ADAPTIVE_PARAMS]
//                             [--faults realistic|SPEC] [skin ...]
//
// Without skins: every skin with a simulator (skins/skin.h), so a new skin joins the table
// by being registered, and the pressure grids grid:16x16 and grid:19x27 (sim/grid_sim.h); a skin id
// given on the line (e.g. grid:16x16) is simulated instead.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/random.h"
#include "tactile/segment/scoring.h"
#include "tactile/segment/segmenter.h"
#include "tactile/segment/threshold.h"
#include "tactile/signal/display_scale.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/sim/sensor_faults.h"
#include "tactile/skins/skin.h"

namespace {

using tactile::Label;
using tactile::Recording;

// `adaptive` before issue 26 (commit edfcbb0): any channel beyond twice its display
// noise band makes a frame active; quiet 0.25 s ends a segment; regions left out.
std::vector<Label> adaptive_before(const Recording& recording) {
  const tactile::Stream& stream = recording.streams.front();
  const int channels = static_cast<int>(stream.channel_count());
  std::vector<int> columns(static_cast<size_t>(channels));
  for (int c = 0; c < channels; ++c) columns[static_cast<size_t>(c)] = c;
  const tactile::RestScale scale = tactile::rest_scale(stream, columns);
  const int64_t samples = stream.sample_count();
  std::vector<uint8_t> active(static_cast<size_t>(samples), 0);
  for (int c = 0; c < channels; ++c) {
    const float rest = scale.rest[static_cast<size_t>(c)];
    if (std::isnan(rest)) continue;
    const float band =
        std::max(scale.noise_band[static_cast<size_t>(c)], 1e-6f * std::max(1.0f, std::fabs(rest)));
    const float* column = stream.samples.col(c).data();
    for (int64_t t = 0; t < samples; ++t)
      if (std::fabs(column[t] - rest) > 2.0f * band) active[static_cast<size_t>(t)] = 1;
  }
  const auto quiet = std::max<int64_t>(1, std::llround(0.25 * stream.rate_hz));
  const auto longest = std::max<int64_t>(1, std::llround(10.0 * stream.rate_hz));
  std::vector<Label> labels;
  for (const tactile::SampleSegment& segment :
       tactile::threshold_segments(active, quiet, longest)) {
    Label label;
    label.t0 = stream.time_of(segment.first);
    label.t1 = stream.time_of(segment.last) + 1.0 / stream.rate_hz;
    if (label.t1 - label.t0 < 0.05) continue;
    labels.push_back(label);
  }
  return labels;
}

struct Scores {
  tactile::DetectionScore frames, events;
  int64_t segments = 0;
};

void add_scores(Scores& scores, const std::vector<Label>& found, const std::vector<Label>& truth,
                const tactile::Stream& stream) {
  scores.frames +=
      tactile::score_frames(found, truth, stream.start_time, stream.rate_hz, stream.sample_count());
  scores.events += tactile::score_events(found, truth);
  scores.segments += static_cast<int64_t>(found.size());
}

std::string format_scores(const Scores& scores) {
  char text[96];
  std::snprintf(text, sizeof text, "%.2f %.2f **%.3f** / **%.3f** (%lld)",
                scores.frames.precision(), scores.frames.recall(), scores.frames.f1(),
                scores.events.f1(), static_cast<long long>(scores.segments));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int subjects = 3;
    uint64_t seed = 1;
    std::string params;                    // `adaptive`'s parameters, "key=value,..."
    std::string fault_spec = "realistic";  // the faulty rows' faults (sim/sensor_faults.h)
    std::vector<std::string> skins;
    for (int k = 1; k < argc; ++k) {
      const std::string word = argv[k];
      if (word == "--subjects" && k + 1 < argc)
        subjects = std::atoi(argv[++k]);
      else if (word == "--params" && k + 1 < argc)
        params = argv[++k];
      else if (word == "--faults" && k + 1 < argc)
        fault_spec = argv[++k];
      else if (word == "--seed" && k + 1 < argc)
        seed = std::strtoull(argv[++k], nullptr, 10);
      else
        skins.push_back(word);
    }
    if (skins.empty()) {
      skins = tactile::simulated_skin_ids();
      skins.push_back("grid:16x16");
      skins.push_back("grid:19x27");
    }
    std::printf(
        "segment_bench: %d subjects per skin, seed %llu; each cell: frame precision, "
        "recall, F1 / one-to-one event F1 (segments found)\n\n",
        subjects, static_cast<unsigned long long>(seed));
    std::printf(
        "| skin | faults | touches | the skin's own segmenter | adaptive before | adaptive now "
        "|\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (const std::string& skin : skins) {
      // A grid:RxC is no registered skin: the pressure grid's simulator, adaptive its own.
      const bool grid = tactile::find_skin(skin) == nullptr && skin.rfind("grid:", 0) == 0;
      const tactile::SkinLayout layout = tactile::load_layout(skin);
      for (const std::string& faults : {std::string("none"), fault_spec}) {
        tactile::SimulationOptions options;
        options.seed = seed;
        options.subjects = subjects;
        options.faults = faults;
        Scores own, before, now;
        int64_t touches = 0;
        for (int subject = 0; subject < subjects; ++subject) {
          tactile::SimulatedTrial trial =
              grid ? tactile::simulate_grid_trial(layout, options, subject, 0)
                   : tactile::skin_record(skin).simulate(layout, options, subject, 0);
          tactile::apply_sensor_faults(trial, layout,
                                       tactile::parse_sensor_faults(options.faults, "faults"),
                                       options.seed, subject, 0);
          const tactile::Stream& stream = trial.recording.streams.front();
          touches += static_cast<int64_t>(trial.labels.size());
          const auto [own_method, own_params] =
              tactile::default_segmenter(skin);
          std::vector<Label> own_found;
          try {
            own_found = tactile::segment_recording(own_method, trial.recording, layout,
                                                   tactile::Parameters::parse(own_params, skin));
          } catch (const tactile::Error&) {
            // The skin's own segmenter may need what a faulty recording lacks.
          }
          add_scores(own, own_found, trial.labels, stream);
          add_scores(before, adaptive_before(trial.recording), trial.labels, stream);
          const std::vector<Label> found = tactile::segment_recording(
              "adaptive", trial.recording, layout, tactile::Parameters::parse(params, "--params"));
          add_scores(now, found, trial.labels, stream);
        }
        std::printf("| %s | %s | %lld | %s: %s | %s | %s |\n", skin.c_str(), faults.c_str(),
                    static_cast<long long>(touches),
                    tactile::default_segmenter(skin).first.c_str(),
                    format_scores(own).c_str(), format_scores(before).c_str(),
                    format_scores(now).c_str());
        std::fflush(stdout);
      }
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "segment_bench: %s\n", error.what());
    return 1;
  }
  return 0;
}

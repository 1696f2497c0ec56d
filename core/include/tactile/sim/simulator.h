#pragma once
// Synthetic skins: recordings generated from the physics of each sensor and of a hand,
// with ground-truth labels, deterministic by seed. One generator per skin.

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

struct SimulationOptions {
  int subjects = 5;
  int trials = 1;
  uint64_t seed = 1;
  std::string condition = "stationary";  // nao: stationary | moving
  bool multi_touch = false;              // nao: a front and a back gesture at once
  std::string side;                      // nao: front | back | "" (both)
  int repetitions = 0;                   // gestures per class in one trial; 0 = the skin's default
  // Sensor faults laid over each trial by write_simulation (sim/sensor_faults.h): "none",
  // "realistic" or "stuck=2,drift=0.3,...". The generators themselves ignore it.
  std::string faults = "none";
};

// One recording of one subject's trial, with its ground-truth labels (source
// kGroundTruth, region set, annotator "simulator") and metadata (skin, subject, trial,
// side, condition).
struct SimulatedTrial {
  Recording recording;
  std::vector<Label> labels;
};

// A generator for one skin. `subject` and `trial` are 0-based. The same (options.seed,
// subject, trial) gives byte-identical output; a subject's habits depend only on
// (options.seed, subject), so they persist across trials.
using TrialGenerator = std::function<SimulatedTrial(
    const SkinLayout& layout, const SimulationOptions& options, int subject, int trial)>;

// The generators of the papers' five skins, each in its skin's own file; the skin records
// (skins/skin.h) hold them, and a skin's generator is read from its record.
SimulatedTrial simulate_nao_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial);
SimulatedTrial simulate_tsa_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial);
SimulatedTrial simulate_fur_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial);
SimulatedTrial simulate_robovie_trial(const SkinLayout& layout, const SimulationOptions& options,
                                      int subject, int trial);
SimulatedTrial simulate_flux_trial(const SkinLayout& layout, const SimulationOptions& options,
                                   int subject, int trial);

// A reproducible random engine for one purpose, derived from the seed and a path of
// names and numbers (e.g. {"nao", "subject", 3}), so that adding a draw in one place
// never shifts the draws of another.
std::mt19937_64 derive_engine(uint64_t seed, const std::string& purpose, int64_t a = 0,
                              int64_t b = 0);

// "<skin>-s01-t01": the recording id the generators use.
std::string simulated_recording_id(const std::string& skin, int subject, int trial);

}  // namespace tactile

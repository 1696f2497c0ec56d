#pragma once
// Writes simulated recordings to disk: one HDF5 file per trial and their ground-truth
// labels in DIR/labels.db, with each skin's class vocabulary.

#include <functional>
#include <string>
#include <vector>

#include "tactile/sim/simulator.h"

namespace tactile {

// Called after each finished recording with (done, total).
using SimulationProgress = std::function<void(int done, int total)>;

struct SimulationSummary {
  std::vector<std::string> files;  // written HDF5 files, in subject/trial order
  int64_t labels = 0;
  double seconds_recorded = 0.0;
};

// Simulates options.subjects x options.trials recordings of one registered skin, or of the
// pressure grid for a grid:RxC layout that is no skin (sim/grid_sim.h), into `folder`
// (created if missing) as <recording id>.h5, replacing earlier ground-truth labels of the
// same recordings in folder/labels.db. Trials run on worker threads; output is identical
// whatever the thread count. Throws tactile::Error.
SimulationSummary write_simulation(const std::string& folder, const std::string& skin,
                                   const SimulationOptions& options,
                                   const SimulationProgress& progress = {});

// The demo workspace: a few short recordings of every skin with a demo share in its record
// (the papers' five) in one folder (with labels.db), small enough to make in seconds.
SimulationSummary write_demo_workspace(const std::string& folder, uint64_t seed = 1,
                                       const SimulationProgress& progress = {});

}  // namespace tactile

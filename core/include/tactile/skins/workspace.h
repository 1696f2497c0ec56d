#pragma once
// Writes simulated recordings to disk: one HDF5 file per trial and their ground-truth
// labels in DIR/labels.db, with each skin's class vocabulary.

#include <functional>
#include <string>
#include <vector>

#include "tactile/shards/shard.h"
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

// The same work in its two halves, as `tactile simulate --shard I/N` and `tactile merge` do it
// (shards/shard.h). The items are the (subject, trial) trials, subject-major; a shard generates and
// writes the recordings of its own items into `folder` (each the file one process writes) and
// keeps their labels; the store is written once, from every item's labels in item order.
struct SimulatedTrials {
  std::vector<std::string> plan;           // "subject/trial" of every item, in order
  std::vector<size_t> done;                // the items simulated, ascending
  std::vector<std::string> files;          // per item: the written HDF5 file ("" if not done)
  std::vector<std::vector<Label>> labels;  // per item: its ground truth
  std::vector<double> seconds;             // per item: the recording's duration
};
SimulatedTrials simulate_trials(const std::string& folder, const std::string& skin,
                                const SimulationOptions& options, const Shard& shard = {},
                                const SimulationProgress& progress = {});
// Writes the ground truth of `trials` (every item done) into folder/labels.db as
// write_simulation does: the skin's classes, a fixed time, each recording's earlier ground
// truth replaced, in item order. Returns the summary of the whole simulation.
SimulationSummary store_simulated_labels(const std::string& folder, const std::string& skin,
                                         const SimulatedTrials& trials);
// A shard's part (command "simulate"): the options, the plan, and per item done its file
// (name and size), seconds and labels.
Part simulation_part(const SimulatedTrials& trials, const std::string& folder,
                     const std::string& skin, const SimulationOptions& options, const Shard& shard);
// The gathered parts (shards/shard.h gather_parts) merged into `folder`: every item's recording
// checked to be there with the size its part names, then store_simulated_labels. Throws
// tactile::Error naming a missing or changed recording (and the part that made it).
SimulationSummary merge_simulation_parts(const std::vector<Part>& parts, const std::string& folder);

// The demo workspace: a few short recordings of every skin with a demo share in its record
// (the papers' five) in one folder (with labels.db), small enough to make in seconds.
SimulationSummary write_demo_workspace(const std::string& folder, uint64_t seed = 1,
                                       const SimulationProgress& progress = {});

// A simulated camera beside each of `files` (sim/touch_video.h), showing its ground-truth
// touches from labels.db in its folder: RECORDING-camera.mp4, attached to it as "camera" with the
// offset 0 (video/attachments.h; `tactile simulate --video`). Returns the videos written. Throws
// tactile::Error naming the recording.
std::vector<std::string> write_camera_videos(const std::vector<std::string>& files, uint64_t seed,
                                             const SimulationProgress& progress = {});

}  // namespace tactile

#pragma once
// Shared by the benchmarks that need Robovie at a real session's length (view_jobs_bench,
// real_size_bench).

#include <filesystem>
#include <vector>

#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile::bench {

// Robovie's 13 trials of one subject end to end: about 30 minutes of 274 films, its ground
// truth (the segments Predict takes when there are no suggestions) in labels.db beside it.
inline void write_long_robovie(const std::filesystem::path& folder) {
  const tactile::SkinLayout layout = tactile::load_layout("robovie");
  tactile::SimulationOptions options;
  options.subjects = 1;
  tactile::Recording whole;
  std::vector<tactile::Label> labels;
  double offset = 0.0;
  for (int trial = 0; offset < 1800.0; ++trial) {
    tactile::SimulatedTrial made =
        tactile::skin_record("robovie").simulate(layout, options, 0, trial);
    tactile::Stream& stream = made.recording.streams.front();
    if (trial == 0) {
      whole = made.recording;
      whole.id = "robovie-30min";
    } else {
      tactile::Stream& all = whole.streams.front();
      const auto rows = all.samples.rows();
      all.samples.conservativeResize(rows + stream.samples.rows(), Eigen::NoChange);
      all.samples.bottomRows(stream.samples.rows()) = stream.samples;
    }
    for (tactile::Label label : made.labels) {
      label.recording = whole.id;
      label.t0 += offset, label.t1 += offset;
      labels.push_back(label);
    }
    offset = whole.streams.front().sample_count() / whole.streams.front().rate_hz;
  }
  tactile::write_recording((folder / "robovie-30min.h5").string(), whole);
  tactile::LabelStore store((folder / "labels.db").string());
  store.add_many(labels);
}

}  // namespace tactile::bench

#pragma once
// The labelled segments of a label store's recordings as a feature table: `tactile features`
// and the workbench's File > Export features call these, so both write the same bytes (the
// table as CSV or ARFF, and the skip log OUT.log beside it).

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "tactile/features/corpus.h"
#include "tactile/shards/shard.h"

namespace tactile {

// By the names of `tactile features`' flags.
struct FeatureTableOptions {
  std::string pipeline;                 // --pipeline
  std::string params;                   // --params key=value,...
  std::string database;                 // --labels
  std::string source = "ground-truth";  // --source: which labels give the segments
  std::string recordings;               // --recordings: folder of ID.h5; "" = the database's
  std::string out;                      // --out FILE.csv or FILE.arff
  int threads = 0;                      // --threads; 0 = one per core
  std::string recording;                // only this recording's segments; "" = every recording's
  std::string layout;                   // only recordings of this skin; "" = every skin
  Shard shard;                          // --shard: only its recordings (the store's order)
};

struct FeatureTable {
  CorpusDataset corpus;
  size_t recordings = 0;  // the recordings read
  // Every recording of the job in the store's order, "ID:SEGMENTS" (a shard's plan), and
  // the indices of those this table holds.
  std::vector<std::string> plan;
  std::vector<size_t> done;
};

// Checks the options (refusals name the flag), finds the recordings and extracts every
// segment's row. `progress` as CorpusOptions'; extraction stops when `cancel` turns true.
FeatureTable extract_feature_table(const FeatureTableOptions& options,
                                   const std::function<void(int64_t, int64_t)>& progress = {},
                                   const std::atomic<bool>* cancel = nullptr);

// Writes OUT.log (the skipped segments, also when every segment was skipped) and then the
// table as CSV or ARFF by OUT's extension; throws tactile::Error naming OUT when there is no row.
void write_feature_table(const FeatureTable& table, const FeatureTableOptions& options);

// "N rows x C features from R recordings, S segments skipped -> OUT", as the command prints.
std::string feature_table_line(const FeatureTable& table, const FeatureTableOptions& options);
// The --json summary: rows, skipped, columns, per-class counts and means; indented.
std::string feature_table_json(const FeatureTable& table, const FeatureTableOptions& options);

//---- Shards: item k is the k-th recording of the store's order ------------------------------

// A shard's table as its part file's content (`tactile features --shard I/N`).
Part feature_table_part(const FeatureTable& table, const FeatureTableOptions& options);
// The table of the whole job from its gathered parts: rows, skips and segment counts as one
// process extracts them, ready for write_feature_table. Throws tactile::Error naming a part
// whose columns differ from the first's.
FeatureTable merge_feature_table_parts(const std::vector<Part>& parts);

}  // namespace tactile

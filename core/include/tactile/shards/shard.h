#pragma once
// Shards: a batch command's work split into N shares that separate processes (a Slurm job
// array, a shell loop, any scheduler) do alone, and the part files they write, which
// `tactile merge` combines into exactly what one process would have written
// (docs/CLUSTER.md).
//
// A command lists its work as items in an order of its own that depends only on its inputs
// (recordings in the store's order, presets x folds, seeds); item k belongs to shard
// (k mod N) + 1. A part file holds the command's name, its inputs, the shard, the size and
// a digest of the whole item list (so shards that saw different work never merge), and one
// entry per item it did, each with its index. The file is JSON with a checksum over what it
// holds, written atomically.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tactile {

struct Shard {
  int index = 0;  // 1..count
  int count = 0;  // 0: not sharded, the whole job
  bool active() const { return count > 0; }
  // True for every item when not sharded.
  bool owns(size_t item) const;
  // The items of a job of `total` items this shard does, ascending.
  std::vector<size_t> items_of(size_t total) const;
  std::string to_string() const;  // "2/4"
  // "I/N" with 1 <= I <= N; "" gives the whole job. Throws tactile::Error naming `where`.
  static Shard parse(const std::string& text, const std::string& where = "--shard");
};

// Where a shard's part goes when not told: "RESULT.part-I-of-N".
std::string default_part_path(const std::string& result, const Shard& shard);

// A digest of a job's item list (its keys in order): parts merge only when they agree on it.
std::string plan_digest(const std::vector<std::string>& keys);
// A digest of a file's bytes, for the inputs of a part (an input file that changed between
// the shards must not merge). Throws tactile::Error naming a file that cannot be read.
std::string file_digest(const std::string& path);

struct Part {
  std::string path;     // the file it was read from ("" before it is written)
  std::string command;  // "features", "evaluate", ...
  Shard shard;
  nlohmann::json inputs;  // the command's arguments that decide the result (object)
  std::string result;     // what one process would have written
  int64_t items = 0;      // items of the whole job
  std::string plan;       // plan_digest of the whole job's items
  nlohmann::json shared;  // what the command keeps beside its items (object; may be null)
  nlohmann::json done;    // the items this shard did: [{"index": k, ...}, ...] ascending
};

// Writes the part (a temporary beside the path, then renamed). Throws tactile::Error.
void write_part(const std::string& path, const Part& part);
// Reads and checks a part file. Throws tactile::Error naming the file: missing, not JSON,
// not a part, checksum failed (damaged or cut), an item outside its shard.
Part read_part(const std::string& path);

// The parts of one job, read and checked against each other, in shard order. Refuses, naming
// the files: no part; parts of another command (`command`, unless ""); parts whose inputs,
// result, shard count or item list differ (the first field that differs, with both values);
// a shard given twice (both files); shards missing ("shard 3/4 is missing", every one).
std::vector<Part> gather_parts(const std::vector<std::string>& paths,
                               const std::string& command = "");

// Every item of gathered parts in item order (each part's `done` entries, checked to be
// its own and to cover the job once); the entries as written.
std::vector<nlohmann::json> items_in_order(const std::vector<Part>& parts);

}  // namespace tactile

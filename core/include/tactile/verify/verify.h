#pragma once
// Checking files for damage: every chunk and attribute of a recording, every row of
// a label store, and what they must agree on. And rewriting files of earlier
// versions in the current, checked format. `tactile verify` and `tactile upgrade`.

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tactile/shards/shard.h"

namespace tactile {

enum class FileKind { kRecording, kLabelStore, kUnknown };

// By the file's first bytes (HDF5 or SQLite signature), else by its extension
// (.h5 .hdf5 / .db .sqlite .sqlite3): a file damaged at its start is still checked.
FileKind file_kind(const std::string& path);

struct FileProblem {
  std::string file;
  std::string message;  // "FILE:PLACE: what is wrong"
};

// Time spans of recordings by recording id, for checking labels against them.
using RecordingSpans = std::map<std::string, std::pair<double, double>>;

// Opens the recording, reads every attribute and every chunk of every dataset,
// recomputes the min/max overview from the samples and compares, checks the time
// stamps; in format 2 also that every chunked dataset carries Fletcher32 and no
// string is variable-length. Adds the recording's span to `spans` when it opens.
std::vector<FileProblem> verify_recording(const std::string& path, RecordingSpans* spans = nullptr);

// Every row of every table against its checksum and values, SQLite's integrity
// check, the digests, and labels inside the spans of the recordings in `spans`.
// Never changes the file (a store of schema 1 is reported, not upgraded).
std::vector<FileProblem> verify_label_store(const std::string& path,
                                            const RecordingSpans& spans = {});

struct VerifiedFile {
  std::string path;
  FileKind kind = FileKind::kUnknown;
  size_t problems = 0;
};

struct VerifyReport {
  std::vector<VerifiedFile> files;
  std::vector<FileProblem> problems;
};

// Files and folders (walked recursively for .h5/.hdf5/.db/.sqlite/.sqlite3);
// recordings first, so label stores are checked against their spans. `step` gets the
// fraction of the files checked, after each (and may throw to stop).
// = verify_report(plan, verify_items(plan, {}, step)) with plan = verify_plan(paths).
VerifyReport verify_paths(const std::vector<std::string>& paths,
                          const std::function<void(double)>& step = {});

// verify_paths in its parts, as `tactile verify --shard I/N` and `tactile merge` use them
// (shards/shard.h). The plan: the files in the order they are checked (recordings first, each
// group in walk order) with their kinds, and the walk's own problems (a missing path, a folder
// that cannot be listed).
struct VerifyPlan {
  std::vector<std::string> files;
  std::vector<FileKind> kinds;
  std::vector<FileProblem> walk_problems;
};
VerifyPlan verify_plan(const std::vector<std::string>& paths);
// One file of the plan checked: its entry of the report and its problems.
struct VerifiedItem {
  size_t index = 0;  // in plan.files
  VerifiedFile file;
  std::vector<FileProblem> problems;
};
// The files of the plan `shard` owns (every one when not sharded), checked in plan order. A
// label store is checked against the spans of every recording of the plan: the recordings
// this shard does not check are only opened for their span.
std::vector<VerifiedItem> verify_items(const VerifyPlan& plan, const Shard& shard = {},
                                       const std::function<void(double)>& step = {});
// The report of every item (all of the plan, in order): the walk's problems, then each file's.
VerifyReport verify_report(const VerifyPlan& plan, const std::vector<VerifiedItem>& items);
// FileKind by the name file_kind_name gives; throws tactile::Error on another name.
FileKind parse_file_kind(const std::string& name);

// "recording", "labels", "unknown": a file's kind as reports name it.
const char* file_kind_name(FileKind kind);
// "verified 2 recording(s) and 1 label store(s): no problems" (or "3 problem(s)"): the
// report's last line, after one line per problem (FileProblem::message).
std::string verify_summary_line(const VerifyReport& report);
// {"files": [{"path", "kind", "problems"}], "problems": [{"file", "problem"}], "ok"}, indented,
// with a final line break: `tactile verify --json`.
std::string verify_report_json(const VerifyReport& report);

struct UpgradeResult {
  FileKind kind = FileKind::kUnknown;
  int from_version = 0;
  int to_version = 0;
  bool rewritten() const { return from_version != to_version; }
};

// A recording of an earlier format is read, written beside itself in the current
// format, verified (checks and the same content, bit for bit), and only then
// renamed over the original: until that moment the original is untouched. A label
// store of schema 1 gets its checksums in one transaction. Throws tactile::Error
// naming the file when anything fails; the original then stays as it was.
UpgradeResult upgrade_file(const std::string& path);
// "PATH: format 1 -> 2", "PATH: already schema 3": what `tactile upgrade` prints per file.
std::string upgrade_line(const std::string& path, const UpgradeResult& result);

}  // namespace tactile

#pragma once
// The recording open in the workbench: where its samples come from (a SampleSource,
// never the whole file in memory), its layout and its labels.

#include <memory>
#include <string>
#include <vector>

#include "tactile/labels/lanes.h"
#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/online_classifier.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

struct Document {
  std::string path;         // absolute
  std::string labels_path;  // "" when the recording has no label database beside it
  std::unique_ptr<SampleSource> source;
  std::vector<std::string> streams;  // the file's streams, to choose from
  SkinLayout layout;
  std::vector<Label> labels;
  Lanes lanes;                 // the labels by tier, indexed by time
  int64_t labels_version = 0;  // new at every reload_labels(): views cache what they derive
  // The label store, open while the document is (every edit is one transaction in it);
  // null until there is one (created beside the recording by the first edit).
  std::unique_ptr<LabelStore> store;
  // What of the store this document has seen: its change count (LabelStore::change_count,
  // moved on by other writers' commits) and its newest journal row, so that the others'
  // edits are reloaded and named (follow_other_writers, labelling.h).
  int64_t store_changes = 0;
  int64_t journal_seen = 0;
  // The store's newest journal row when this document first saw it: an undo of an edit at or
  // before it takes back work of an earlier session, and says so.
  int64_t journal_at_open = -1;
  // The skin's class vocabulary: the store's for this layout, else the layout's own.
  std::vector<std::string> classes;
  // Damaged label rows left out of `labels`, or why the label store did not open,
  // each "STORE: place: what". Damaged samples are the source's damage().
  std::vector<std::string> label_problems;
  // A live stream with nothing recorded yet: labels have no recording to belong to, so
  // label_store() refuses with this reason ("" for a recording).
  std::string labels_refused;
  // Labels shown but not stored: live decisions of an online model (their own lane).
  std::vector<Label> transient_labels;
  // Why labels cannot be saved where they belong (a read-only folder or store), with the way
  // out; "" when they can. The recording is viewed all the same; label_store() refuses.
  std::string labels_read_only;
  // The recording id labels are made for when the source has none of its own (live).
  std::string live_recording_id;

  const SampleSource& samples() const { return *source; }
  // Re-reads this recording's labels from the store and rebuilds the lanes.
  void reload_labels();
  // Takes the store's change count and newest journal row as seen.
  void mark_store_seen();
  // The store, opened (or created beside the recording) on first need. Throws
  // tactile::Error.
  LabelStore& label_store();
  // The user's own store for this recording's folder (docs/FILE_FORMAT.md, "Read-only folders
  // and stores"), and the switch to it: the read-only store's labels of this recording are
  // copied in once. Throws tactile::Error.
  std::string own_store_path() const;
  void keep_labels_in_own_store();
  const std::string& recording_id() const {
    return live_recording_id.empty() ? source->info().recording_id : live_recording_id;
  }
};

struct DocumentOptions {
  std::string labels_path;  // "" = labels.db beside the recording when there is one
  std::string stream;       // "" = the first stream
  int64_t cache_bytes = int64_t{32} << 20;
};

// Faults of the disk, injected into every open recording's reads (`fault read` in scripts, for
// tests and benchmarks): reads that hang, or that fail as on a pulled USB stick.
enum class ReadFault { kNone, kHang, kFail };
void inject_read_fault(ReadFault fault);

// Opens a recording (HDF5) through a file-backed source, with its layout and labels.
// Throws tactile::Error when the recording cannot be opened; damaged chunks read as
// gaps (the source's damage()) and damaged label rows are left out and named.
std::unique_ptr<Document> open_document(const std::string& path, const DocumentOptions& options);

}  // namespace tactile

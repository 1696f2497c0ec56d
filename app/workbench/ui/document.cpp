#include "document.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <set>
#include <thread>

#include "tactile/error.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

namespace fs = std::filesystem;

namespace {

std::atomic<int> injected_fault{static_cast<int>(ReadFault::kNone)};

// On a source's reading thread, before each read of its file.
void read_as_injected(const std::string& path) {
  // A hang lasts while it is injected (a minute at most, so that a forgotten one ends).
  for (int waited = 0; injected_fault.load() == static_cast<int>(ReadFault::kHang) && waited < 6000;
       ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (injected_fault.load() == static_cast<int>(ReadFault::kFail))
    throw Error(path, "cannot read the file: Input/output error (injected)");
}

}  // namespace

void inject_read_fault(ReadFault fault) { injected_fault.store(static_cast<int>(fault)); }

namespace {

// Why labels cannot be written at `store` ("" when they can): the store is read-only, or the
// folder it is (or would be) in is, where SQLite keeps its write-ahead log beside it.
std::string read_only_reason(const fs::path& store) {
  std::error_code error;
  if (fs::exists(store, error) && ::access(store.c_str(), W_OK) != 0)
    return store.string() + " is read-only";
  const fs::path folder = store.parent_path().empty() ? fs::path(".") : store.parent_path();
  if (::access(folder.c_str(), W_OK) != 0) return "the folder " + folder.string() + " is read-only";
  return "";
}

// A user's own place for labels of recordings in folders they cannot write:
// $XDG_DATA_HOME (or ~/.local/share)/tactile-workbench/labels/FOLDER-HASH.db.
std::string own_store_for(const std::string& recording) {
  const char* data = std::getenv("XDG_DATA_HOME");
  const char* home = std::getenv("HOME");
  const fs::path root =
      data && *data ? fs::path(data) : fs::path(home ? home : ".") / ".local" / "share";
  const fs::path folder = fs::path(recording).parent_path();
  char hash[17];
  std::snprintf(hash, sizeof hash, "%08zx",
                std::hash<std::string>{}(folder.string()) & 0xffffffffu);
  return (root / "tactile-workbench" / "labels" / (folder.filename().string() + "-" + hash + ".db"))
      .string();
}

}  // namespace

std::unique_ptr<Document> open_document(const std::string& path, const DocumentOptions& options) {
  auto document = std::make_unique<Document>();
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  document->path = error ? path : absolute.lexically_normal().string();
  FileSourceOptions source_options;
  source_options.stream = options.stream;
  source_options.cache_bytes = options.cache_bytes;
  source_options.damaged_chunks_as_gaps = true;
  source_options.before_read = [path = document->path] { read_as_injected(path); };
  auto source = std::make_unique<FileSampleSource>(document->path, source_options);
  document->streams = source->stream_names();
  document->source = std::move(source);
  document->layout = load_layout(document->source->info().layout_id);
  document->labels_path = options.labels_path;
  if (document->labels_path.empty()) {
    const fs::path beside = fs::path(document->path).parent_path() / "labels.db";
    if (fs::exists(beside, error)) document->labels_path = beside.string();
  }
  document->classes = document->layout.classes;
  const std::string read_only = read_only_reason(
      document->labels_path.empty() ? fs::path(document->path).parent_path() / "labels.db"
                                    : fs::path(document->labels_path));
  if (!read_only.empty())
    document->labels_read_only = "labels cannot be saved here (" + read_only +
                                 "): Labels > Keep labels in my own store (" +
                                 own_store_for(document->path) + ")";
  if (!document->labels_path.empty()) {
    // A damaged label store costs the labels, not the recording.
    try {
      document->store = std::make_unique<LabelStore>(
          document->labels_path,
          read_only.empty() ? LabelStore::OpenMode::kCreate : LabelStore::OpenMode::kReadOnly);
      document->mark_store_seen();
      const std::vector<std::string> vocabulary = document->store->classes(document->layout.id);
      if (!vocabulary.empty()) document->classes = vocabulary;
    } catch (const Error& failure) {
      document->label_problems.push_back(failure.what());
    }
  }
  document->reload_labels();
  // No vocabulary for this skin (a grid, other people's data): the classes its labels use.
  if (document->classes.empty()) {
    std::set<std::string> used;
    for (const Label& label : document->labels)
      if (label.class_name != kUnknownClass) used.insert(label.class_name);
    document->classes.assign(used.begin(), used.end());
  }
  return document;
}

void Document::reload_labels() {
  if (store) {
    LabelFilter filter;
    filter.recording = recording_id();
    labels = store->list(filter);
    label_problems.clear();
    for (const StoreProblem& problem : store->problems())
      label_problems.push_back(problem.where(store->path()) + ": " + problem.what);
  }
  // Without a store the labels are last time's: their transient part is replaced.
  std::erase_if(labels, [](const Label& label) {
    return label.id == 0 && label.annotator == kOnlineAnnotator;
  });
  labels.insert(labels.end(), transient_labels.begin(), transient_labels.end());
  lanes = group_into_lanes(labels);
  // Unique across documents, so a cache never mistakes a reopened recording for the last.
  static std::atomic<int64_t> reloads{0};
  labels_version = ++reloads;
}

void Document::mark_store_seen() {
  if (!store) return;
  store_changes = store->change_count();
  journal_seen = store->last_sequence();
  if (journal_at_open < 0) journal_at_open = journal_seen;
}

LabelStore& Document::label_store() {
  if (!labels_refused.empty()) throw Error("labels", labels_refused);
  // Refused before anything is written: nothing half-written in a read-only folder.
  if (!labels_read_only.empty()) throw Error("labels", labels_read_only);
  if (!store) {
    if (labels_path.empty()) labels_path = (fs::path(path).parent_path() / "labels.db").string();
    store = std::make_unique<LabelStore>(labels_path);
    mark_store_seen();
    if (!layout.classes.empty() && store->classes(layout.id).empty())
      store->set_classes(layout.id, layout.classes);
  }
  return *store;
}

std::string Document::own_store_path() const { return own_store_for(path); }

void Document::keep_labels_in_own_store() {
  const std::string own = own_store_path();
  std::error_code error;
  fs::create_directories(fs::path(own).parent_path(), error);
  if (error)
    throw Error(fs::path(own).parent_path().string(),
                "cannot create the folder: " + error.message());
  auto mine = std::make_unique<LabelStore>(own);
  if (!layout.classes.empty() && mine->classes(layout.id).empty())
    mine->set_classes(layout.id, layout.classes);
  // The read-only store's labels of this recording come along, once.
  LabelFilter filter;
  filter.recording = recording_id();
  if (store && mine->count(recording_id()) == 0) {
    std::vector<Label> kept = store->list(filter);
    if (!kept.empty()) mine->add_many(kept);
  }
  store = std::move(mine);
  labels_path = own;
  labels_read_only.clear();
  journal_at_open = -1;  // another store: its own journal
  mark_store_seen();     // the copy is ours, not another writer's news
  reload_labels();
}

}  // namespace tactile

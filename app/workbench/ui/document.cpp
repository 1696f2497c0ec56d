#include "document.h"

#include <atomic>
#include <filesystem>
#include <set>

#include "tactile/error.h"
#include "tactile/io/label_store.h"

namespace tactile {

namespace fs = std::filesystem;

std::unique_ptr<Document> open_document(const std::string& path, const DocumentOptions& options) {
  auto document = std::make_unique<Document>();
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  document->path = error ? path : absolute.lexically_normal().string();
  FileSourceOptions source_options;
  source_options.stream = options.stream;
  source_options.cache_bytes = options.cache_bytes;
  source_options.damaged_chunks_as_gaps = true;
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
  if (!document->labels_path.empty()) {
    // A damaged label store costs the labels, not the recording.
    try {
      document->store = std::make_unique<LabelStore>(document->labels_path);
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
  std::erase_if(labels, [](const Label& label) { return label.id == 0 && label.annotator == kOnlineAnnotator; });
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
}

LabelStore& Document::label_store() {
  if (!labels_refused.empty()) throw Error("labels", labels_refused);
  if (!store) {
    if (labels_path.empty()) labels_path = (fs::path(path).parent_path() / "labels.db").string();
    store = std::make_unique<LabelStore>(labels_path);
    mark_store_seen();
    if (!layout.classes.empty() && store->classes(layout.id).empty())
      store->set_classes(layout.id, layout.classes);
  }
  return *store;
}

}  // namespace tactile

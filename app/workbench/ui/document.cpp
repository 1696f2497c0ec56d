#include "document.h"

#include <filesystem>

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
  if (!document->labels_path.empty()) {
    // A damaged label store costs the labels, not the recording.
    try {
      LabelStore store(document->labels_path);
      LabelFilter filter;
      filter.recording = document->recording_id();
      document->labels = store.list(filter);
      for (const StoreProblem& problem : store.problems())
        document->label_problems.push_back(problem.where(store.path()) + ": " + problem.what);
    } catch (const Error& failure) {
      document->label_problems.push_back(failure.what());
    }
  }
  return document;
}

}  // namespace tactile

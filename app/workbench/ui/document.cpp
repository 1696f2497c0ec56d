#include "document.h"

#include <filesystem>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/io/label_store.h"

namespace tactile {

namespace fs = std::filesystem;

std::unique_ptr<Document> open_document(const std::string& path, const std::string& labels_path) {
  auto document = std::make_unique<Document>();
  document->path = path;
  document->recording = read_recording(path);
  if (document->recording.streams.empty()) throw Error(path, "the recording has no stream");
  document->layout = load_layout(document->recording.layout_id);
  document->labels_path = labels_path;
  if (document->labels_path.empty()) {
    const fs::path beside = fs::path(path).parent_path() / "labels.db";
    std::error_code error;
    if (fs::exists(beside, error)) document->labels_path = beside.string();
  }
  if (!document->labels_path.empty()) {
    LabelStore store(document->labels_path);
    LabelFilter filter;
    filter.recording = document->recording.id;
    document->labels = store.list(filter);
  }
  select_stream(*document, 0);
  return document;
}

void select_stream(Document& document, int stream_index) {
  document.stream_index = stream_index;
  const Stream& stream = document.stream();
  document.pyramids.clear();
  document.pyramids.reserve(static_cast<size_t>(stream.channel_count()));
  for (int64_t column = 0; column < stream.channel_count(); ++column)
    document.pyramids.emplace_back(std::span<const float>(
        stream.samples.col(column).data(), static_cast<size_t>(stream.sample_count())));
}

}  // namespace tactile

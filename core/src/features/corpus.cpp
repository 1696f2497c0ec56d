// Corpus feature extraction on a small pool of worker threads.
#include "tactile/features/corpus.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/jobs/job.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// What one recording gives, kept until every recording is done so rows can be merged in
// the given order.
struct RecordingRows {
  std::vector<FeatureColumn> columns;
  std::string layout_id;
  std::vector<std::vector<double>> values;
  std::vector<Label> labels;  // the row's segment, class resolved
  std::vector<std::string> subjects;
  std::vector<Metadata> metadata;
  std::vector<SkippedSegment> skipped;
  std::exception_ptr error;
};

RecordingRows extract_recording(const FeatureExtractor& extractor, const CorpusRecording& job,
                                const std::atomic<bool>* cancel) {
  const auto stop_if_cancelled = [cancel] {
    if (cancel != nullptr && cancel->load()) throw Error("features", "cancelled");
  };
  RecordingRows rows;
  // A pipeline that reads only the segments' samples reads their windows from the file (30
  // minutes of Robovie are never held whole); any other reads the whole recording.
  std::optional<FileSampleSource> source;
  std::optional<Recording> raw;
  if (extractor.reads_segment_only())
    source.emplace(job.path);
  else
    raw = read_recording(job.path, [&](double) { stop_if_cancelled(); });
  const SkinLayout layout = load_layout(source ? source->info().layout_id : raw->layout_id);
  rows.layout_id = layout.id;
  rows.columns = extractor.columns(layout);
  stop_if_cancelled();
  // A long recording has many segments: a cancel stops between two.
  const auto each = [&](size_t) { stop_if_cancelled(); };
  const FeatureExtractor::Segments extracted =
      source ? extract_source_segments(extractor, *source, layout, job.segments, each)
             : extractor.extract_segments(*raw, layout, job.segments, each);
  const auto subject = extracted.metadata.find("subject");
  Metadata shared = extracted.metadata;
  // These have columns of their own in a dataset.
  for (const char* key : {"subject", "class", "recording", "segment_id"}) shared.erase(key);
  shared["layout"] = layout.id;
  for (size_t index_of_segment = 0; index_of_segment < job.segments.size(); ++index_of_segment) {
    const Label& segment = job.segments[index_of_segment];
    const FeatureResult& result = extracted.results[index_of_segment];
    std::string reason = result.skip_reason;
    if (reason.empty() && result.values.size() != rows.columns.size())
      reason = "extractor gave " + std::to_string(result.values.size()) + " values for " +
               std::to_string(rows.columns.size()) + " columns";
    for (size_t index = 0; reason.empty() && index < result.values.size(); ++index)
      if (!std::isfinite(result.values[index]))
        reason = "non-finite value in column " + rows.columns[index].name;
    if (!reason.empty()) {
      rows.skipped.push_back({job.id, segment.id, segment.t0, segment.t1, reason});
      continue;
    }
    rows.values.push_back(result.values);
    Label labelled = segment;
    labelled.recording = job.id;
    labelled.class_name = segment_class(segment, job.ground_truth);
    rows.labels.push_back(std::move(labelled));
    rows.subjects.push_back(subject == extracted.metadata.end() ? "" : subject->second);
    Metadata metadata = shared;
    metadata["region"] = segment.region;
    metadata["t0"] = shortest_text(segment.t0);
    metadata["t1"] = shortest_text(segment.t1);
    rows.metadata.push_back(std::move(metadata));
  }
  return rows;
}

bool same_names(const std::vector<FeatureColumn>& a, const std::vector<FeatureColumn>& b) {
  return std::equal(
      a.begin(), a.end(), b.begin(), b.end(),
      [](const FeatureColumn& x, const FeatureColumn& y) { return x.name == y.name; });
}

}  // namespace

std::string segment_class(const Label& segment, const std::vector<Label>& ground_truth) {
  if (!segment.class_name.empty() && segment.class_name != kUnknownClass) return segment.class_name;
  std::string best = kUnknownClass;
  double longest = 0.0;
  for (const Label& truth : ground_truth) {
    if (truth.recording != segment.recording && !segment.recording.empty()) continue;
    const double overlap = std::min(segment.t1, truth.t1) - std::max(segment.t0, truth.t0);
    if (overlap > longest) {
      longest = overlap;
      best = truth.class_name;
    }
  }
  return best;
}

std::vector<CorpusRecording> corpus_from_store(const CorpusQuery& query) {
  LabelStore store(query.database, LabelStore::OpenMode::kExisting);
  LabelFilter filter;
  filter.source = query.source;
  if (!query.recording.empty()) filter.recording = query.recording;
  const std::vector<Label> labels = store.list(filter);
  std::map<std::string, std::vector<Label>> ground_truth;
  if (query.source != LabelSource::kGroundTruth) {
    LabelFilter truth;
    truth.source = LabelSource::kGroundTruth;
    if (!query.recording.empty()) truth.recording = query.recording;
    for (Label& label : store.list(truth))
      ground_truth[label.recording].push_back(std::move(label));
  }
  const std::filesystem::path folder = query.folder.empty()
                                           ? std::filesystem::absolute(query.database).parent_path()
                                           : std::filesystem::path(query.folder);
  std::vector<CorpusRecording> corpus;
  std::map<std::string, size_t> wanted;  // recording id -> index in corpus, npos: other layout
  for (const Label& label : labels) {
    auto known = wanted.find(label.recording);
    if (known == wanted.end()) {
      const std::string path = (folder / (label.recording + ".h5")).string();
      std::error_code error;
      if (!std::filesystem::is_regular_file(path, error))
        throw Error(path, "recording file missing (recording '" + label.recording +
                              "' has labels in " + query.database + ")");
      const bool of_layout =
          query.layout.empty() || RecordingFile(path).layout_id() == query.layout;
      known = wanted.emplace(label.recording, of_layout ? corpus.size() : std::string::npos).first;
      if (of_layout) {
        CorpusRecording recording;
        recording.id = label.recording;
        recording.path = path;
        recording.ground_truth = ground_truth[label.recording];
        corpus.push_back(std::move(recording));
      }
    }
    if (known->second != std::string::npos) corpus[known->second].segments.push_back(label);
  }
  if (corpus.empty())
    throw Error(query.database,
                std::string("no labels of source ") + to_string(query.source) +
                    (query.layout.empty() ? "" : " on " + query.layout + " recordings") +
                    (query.recording.empty() ? "" : " of recording " + query.recording));
  return corpus;
}

CorpusDataset extract_corpus(const FeatureExtractor& extractor,
                             const std::vector<CorpusRecording>& recordings,
                             const CorpusOptions& options) {
  const auto total = static_cast<int64_t>(recordings.size());
  std::vector<RecordingRows> results(recordings.size());
  int threads = options.threads > 0 ? options.threads : thread_budget();
  threads = std::clamp<int>(threads, 1, std::max<int>(1, static_cast<int>(total)));

  std::atomic<int64_t> next{0};
  std::mutex progress_mutex;
  int64_t done = 0;
  const auto work = [&] {
    while (true) {
      if (options.cancel != nullptr && options.cancel->load()) return;
      const int64_t index = next.fetch_add(1);
      if (index >= total) return;
      RecordingRows& rows = results[static_cast<size_t>(index)];
      try {
        rows = extract_recording(extractor, recordings[static_cast<size_t>(index)], options.cancel);
      } catch (...) {
        rows.error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(progress_mutex);
      ++done;
      if (options.progress) options.progress(done, total);
    }
  };
  std::vector<std::thread> pool;
  for (int worker = 1; worker < threads; ++worker) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  if (options.cancel != nullptr && options.cancel->load()) throw Error("features", "cancelled");

  CorpusDataset corpus;
  Dataset& dataset = corpus.dataset;
  int64_t row_count = 0;
  for (size_t index = 0; index < results.size(); ++index) {
    const RecordingRows& rows = results[index];
    if (rows.error) std::rethrow_exception(rows.error);
    if (index == 0) {
      dataset.columns = rows.columns;
    } else if (!same_names(rows.columns, dataset.columns)) {
      throw Error(recordings[index].path,
                  "layout " + rows.layout_id + " gives " + std::to_string(rows.columns.size()) +
                      " other columns than layout " + results[0].layout_id + " of " +
                      recordings[0].path + " (" + std::to_string(dataset.columns.size()) +
                      "); extract one layout at a time");
    }
    row_count += static_cast<int64_t>(rows.values.size());
  }
  dataset.features.resize(row_count, static_cast<int64_t>(dataset.columns.size()));
  int64_t row = 0;
  for (RecordingRows& rows : results) {
    for (size_t index = 0; index < rows.values.size(); ++index, ++row) {
      dataset.features.row(row) =
          Eigen::Map<const Eigen::RowVectorXd>(rows.values[index].data(), dataset.features.cols());
      dataset.classes.push_back(rows.labels[index].class_name);
      dataset.subjects.push_back(rows.subjects[index]);
      dataset.recordings.push_back(rows.labels[index].recording);
      dataset.segment_ids.push_back(rows.labels[index].id);
      dataset.metadata.push_back(std::move(rows.metadata[index]));
    }
    corpus.skipped.insert(corpus.skipped.end(), rows.skipped.begin(), rows.skipped.end());
    corpus.segments += static_cast<int64_t>(rows.values.size() + rows.skipped.size());
  }
  return corpus;
}

}  // namespace tactile

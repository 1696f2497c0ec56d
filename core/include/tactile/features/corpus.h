#pragma once
// Corpus feature extraction: many recordings, each read and preprocessed once, its
// labelled segments turned into dataset rows, on worker threads with progress and
// cancel. Rows come out in the order the recordings and their segments were given,
// whatever the threads did.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tactile/features/dataset.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/labelstore/label.h"

namespace tactile {

struct CorpusRecording {
  std::string id;                   // the recording id the labels use
  std::string path;                 // its .h5 file
  std::vector<Label> segments;      // one row each (or a skip)
  std::vector<Label> ground_truth;  // classes for segments without one
};

struct SkippedSegment {
  std::string recording;
  int64_t segment_id = 0;
  double t0 = 0.0, t1 = 0.0;
  std::string reason;
};

struct CorpusOptions {
  int threads = 0;  // 0: one per hardware thread; never more than there are recordings
  // Called after each recording with (recordings done, total), one call at a time.
  std::function<void(int64_t, int64_t)> progress;
  // When set and true, workers stop after their current recording and
  // extract_corpus throws tactile::Error("features", "cancelled").
  const std::atomic<bool>* cancel = nullptr;
};

struct CorpusDataset {
  Dataset dataset;
  std::vector<SkippedSegment> skipped;  // in recording, then segment order
  int64_t segments = 0;                 // segments seen (rows + skipped)
};

// The extractor's const methods are called from several threads at once. Columns come
// from the first recording's layout; a recording whose layout gives other columns is an
// error. Row metadata: the recording's metadata (but subject, which has its own column),
// plus layout, region, t0 and t1 of the segment. A row with a non-finite value is skipped
// with a reason, never written. Throws tactile::Error naming the file for an unreadable
// recording (the first failing one in the given order).
CorpusDataset extract_corpus(const FeatureExtractor& extractor,
                             const std::vector<CorpusRecording>& recordings,
                             const CorpusOptions& options = {});

// The labels of one source in a label store grouped by recording (the store's order),
// each recording's file `folder/ID.h5` (folder "" = the database's folder) checked up
// front, with the ground truth of each for segments without a class. With `layout`, only
// recordings of that skin (read from each file's attributes); with `recording`, only that
// one. Throws tactile::Error naming the database when it holds no such labels, or the file
// that is missing.
struct CorpusQuery {
  std::string database;
  LabelSource source = LabelSource::kGroundTruth;
  std::string folder;
  std::string layout;
  std::string recording = {};  // a default: callers that list the fields above stay valid
};
std::vector<CorpusRecording> corpus_from_store(const CorpusQuery& query);

// A segment's class: its own, or for one without (empty or kUnknownClass) the class of
// the ground-truth label overlapping it longest (the first of equals), kUnknownClass
// when none overlaps.
std::string segment_class(const Label& segment, const std::vector<Label>& ground_truth);

}  // namespace tactile

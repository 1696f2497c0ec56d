#pragma once
// A dataset: one row of features per segment, with class, subject, recording, segment
// id and metadata, so any evaluation protocol can split by them. Written as CSV (pandas)
// or ARFF (Weka), read back from CSV.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/io/recording.h"

namespace tactile {

struct Dataset {
  std::vector<FeatureColumn> columns;   // feature columns
  Eigen::MatrixXd features;             // rows = segments, columns = features
  std::vector<std::string> classes;     // per row
  std::vector<std::string> subjects;    // per row ("" when unknown)
  std::vector<std::string> recordings;  // per row
  std::vector<int64_t> segment_ids;     // per row: the label id in the label store
  std::vector<Metadata> metadata;       // per row: region, side, condition, trial, ...

  int64_t rows() const { return features.rows(); }
  // Distinct classes in first-seen order.
  std::vector<std::string> class_names() const;
  // The value of metadata `key` that every row carries ("layout": the table's skin); "" when
  // rows differ, lack it, or there are none.
  std::string shared_metadata(const std::string& key) const;
};

// CSV: feature columns, then class, subject, recording, segment_id and one column per
// metadata key (union over rows, sorted). Numbers round-trip exactly. Temp file + rename.
void write_dataset_csv(const std::string& path, const Dataset& dataset);
// ARFF for Weka: numeric attributes, then class as a nominal attribute (and subject,
// recording as strings are left out so that Weka's classifiers run on the file as is).
void write_dataset_arff(const std::string& path, const Dataset& dataset,
                        const std::string& relation);
// Reads a dataset CSV: the one write_dataset_csv writes, or any CSV with a `class`
// column whose other numeric columns are features. Throws tactile::Error naming file,
// line and column.
//   Our own files are recognised by class, subject, recording, segment_id side by side:
//   columns before them are features, columns after them metadata (an empty cell: the row
//   lacks that key). In any other file a column is a feature when its first data row holds
//   a number there, else metadata; subject, recording and segment_id are optional. Column
//   descriptions are not stored in CSV and read back empty. Both writers refuse a dataset
//   with no rows, NaN/inf values, repeated column names or an empty class; the ARFF
//   also leaves out segment_id and metadata, and keeps descriptions as comments.
Dataset read_dataset_csv(const std::string& path);

}  // namespace tactile

#pragma once
// Labels made elsewhere, in the two shapes `tactile labels export` writes: RFC 4180
// CSV (header id,recording,t0,t1,region,class,annotator,source,confidence,note,
// created,modified; quoted fields may hold commas, quotes and line breaks) and JSON
// ({"labels": [...]}). `tactile labels import` adds them to a store in one transaction.

#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

// Each label is validated as the store validates a new one; throws tactile::Error naming the
// file and line (CSV) or label index (JSON) of the first bad one. Ids, created and modified
// are read but the store assigns its own. Which of the two a file is, is the label formats'
// choice (labels/label_format.h).
std::vector<Label> read_labels_csv(const std::string& path);
std::vector<Label> read_labels_json(const std::string& path);

// The CSV that `labels export --csv` writes for these labels (LabelStore::export_csv).
std::string labels_csv(const std::vector<Label>& labels);

}  // namespace tactile

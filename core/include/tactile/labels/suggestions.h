#pragma once
// Suggestions: a segmenter's labels an operator accepts into their own lane or rejects.
// A rejected suggestion is remembered (LabelStore::reject), so a rerun of the method
// leaves out the segments that match it.

#include <string>
#include <vector>

#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

// Removes from `segments` those matching a rejection of the same recording and method
// (their spans overlap with IoU >= `iou`). Returns how many were removed.
size_t drop_rejected(std::vector<Label>& segments, const std::vector<Rejection>& rejections,
                     double iou = 0.5);

// A segmenter run as one edit of the store, as both the command line and the workbench store
// it: segments without a class get kUnknownClass, segments an annotator rejected before are
// left out, and with `replace` the recording's earlier suggestions of the same method go.
struct SegmenterRun {
  LabelEdit edit;
  std::string annotator;  // the suggestions' annotator, "segmenter:METHOD"
  size_t rejected = 0;    // segments left out: rejected before
  size_t replaced = 0;    // earlier suggestions of the method removed
};
SegmenterRun segmenter_run(const LabelStore& store, const std::string& recording,
                           const std::string& method, std::vector<Label> segments,
                           bool replace = true);

}  // namespace tactile

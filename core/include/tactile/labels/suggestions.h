#pragma once
// Suggestions: a segmenter's labels an operator accepts into their own lane or rejects.
// A rejected suggestion is remembered (LabelStore::reject), so a rerun of the method
// leaves out the segments that match it.

#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/label_store.h"

namespace tactile {

// Removes from `segments` those matching a rejection of the same recording and method
// (their spans overlap with IoU >= `iou`). Returns how many were removed.
size_t drop_rejected(std::vector<Label>& segments, const std::vector<Rejection>& rejections,
                     double iou = 0.5);

}  // namespace tactile

#pragma once
// A label: a touch segment [t0, t1) of a recording, on a region, with a class.

#include <cstdint>
#include <optional>
#include <string>

namespace tactile {

enum class LabelSource { kManual, kSegmenter, kModel, kGroundTruth };

// "manual", "segmenter", "model", "ground-truth".
const char* to_string(LabelSource source);
// Throws tactile::Error on an unknown name.
LabelSource parse_label_source(const std::string& name);

// The class stored for a segment whose class nobody knows yet (a segmenter's output): the
// label store needs a class, and `tactile features` gives such segments the class of the
// ground truth they overlap most.
inline constexpr const char* kUnknownClass = "unknown";

struct Label {
  int64_t id = 0;  // assigned by the LabelStore; 0 before insertion
  std::string recording;
  double t0 = 0.0;             // seconds, inclusive
  double t1 = 0.0;             // seconds, exclusive
  std::string region = "all";  // a layout group id, or "all"
  std::string class_name;
  std::string annotator;
  LabelSource source = LabelSource::kManual;
  double confidence = 1.0;
  std::string note;
  std::string created;   // ISO 8601 UTC, set by the store
  std::string modified;  // ISO 8601 UTC, set by the store
  // Set by the store: 1 when added, one more at every change (an edit, an undo, a redo). An
  // edit of the label states the revision its editor last saw, and the store refuses it when
  // someone else changed the label since (LabelStore::apply).
  int64_t revision = 0;
};

}  // namespace tactile

#pragma once
// Labels to and from the tools labs already use (docs/INTEROP.md): ELAN's .eaf (EAF 3.0 XML,
// label_eaf.cpp) and Label Studio's JSON export of time-series labels (label_studio.cpp).
//
// ELAN: one tier per lane (tier id = the lane id: "ground-truth", "manual:ana",
// "segmenter:threshold", "model:svm"), the class as the annotation's value from a controlled
// vocabulary (the skin's), and region, confidence and note as dependent tiers
// (Symbolic_Association) "TIER/region", "TIER/confidence", "TIER/note". ELAN counts in whole
// milliseconds: times come back to the millisecond.
//
// Label Studio: one task per recording; ground truth and each annotator an annotation (ground
// truth with "ground_truth": true), each segmenter and model a prediction (model_version = the
// lane id, each result's score = the confidence); times are start/end in seconds, exact.
//
// Both readers check every element before anything is returned, and refuse a malformed one
// with tactile::Error naming the file and the element (tier and annotation id, task and result
// id): import_interop_file adds all or nothing.

#include <map>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

struct InteropImport {
  // The recording of the labels; when empty, the file's own (ELAN: the tactile:recording
  // property, else the media file's name; Label Studio: the task's data).
  std::string recording;
  // ELAN: tier -> lane id ("ground-truth", "manual:NAME" or just NAME, "segmenter:METHOD",
  // "model:NAME", or "" for the tier's default lane). When not empty, only these tiers are
  // imported, and each must exist.
  std::map<std::string, std::string> tiers;
  // Label Studio: annotator (completed_by: the user's id or email, or our name) -> lane id.
  std::map<std::string, std::string> annotators;
};

// The labels of one recording as an EAF 3.0 document. `vocabulary` is the controlled
// vocabulary of classes (the skin's); classes the labels use beyond it are added. Throws naming
// the label when it spans less than a millisecond, or when the labels hold several recordings.
std::string labels_eaf(const std::vector<Label>& labels,
                       const std::vector<std::string>& vocabulary = {});
// `where` names the document in errors (the file's path).
std::vector<Label> parse_eaf(const std::string& text, const std::string& where,
                             const InteropImport& options = {});

// The labels (any recordings) as Label Studio's JSON export: a list of tasks.
std::string labels_label_studio(const std::vector<Label>& labels);
std::vector<Label> parse_label_studio(const std::string& text, const std::string& where,
                                      const InteropImport& options = {});

// What a file holds, for choosing before an import: ELAN's top-level tiers (dependent ones
// carry regions, confidences and notes), Label Studio's annotators (completed_by, or our name)
// and model versions. `lane` is where a source's labels go unless mapped.
struct InteropSource {
  std::string name;   // the tier id; the annotator (our name, else the user's id or email);
                      // the prediction's model_version
  std::string lane;   // "ground-truth", "manual:NAME" or NAME, "segmenter:METHOD", "model:NAME"
  size_t labels = 0;  // annotations (ELAN) or results (Label Studio)
};
struct InteropSources {
  std::string format;     // "ELAN", "Label Studio"
  std::string recording;  // the file's own (ELAN: its property or media; Label Studio: the
                          // tasks', comma-separated); "" when it names none
  std::vector<InteropSource> sources;
};
InteropSources eaf_sources(const std::string& text, const std::string& where);
InteropSources label_studio_sources(const std::string& text, const std::string& where);

// True for a .json file in Label Studio's shape (a list of tasks, or one task), not
// {"labels": [...]} as `labels export --json` writes.
bool is_label_studio_json(const std::string& text);

// A file's text, refused past 256 MiB before anything is allocated.
std::string read_interop_text(const std::string& path);

}  // namespace tactile

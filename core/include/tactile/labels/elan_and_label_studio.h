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
// truth with "ground_truth": true; completed_by only for an annotator mapped to a project member,
// the name in our key tactile_annotator), each segmenter and model a prediction (model_version =
// the lane id, each result's score = the confidence); times are start/end in seconds, exact.
// Read: the spans of a TimeSeries (timeserieslabels; epoch milliseconds when its time column
// holds dates, placed on the recording's clock) and of an Audio (labels, in seconds); results
// of other controls are left out and counted.
//
// Both readers check every element before anything is returned, and refuse a malformed one
// with tactile::Error naming the file and the element (tier and annotation id, task and result
// id): import_interop_file adds all or nothing.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tactile/labelstore/label.h"

namespace tactile {

// Where a recording's first sample sits on the wall clock: what places Label Studio's epoch
// milliseconds (a TimeSeries whose time column holds dates) on the recording's own clock.
struct RecordingClock {
  bool found = false;         // the recording's file was read
  double first_sample = 0.0;  // the time of its first sample on its own clock, in seconds
  // That sample's Unix time in milliseconds, when the file says: its clock is a Unix clock
  // (first sample at 1e9 s or later), or its metadata start_time is a date-time with a zone.
  std::optional<double> start_ms;
  std::string file;     // the file looked for ("ws/s07.h5")
  std::string missing;  // found without start_ms: why ("its start_time '...' names no zone")
};

// The key --annotator maps a Label Studio annotation without completed_by by (Label Studio's
// own example tasks have none): --annotator none=NAME.
inline constexpr const char* kStudioNoUser = "none";

struct InteropImport {
  // The recording of the labels; when empty, the file's own (ELAN: the tactile:recording
  // property, else the media file's name; Label Studio: the task's data).
  std::string recording;
  // ELAN: tier -> lane id ("ground-truth", "manual:NAME" or just NAME, "segmenter:METHOD",
  // "model:NAME", or "" for the tier's default lane). When not empty, only these tiers are
  // imported, and each must exist.
  std::map<std::string, std::string> tiers;
  // Label Studio: annotator (completed_by: the user's id or email; our name; "none" for an
  // annotation without completed_by) or model_version -> lane id.
  std::map<std::string, std::string> annotators;
  // Label Studio's epoch milliseconds: the Unix time in milliseconds of the recording's first
  // sample (--start-ms), before the recording's own start and the task's first time value.
  std::optional<double> start_ms;
  // The folder of RECORDING.h5 whose start places epoch milliseconds; "" = the label store's
  // (import_label_file fills `clock` from it).
  std::string recordings;
  // The recording's clock by its name; unset: nothing known of any recording.
  std::function<RecordingClock(const std::string& recording)> clock;
};

// What an export to another tool takes beyond the labels.
struct InteropExport {
  // Label Studio: annotator name -> the project member Label Studio's import accepts as
  // completed_by: a user id ("7") or an e-mail ("ana@lab.org", written {"email": ...}). An
  // annotator not mapped gets no completed_by (Label Studio gives it to the user who imports).
  std::map<std::string, std::string> members;
};

// The labels of one recording as an EAF 3.0 document. `vocabulary` is the controlled
// vocabulary of classes (the skin's); classes the labels use beyond it are added. Throws naming
// the label when it spans less than a millisecond, or when the labels hold several recordings.
std::string labels_eaf(const std::vector<Label>& labels,
                       const std::vector<std::string>& vocabulary = {});
// `where` names the document in errors (the file's path).
std::vector<Label> parse_eaf(const std::string& text, const std::string& where,
                             const InteropImport& options = {});

// The labels (any recordings) as Label Studio's JSON export: a list of tasks. Throws naming
// --member when a member is not a user id or e-mail, or names no annotator of the labels, and
// naming the label when a time is past 1e11 s (Label Studio's reader takes that for epoch ms).
std::string labels_label_studio(const std::vector<Label>& labels,
                                const InteropExport& options = {});
// `left_out`, when given, gets one line per kind of result that is not a time span
// ("2 choices from 'quality'"); when the file holds such results and no span at all, it is
// refused instead.
std::vector<Label> parse_label_studio(const std::string& text, const std::string& where,
                                      const InteropImport& options = {},
                                      std::vector<std::string>* left_out = nullptr);

// What a file holds, for choosing before an import: ELAN's top-level tiers (dependent ones
// carry regions, confidences and notes), Label Studio's annotators (completed_by, or our name)
// and model versions. `lane` is where a source's labels go unless mapped.
struct InteropSource {
  std::string name;   // the tier id; the annotator (our name, else the user's id or email,
                      // "none" without completed_by); the prediction's model_version
  std::string lane;   // "ground-truth", "manual:NAME" or NAME, "segmenter:METHOD", "model:NAME";
                      // "" when it must be mapped (an annotation without completed_by)
  size_t labels = 0;  // annotations (ELAN) or time spans (Label Studio)
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

#pragma once
// A label store's labels to and from files, and the agreement of two of its lanes as a report:
// `tactile labels export / import / agreement` and the workbench's File > Export labels,
// Labels > Import labels and Labels > Agreement report call these, so both write the same
// bytes and print the same report.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tactile/labels/agreement.h"
#include "tactile/labels/elan_and_label_studio.h"
#include "tactile/labels/quality.h"
#include "tactile/labelstore/label.h"
#include "tactile/labelstore/label_store.h"

namespace tactile {

// A --source option's value ("manual", "segmenter", "model", "ground-truth"); throws
// tactile::Error naming `option`.
LabelSource label_source_option(const std::string& text, const std::string& option = "--source");

// "DB: labels row 17 field t1: what", one per damaged row a read of `store` met.
std::vector<std::string> damage_lines(const LabelStore& store);

struct LabelExport {
  size_t labels = 0;                 // written
  std::vector<std::string> damaged;  // damaged rows left out (damage_lines)
};

// The labels the filter matches in a label format (labels/label_format.h, by its name: "CSV",
// "JSON", "ELAN", "Label Studio"), written in one rename. `vocabulary` is ELAN's controlled
// vocabulary (the skin's classes). The database must exist (a mistyped path leaves no new
// database behind). A damaged row is left out and named in `damaged`: the caller decides
// whether that fails.
LabelExport export_label_file(const std::string& database, const std::string& out,
                              const std::string& format, const LabelFilter& filter = {},
                              const std::vector<std::string>& vocabulary = {},
                              const InteropExport& interop = {});

struct LabelImport {
  size_t added = 0;
  size_t already = 0;                 // in the store before, left as they were
  std::vector<std::string> left_out;  // what the file holds besides labels, one line per kind
};

// The labels of a file of any label format (label_format_of), checked whole and added in one
// transaction (the store is created when missing), with `options` (recording, tier and
// annotator mappings) for the formats that take them. Label Studio's epoch milliseconds are
// placed by the recording's start, read from RECORDING.h5 in options.recordings (default: the
// store's folder) unless options.clock is given. A label whose recording is in that folder and
// that lies outside it or is shorter than one of its samples refuses the whole file. A label the
// store holds already (same recording, times, region, class, annotator, lane, confidence and
// note) is not added again: importing a file twice changes nothing.
LabelImport import_label_file(const std::string& database, const std::string& file,
                              const InteropImport& options = {});
// Where RECORDING.h5 puts its first sample: on its own clock, and as a Unix time when its
// clock is a Unix clock (first sample at 1e9 s or later) or its metadata start_time is an ISO
// 8601 date-time with a zone ("2020-06-15T19:52:31.951Z", "...+02:00"). found = false when
// there is no such file.
RecordingClock recording_clock(const std::string& folder, const std::string& recording);
// An ISO 8601 date-time with a zone as a Unix time in milliseconds: "2020-06-15T19:52:31.951Z",
// "2020-06-15 21:52:31+02:00"; none for any other text (a local time without zone).
std::optional<double> unix_milliseconds(const std::string& text);
// The tiers (ELAN) or annotators and models (Label Studio) of a file import_label_file reads
// through `options`; format "" for a file of our own CSV or JSON, which has none to choose.
InteropSources interop_sources(const std::string& file);
// "imported N label(s) into DB", as `tactile labels import` prints it, with the labels already
// there ("; 5 already there, not added again") and what was left out ("; left out what is no
// time span: 1 choices from 'quality'").
std::string imported_labels_line(const LabelImport& imported, const std::string& database);

// The spans of the recordings `labels` name whose files are in `folder` as <id>.h5 (the others
// are left out: their labels cannot be checked against them).
std::map<std::string, RecordingSpan> recording_spans(const std::vector<Label>& labels,
                                                     const std::string& folder);

// Two lanes of a store compared (`tactile labels agreement`).
struct AgreementQuery {
  std::string database;
  // "ground-truth", "manual:NAME" (or just NAME), "segmenter:METHOD", "model:NAME".
  std::string a, b;
  std::string recording;   // "" = every recording
  std::string recordings;  // folder of RECORDING.h5 for spans and rates; "" = the database's
  double iou = 0.5;
};

struct AgreementReport {
  AgreementQuery query;
  Agreement agreement;
  std::vector<std::string> damaged;  // damaged rows the lanes leave out (damage_lines)
};

// Each lane's labels (refused naming --a or --b when it has none), each recording's span and
// rate from its file when the folder holds it.
AgreementReport lane_agreement(const AgreementQuery& query,
                               const std::function<void(double)>& step = {});
// The report as the command line prints it: the lanes, kappa, segment F1, the class
// confusion, one line per disagreement.
std::string agreement_text(const AgreementReport& report);
// The same as JSON (`--json`), indented, with a final line break.
std::string agreement_json(const AgreementReport& report);

}  // namespace tactile

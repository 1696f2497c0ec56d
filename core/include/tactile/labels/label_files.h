#pragma once
// A label store's labels to and from files, and the agreement of two of its lanes as a report:
// `tactile labels export / import / agreement` and the workbench's File > Export labels,
// Labels > Import labels and Labels > Agreement report call these, so both write the same
// bytes and print the same report.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/label_store.h"
#include "tactile/labels/agreement.h"
#include "tactile/labels/label_interop.h"

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

// The labels the filter matches, written as RFC 4180 CSV or as JSON ({"labels": [...]}), in
// one rename. The database must exist (a mistyped path leaves no new database behind). A
// damaged row is left out and named in `damaged`: the caller decides whether that fails.
LabelExport export_labels(const std::string& database, const std::string& out, bool json,
                          const LabelFilter& filter = {});

// The formats of other tools (label_interop.h, docs/INTEROP.md).
enum class InteropFormat { kElan, kLabelStudio };
// The labels the filter matches as an ELAN .eaf (one recording: refused naming the recordings
// when the filter matches several) or a Label Studio JSON, in one rename. `vocabulary` is the
// ELAN controlled vocabulary (a skin's classes).
LabelExport export_interop(const std::string& database, const std::string& out,
                           InteropFormat format, const LabelFilter& filter = {},
                           const std::vector<std::string>& vocabulary = {});

// The labels of a CSV or JSON file as export_labels writes them, checked whole and added in
// one transaction (created when missing). Returns how many.
// FILE.eaf (ELAN) and a Label Studio JSON export (a list of tasks) are read as
// label_interop.h says, with `options` (recording, tier and annotator mappings).
size_t import_label_file(const std::string& database, const std::string& file,
                         const InteropImport& options = {});
// The tiers (ELAN) or annotators and models (Label Studio) of a file import_label_file reads
// through `options`; format "" for a file of our own CSV or JSON, which has none to choose.
InteropSources interop_sources(const std::string& file);
// "imported N label(s) into DB", as `tactile labels import` prints it.
std::string imported_labels_line(size_t labels, const std::string& database);

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

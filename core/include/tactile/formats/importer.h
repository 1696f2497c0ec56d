#pragma once
// A recording format of another program, behind one interface (docs/IMPORT.md, "A new format"):
// its name, the extensions it claims or a test of the file's first bytes, the options it takes
// with their help, and the read. One file per format in core/src/formats/, one registry row
// each (builtin_importers.cpp); a program or a test adds its own with register_importer.
//
// The command line's flags (`tactile import --help`) and the workbench's Import dialog are
// made from the options each importer declares, so neither names a format.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/formats/csv_files.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

// One option of a format, as `tactile import` takes it and the Import dialog shows it.
struct ImportOption {
  enum class Kind {
    kText,    // any text (a dataset path, a stream's name)
    kNumber,  // a positive number
    kCount,   // a positive whole number
    kList,    // comma-separated names
    kFile,    // a path (the dialog offers Browse...)
    kSwitch,  // on or off (a flag without a value)
  };
  std::string flag;  // "--dataset"
  Kind kind = Kind::kText;
  std::string help;  // one line for --help: what it is and its default
  std::string hint;  // the dialog's grey text in the empty field; "" = help
  // Only taken (and shown) when this switch is on, or only when it is off: "" = always.
  std::string only_with, never_with;
};

// The option values of one import, by flag, as text as given ("1" for a switch that is on). A
// flag that is absent was not given. The readers below throw tactile::Error naming the flag.
class ImportValues {
 public:
  void set(const std::string& flag, const std::string& text) { values_[flag] = text; }
  void set_switch(const std::string& flag, bool on) {
    if (on)
      values_[flag] = "1";
    else
      values_.erase(flag);
  }
  void erase(const std::string& flag) { values_.erase(flag); }
  bool has(const std::string& flag) const { return values_.count(flag) > 0; }
  const std::map<std::string, std::string>& all() const { return values_; }

  // "" when absent.
  std::string text(const std::string& flag) const;
  bool on(const std::string& flag) const { return has(flag) && text(flag) != "0"; }
  // A positive finite number; none when absent.
  std::optional<double> number(const std::string& flag) const;
  // A positive whole number; none when absent.
  std::optional<int64_t> count(const std::string& flag) const;
  // The comma-separated items, trimmed, empty ones dropped.
  std::vector<std::string> list(const std::string& flag) const;

 private:
  std::map<std::string, std::string> values_;
};

// What an importer read, for the import to write and the preview to show.
struct ImportRead {
  std::vector<ImportedRecording> recordings;
  std::string described;       // "long CSV", ".npz array", "XDF stream 'pressure'"
  std::vector<int64_t> shape;  // the array's shape as stored (array files); empty otherwise
};

class RecordingImporter {
 public:
  virtual ~RecordingImporter() = default;
  // "CSV", "NumPy", "EDF+/BDF+": unique, for help texts and the dialog.
  virtual std::string name() const = 0;
  // Lower-case, with the dot: {".csv", ".txt"}.
  virtual std::vector<std::string> extensions() const = 0;
  // True when the file's first bytes (up to 512) are this format's: a file whose extension no
  // importer claims is read by the first importer that recognises it. Default: never.
  virtual bool recognises(const std::string& first_bytes) const;
  virtual std::vector<ImportOption> options() const = 0;
  // Why this format refuses a flag it does not take, when more can be said than that it is not
  // one of its options ("an EDF file states its own rate"); "" = the general refusal.
  virtual std::string refusal_of(const std::string& flag) const;
  // True when the import makes several recordings, one file each in the --out folder.
  virtual bool writes_several(const ImportValues& values) const;
  // The file read into recordings of the layout. `values` holds only this importer's options,
  // checked against their kinds and conditions. Throws tactile::Error naming the option or the
  // place in the file.
  virtual ImportRead read(const std::string& path, const SkinLayout& layout,
                          const ImportValues& values) const = 0;
};

// Adds an importer, or replaces the one of the same name. Register at start-up, before other
// threads read the list.
void register_importer(std::unique_ptr<RecordingImporter> importer);
// Every importer: the built-in ones first, then in registration order.
std::vector<const RecordingImporter*> importers();
// The importer of a file: by its extension, else by its first bytes (when it can be read);
// nullptr for none.
const RecordingImporter* importer_for(const std::string& path);
// Every extension some importer claims, for a file browser's filter.
std::vector<std::string> import_extensions();
// "CSV (.csv, .txt), NumPy (.npy, .npz), ...": what `tactile import` reads, for help texts
// and refusals.
std::string import_formats_text();

// Each flag once over every importer, in the order first declared, with the names of the
// formats that take it: the command line's flags.
struct SharedImportOption {
  ImportOption option;               // the first declaration
  std::vector<std::string> formats;  // every format that takes it
  std::vector<std::string> helps;    // each format's help, in the order of `formats`
};
std::vector<SharedImportOption> all_import_options();

// The values an importer takes, checked: a flag it does not declare, a value of the wrong kind,
// an option given without its only_with switch or with its never_with one: tactile::Error
// naming the flag and what the format takes instead.
void check_import_values(const RecordingImporter& importer, const ImportValues& values);

// The built-in importers (builtin_importers.cpp), one per format of core/src/formats/.
std::vector<std::unique_ptr<RecordingImporter>> builtin_importers();

}  // namespace tactile
